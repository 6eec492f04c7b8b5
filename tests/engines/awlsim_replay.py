"""Replays a recorded input trace through an AWL source in awlsim, scan by scan.

Usage: awlsim_replay.py FILE.awl en|de SCAN_MS INPUTS OUTPUTS [MEMORY] < trace
INPUTS and OUTPUTS are comma-separated byte.bit addresses (I and Q areas);
MEMORY, if given, byte.bit addresses of memory bits (the step flags) printed
after the outputs and a space, as an online view of them would show.
Each line of the trace holds one character 0/1 per input; for each line one
OB1 cycle runs at a virtual time of (line number x SCAN_MS) and one line of
0/1 per output is printed. Time is virtual: awlsim's clock is replaced, so
timers run exactly as long as the scans say, however fast Python is.
"""
import sys

from awlsim_loader.common import *  # noqa: F401,F403 (awlsim's own way to load itself)
from awlsim_loader.core import *  # noqa: F401,F403
from awlsim_loader.awlcompiler import *  # noqa: F401,F403


def bits(text):
    if not text:
        return []
    return [tuple(int(n) for n in a.split(".")) for a in text.split(",")]


def main():
    path, mnemonics, scan_ms, inputs, outputs = sys.argv[1:6]
    memory = bits(sys.argv[6]) if len(sys.argv) > 6 else []
    scan = int(scan_ms) / 1000.0
    inputs, outputs = bits(inputs), bits(outputs)
    project = Project.fromProjectOrRawAwlFile(path)
    sim = AwlSim()
    sim.reset()
    cpu = sim.getCPU()
    cpu.getConf().setConfiguredMnemonics(
        {"en": S7CPUConfig.MNEMONICS_EN, "de": S7CPUConfig.MNEMONICS_DE}[mnemonics])
    for source in project.getAwlSources():
        parser = AwlParser()
        parser.parseSource(source)
        sim.load(parser.getParseTree())
    sim.build()
    # Virtual time: the CPU's clock is whatever the trace says.
    cpu.updateTimestamp = lambda *args, **kwargs: None
    base = 1000.0
    cpu.now = base
    sim.startup()
    out = sys.stdout
    in_bytes = sorted({b for b, _ in inputs})
    out_bytes = sorted({b for b, _ in outputs})
    for n, line in enumerate(sys.stdin):
        line = line.strip()
        image = {b: 0 for b in in_bytes}
        for (byte, bit), ch in zip(inputs, line):
            if ch == "1":
                image[byte] |= 1 << bit
        for byte, value in image.items():
            cpu.storeInputByte(byte, value)
        # A clock a billionth fast: a timer whose time has come exactly is
        # seen as elapsed, not lost to floating-point rounding.
        cpu.now = base + n * scan * (1.0 + 1e-9)
        sim.runCycle()
        q = {b: cpu.fetchOutputByte(b) for b in out_bytes}
        out.write("".join("1" if (q[b] >> bit) & 1 else "0" for b, bit in outputs))
        if memory:
            out.write(" ")
            flags = cpu.flags.getRawDataBytes()
            out.write("".join("1" if (flags[b] >> bit) & 1 else "0" for b, bit in memory))
        out.write("\n")


if __name__ == "__main__":
    main()
