# shellcheck shell=bash
# Shared by the isogami Slurm scripts (sourced, not run): logging, the run's final status, and
# submitting its jobs. Every job gets the run file OUT/run.env (written by `submit`: N, OUT,
# DB, ISOGAMI, RETRIES, SCRIPTS, RUN_ENV, EXPLORE_ARGS, SHARD_SBATCH, MERGE_SBATCH) as its
# first argument; it names this folder (SCRIPTS), so jobs find these helpers although sbatch
# runs a copy of the job script.

# One timestamped line to stderr (the job's log) and to OUT/run.log (the whole run's log).
log() {
  local line
  line="$(date '+%F %T') $*"
  printf '%s\n' "$line" >&2
  printf '%s\n' "$line" >>"$OUT/run.log"
}

# The run's outcome in OUT/STATUS ("merged …" or "failed: …"), written atomically; `submit
# --wait` waits for this file.
set_status() {
  printf '%s\n' "$*" >"$OUT/STATUS.tmp.$$"
  mv -f "$OUT/STATUS.tmp.$$" "$OUT/STATUS"
}

# sbatch --parsable with the given arguments; prints the job id (without a cluster name).
submit_job() {
  local out
  out=$(sbatch --parsable "$@") || return 1
  printf '%s\n' "${out%%;*}"
}

# Submits shards ($1: an sbatch array list such as 0-3 or 2,5) and a merge job that runs after
# they have all ended, however they ended ($2: the merge attempt). Records both job ids in
# OUT/jobs and prints "ARRAY_ID MERGE_ID".
submit_round() {
  local list=$1 attempt=$2 array merge
  array=$(submit_job --array="$list" "${SHARD_SBATCH[@]}" "$SCRIPTS/shard.sbatch" "$RUN_ENV") ||
    return 1
  merge=$(submit_job --dependency="afterany:$array" "${MERGE_SBATCH[@]}" \
    "$SCRIPTS/merge.sbatch" "$RUN_ENV" "$attempt") || {
    scancel "$array" 2>/dev/null || true
    return 1
  }
  printf '%s %s\n' "$array" "$merge" >>"$OUT/jobs"
  printf '%s %s\n' "$array" "$merge"
}
