#!/usr/bin/env bash
# Profiles one `isogami explore` run and draws its flame graph, stacks folded into the
# pipeline's stages (scripts/profile/fold.py).
#
#   scripts/profile/flamegraph.sh OUT.svg "TITLE" [EXPLORE ARGS...]
#
# Needs perf (Debian's linux-perf) and inferno (`cargo install inferno`, its binaries on PATH),
# and a release build (`cargo build --release`: line tables are on in the release profile).
# Samples at $PERF_HZ Hz (default 29: a cap-20 run stays under 1 GB of samples) with DWARF call
# stacks, into a temporary folder removed on exit.
set -euo pipefail
if [ $# -lt 2 ]; then
    echo "usage: scripts/profile/flamegraph.sh OUT.svg TITLE [EXPLORE ARGS...]" >&2
    exit 2
fi
out=$1
title=$2
shift 2
hz=${PERF_HZ:-29}
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$root/target/release/isogami
[ -x "$bin" ] || { echo "flamegraph.sh: build first: cargo build --release" >&2; exit 2; }
for tool in perf inferno-collapse-perf inferno-flamegraph; do
    command -v "$tool" > /dev/null || { echo "flamegraph.sh: $tool is not on PATH" >&2; exit 2; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
perf record -F "$hz" -g --call-graph dwarf,32768 -o "$work/perf.data" \
    "$bin" explore --db "$work/explore.db" "$@" > "$work/explore.log"
sed -n '/^stage /,/^$/p' "$work/explore.log"
perf script -i "$work/perf.data" 2> /dev/null | inferno-collapse-perf > "$work/stacks.folded"
python3 "$root/scripts/profile/fold.py" "$work/stacks.folded" > "$work/stages.folded"
inferno-flamegraph --title "$title" \
    --subtitle "perf at $hz Hz, DWARF stacks; rayon and std frames folded away; width = CPU time summed over threads" \
    --minwidth 0.2 --width 1400 --colors rust "$work/stages.folded" > "$work/flamegraph.svg"
mv "$work/flamegraph.svg" "$out"
awk '{n = $NF; sub(/ [0-9]+$/, ""); split($0, f, ";"); s[f[1]] += n; t += n}
     END {for (k in s) printf "%5.1f %%  %s\n", 100 * s[k] / t, k}' "$work/stages.folded" | sort -rn
