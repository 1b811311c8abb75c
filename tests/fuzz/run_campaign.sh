#!/usr/bin/env bash
# The long fuzz campaign (make fuzz): runs each libFuzzer target of BIN_DIR for RUNS cases in
# all, split over JOBS parallel jobs that share one corpus per target, and prints the cases
# executed (summed over the jobs' final stats), wall and CPU time per target. Exits 1 on the
# first target that broke a rule (libFuzzer leaves the reproducing input in BIN_DIR/crash-*).
#
#   tests/fuzz/run_campaign.sh BIN_DIR RUNS JOBS TARGET...
#
# FUZZ_MAX_TIME (seconds, optional) caps each job's time; a target it cuts short is reported
# with the cases it ran, never as complete.
set -euo pipefail
bin=$1 runs=$2 jobs=$3
shift 3
per_job=$(((runs + jobs - 1) / jobs))
printf '%-14s %12s %10s %10s %s\n' target cases "wall s" "job s" result
for t in "$@"; do
  work="$bin/run_$t"
  rm -rf "$work" && mkdir -p "$work/corpus"
  # One job keeps a fixed seed (reproducible); several take libFuzzer's per-job seeds, or
  # they would all repeat the same mutations.
  seed=()
  [ "$jobs" -eq 1 ] && seed=(-seed=1)
  limit=()
  [ -n "${FUZZ_MAX_TIME:-}" ] && limit=(-max_total_time="$FUZZ_MAX_TIME")
  start=$(date +%s.%N)
  status=0
  (cd "$work" && "$(realpath "../fuzz_$t")" -runs="$per_job" -jobs="$jobs" -workers="$jobs" \
      -max_len=2048 -print_final_stats=1 "${seed[@]}" "${limit[@]}" -artifact_prefix="$(realpath ..)/" \
      corpus > driver.log 2>&1) || status=$?
  wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {print b - a}')
  if [ "$jobs" -eq 1 ]; then logs=("$work/driver.log"); else logs=("$work"/fuzz-*.log); fi
  cases=$(cat "${logs[@]}" | awk '/stat::number_of_executed_units/ {s += $2} END {print s + 0}')
  # each job is one single-threaded process: the sum of their run times is the CPU time spent
  cpu=$(cat "${logs[@]}" | awk '/^Done [0-9]+ runs in/ {s += $5} END {print s + 0}')
  failed=$(grep -h "^fuzz: \|SUMMARY: \|ERROR: libFuzzer" "${logs[@]}" | head -1 || true)
  if [ "$status" -ne 0 ] || [ -n "$failed" ]; then
    printf '%-14s %12s %10.0f %10.0f FAILED: %s\n' "$t" "$cases" "$wall" "$cpu" "${failed:-exit $status}"
    exit 1
  fi
  result="nothing found"
  [ "$cases" -lt "$runs" ] && result="nothing found, but cut short by FUZZ_MAX_TIME"
  printf '%-14s %12s %10.0f %10.0f %s\n' "$t" "$cases" "$wall" "$cpu" "$result"
done
