#!/bin/sh
# Seeds the `templates` target with the default templates, each behind the
# byte that selects it (their order in src/emit/templates.rs's DEFAULTS):
# the fuzzer then mutates real templates instead of growing them from noise.
set -eu
cd "$(dirname "$0")/../.."
mkdir -p fuzz/corpus/templates
i=0
for name in $(grep -o 'templates/[^"]*\.j2' src/emit/templates.rs | sed 's|templates/||'); do
    { printf "\\$(printf %03o "$i")"; cat "templates/$name"; } > "fuzz/corpus/templates/default-$i"
    i=$((i + 1))
done
echo "$i seeds in fuzz/corpus/templates"
