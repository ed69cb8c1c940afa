#!/usr/bin/env bash
# A sharded run without Slurm (what scripts/slurm/submit does on a cluster): runs N shards one
# after another (or in parallel with PARALLEL=1) and merges them, e.g. to check that N shards
# merged equal one run. A shard that fails stops the script; running it again resumes.
#   scripts/explore-local-shards.sh 4 --quick
set -euo pipefail
N=${1:?usage: explore-local-shards.sh N [explore args...]}
shift
OUT=${ISOGAMI_OUT:-shards}
ISOGAMI=${ISOGAMI:-isogami}
mkdir -p "$OUT"
shards=()
pids=()
for ((i = 0; i < N; i++)); do
  shards+=("$OUT/shard-$i.db")
  if [ "${PARALLEL:-0}" = 1 ]; then
    "$ISOGAMI" explore --shard "$i/$N" --db "$OUT/shard-$i.db" --jobs 1 "$@" &
    pids+=("$!")
  else
    "$ISOGAMI" explore --shard "$i/$N" --db "$OUT/shard-$i.db" "$@"
  fi
done
for pid in "${pids[@]}"; do wait "$pid"; done
# merge proves the N shards complete before it writes anything.
"$ISOGAMI" merge --into "${ISOGAMI_DB:-isogami.db}" "${shards[@]}"
