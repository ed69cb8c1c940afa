#!/usr/bin/env bash
# The Slurm array job's logic without Slurm: runs N shards one after another (or in parallel
# with PARALLEL=1) and merges them, e.g. to check that N shards merged equal one run.
#   scripts/explore-local-shards.sh 4 --quick
set -euo pipefail
N=${1:?usage: explore-local-shards.sh N [explore args...]}
shift
OUT=${ISOGAMI_OUT:-shards}
ISOGAMI=${ISOGAMI:-isogami}
mkdir -p "$OUT"
for ((i = 0; i < N; i++)); do
  if [ "${PARALLEL:-0}" = 1 ]; then
    "$ISOGAMI" explore --shard "$i/$N" --db "$OUT/shard-$i.db" --jobs 1 "$@" &
  else
    "$ISOGAMI" explore --shard "$i/$N" --db "$OUT/shard-$i.db" "$@"
  fi
done
wait
"$ISOGAMI" merge --into "${ISOGAMI_DB:-isogami.db}" "$OUT"/shard-*.db
