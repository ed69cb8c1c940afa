#!/usr/bin/env bash
# Runs the whole isogami exploration on a Slurm cluster as an array job of N shards, then
# merges the shard databases into one.
#
#   sbatch --array=0-15 scripts/explore-slurm.sh          # 16 shards (N from the array)
#   ISOGAMI_ARGS="--threshold 0.2" sbatch --array=0-63 scripts/explore-slurm.sh
#
# Each array task explores a disjoint, deterministic slice of the work units (family x
# supercell) into shards/shard-I.db; a task that is killed or preempted can simply be
# resubmitted: committed units are skipped. The last task to finish submits the merge (a
# dependent job), which writes isogami.db. Results do not depend on N.
#SBATCH --job-name=isogami-explore
#SBATCH --cpus-per-task=4
#SBATCH --time=02:00:00
#SBATCH --output=shards/%x-%a.log
set -euo pipefail

ISOGAMI=${ISOGAMI:-isogami}
OUT=${ISOGAMI_OUT:-shards}
N=${SLURM_ARRAY_TASK_COUNT:?run this with sbatch --array=0-(N-1)}
I=${SLURM_ARRAY_TASK_ID:?run this with sbatch --array=0-(N-1)}
mkdir -p "$OUT"

# shellcheck disable=SC2086
"$ISOGAMI" explore --shard "$I/$N" --jobs "${SLURM_CPUS_PER_TASK:-1}" \
  --db "$OUT/shard-$I.db" ${ISOGAMI_ARGS:-}
touch "$OUT/done-$I"

# The last shard to finish merges everything.
if [ "$(find "$OUT" -maxdepth 1 -name 'done-*' | wc -l)" -eq "$N" ]; then
  if mkdir "$OUT/merge.lock" 2>/dev/null; then
    "$ISOGAMI" merge --into "${ISOGAMI_DB:-isogami.db}" "$OUT"/shard-*.db
    "$ISOGAMI" db stats --db "${ISOGAMI_DB:-isogami.db}"
  fi
fi
