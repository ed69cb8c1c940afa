# shellcheck shell=bash
# Shared by the isogami Slurm scripts (sourced, not run): logging, the run's final status, and
# submitting its jobs. Every job gets the run file OUT/run.env (written by `submit`: N, OUT,
# DB, ISOGAMI, RETRIES, SCRIPTS, RUN_ENV, EXPLORE_ARGS, SHARD_SBATCH, MERGE_SBATCH, SHARD_TIME,
# THROTTLE) as its
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

# A Slurm time limit (M, M:S, H:M:S, D-H, D-H:M, D-H:M:S) in seconds; fails on anything else
# (UNLIMITED included: a limit that can be raised is needed).
time_seconds() {
  local t=$1 d=0 h=0 m=0 s=0 rest
  local -a f
  if [[ $t =~ ^([0-9]+)-(.+)$ ]]; then
    d=${BASH_REMATCH[1]}
    rest=${BASH_REMATCH[2]}
    [[ $rest =~ ^[0-9]+(:[0-9]+){0,2}$ ]] || return 1
    IFS=: read -ra f <<<"$rest"
    h=${f[0]}
    m=${f[1]:-0}
    s=${f[2]:-0}
  else
    [[ $t =~ ^[0-9]+(:[0-9]+){0,2}$ ]] || return 1
    IFS=: read -ra f <<<"$t"
    case ${#f[@]} in
      1) m=${f[0]} ;;
      2) m=${f[0]}; s=${f[1]} ;;
      3) h=${f[0]}; m=${f[1]}; s=${f[2]} ;;
    esac
  fi
  local total=$(((10#$d * 24 + 10#$h) * 3600 + 10#$m * 60 + 10#$s))
  ((total > 0)) || return 1
  printf '%s\n' "$total"
}

# Seconds as a Slurm time limit: D-HH:MM:SS, or HH:MM:SS under a day.
time_text() {
  local t=$1
  if ((t >= 86400)); then
    printf '%d-%02d:%02d:%02d\n' $((t / 86400)) $((t % 86400 / 3600)) $((t % 3600 / 60)) $((t % 60))
  else
    printf '%02d:%02d:%02d\n' $((t / 3600)) $((t % 3600 / 60)) $((t % 60))
  fi
}

# Twice the time limit $1, as a Slurm time limit: the next round's limit after a shard task
# reached its limit.
double_time() {
  local s
  s=$(time_seconds "$1") || return 1
  time_text $((2 * s))
}

# Whether the run has been cancelled (scripts/slurm/cancel): no job may start work or submit.
cancelled() {
  [[ -e $OUT/CANCELLED ]]
}

# Submits shards ($1: an sbatch array list such as 0-3 or 2,5; the run's THROTTLE, when set,
# caps how many run at once) with the time limit $3 (default SHARD_TIME), and a merge job that
# runs after they have all ended, however they ended ($2: the merge attempt; the merge job is
# told the shards' limit). Records both job ids in OUT/jobs and prints "ARRAY_ID MERGE_ID".
# Refused once the run is cancelled; a cancel that comes while this submits finds the ids in
# OUT/jobs, and jobs submitted after the cancel are cancelled here.
submit_round() {
  local list=$1 attempt=$2 limit=${3:-$SHARD_TIME} array merge
  cancelled && return 1
  [[ -n ${THROTTLE:-} ]] && list+="%$THROTTLE"
  array=$(submit_job --array="$list" --time="$limit" "${SHARD_SBATCH[@]}" \
    "$SCRIPTS/shard.sbatch" "$RUN_ENV") || return 1
  merge=$(submit_job --dependency="afterany:$array" "${MERGE_SBATCH[@]}" \
    "$SCRIPTS/merge.sbatch" "$RUN_ENV" "$attempt" "$limit") || {
    scancel "$array" 2>/dev/null || true
    return 1
  }
  printf '%s %s\n' "$array" "$merge" >>"$OUT/jobs"
  if cancelled; then
    scancel "$array" "$merge" 2>/dev/null || true
    return 1
  fi
  printf '%s %s\n' "$array" "$merge"
}
