#!/usr/bin/env python3
"""beremiz_editor_load.py PLCOPEN2ST PLC.xml

Loads a Beremiz project's plc.xml with Beremiz's own project model
(PLCControler.OpenXMLFile, as the IDE opens a project), then, for every
POU with a graphical body, asks the model for the instances exactly as the
SFC and LD editors do when they open the POU
(GetEditedElementInstancesInfos, read by editors/Viewer.py), and checks
what the editors' loader would do with them, without a window: every
element has an integer size > 0 and position; every wire's source
(refLocalId) is an element of the POU; its first point lies on its own
input connector and its last point on the connector the editor connects it
to (Viewer.CreateWires asks the source for the connector nearest to the
last point among its input, outputs and a step's action connector, or the
named output of a block): that connector must be one of the source's
outputs (or a step's action connector), at distance 0, so no leg is
connected wrongly.
Prints one line per POU: `pou NAME TYPE: N step, M transition, ...` and
`wire-errors K`; exit 1 if the project does not load or a check fails
(each failure on its own line).
"""
import importlib.util
import os
import sys
from collections import Counter


def load_controller(plcopen2st):
    spec = importlib.util.spec_from_file_location("plcopen2st", plcopen2st)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.PLCControler()


def absolute(instance, connector):
    return (instance.x + connector.position.x, instance.y + connector.position.y)


def check_link(pou, instances, instance, connector, link, errors):
    source = instances.get(link.refLocalId)
    where = "%s: element %d's wire from %s" % (pou, instance.id, link.refLocalId)
    if source is None:
        errors.append(where + ": no such element")
        return
    points = [(p.x, p.y) for p in link.points]
    if len(points) < 2:
        errors.append(where + ": fewer than two points")
        return
    if points[0] != absolute(instance, connector):
        errors.append("%s: first point %s is not on its input %s" %
                      (where, points[0], absolute(instance, connector)))
    # The connectors the editor chooses among (a step's action connector
    # too); the chosen one must be a source's output, not its input.
    outputs = list(source.outputs)
    action = getattr(source.specific_values, "action", None) if source.type == "step" else None
    if action is not None:
        outputs.append(action)
    candidates = outputs + list(source.inputs)
    if link.formalParameter:
        candidates = [o for o in source.outputs if o.name == link.formalParameter]
    if not candidates:
        errors.append("%s: the source has no output %s" % (where, link.formalParameter or ""))
        return
    nearest = min(candidates, key=lambda o: (absolute(source, o)[0] - points[-1][0]) ** 2 +
                  (absolute(source, o)[1] - points[-1][1]) ** 2)
    if absolute(source, nearest) != points[-1] or not any(nearest is o for o in outputs):
        errors.append("%s: last point %s is not on an output of %s (the editor connects %s)" %
                      (where, points[-1], source.type, absolute(source, nearest)))


def check_pou(ctrl, name, errors):
    tagname = "P::" + name
    instances = ctrl.GetEditedElementInstancesInfos(tagname)
    counts = Counter()
    for instance in instances.values():
        counts[instance.type] += 1
        for value in (instance.x, instance.y, instance.width, instance.height):
            if not isinstance(value, int):
                errors.append("%s: element %d has a size or position %r" % (name, instance.id, value))
        if instance.width <= 0 or instance.height <= 0:
            errors.append("%s: element %d is %dx%d" % (name, instance.id, instance.width, instance.height))
        for connector in instance.inputs:
            for link in connector.links:
                check_link(name, instances, instance, connector, link, errors)
    return counts


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 2
    ctrl = load_controller(argv[0])
    error = ctrl.OpenXMLFile(os.path.abspath(argv[1]))
    if ctrl.Project is None or error:
        print("cannot load %s: %s" % (argv[1], error))
        return 1
    errors = []
    for pou in ctrl.Project.getpous():
        language = pou.getbodyType()
        if language not in ("SFC", "LD", "FBD"):
            print("pou %s %s" % (pou.getname(), language))
            continue
        counts = check_pou(ctrl, pou.getname(), errors)
        listed = ", ".join("%d %s" % (n, t) for t, n in sorted(counts.items()))
        print("pou %s %s: %s" % (pou.getname(), language, listed))
    for error in errors:
        print("error: " + error)
    print("wire-errors %d" % len(errors))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
