#!/usr/bin/env bash
# Runs every libFuzzer harness of a FILMBACK_FUZZ build for a bounded time, two at a time, each on a
# fresh working corpus seeded from tests/fuzz/corpus/<harness>/ (which is not changed). Fails on any
# finding: a crash, a sanitizer report, an uncaught exception, a leak, an input that runs longer
# than 10 s or allocates more than 2 GB. Prints each harness's executions, coverage and corpus.
# Usage: tests/fuzz/run_fuzzers.sh BUILD_DIR SECONDS_EACH
set -uo pipefail
build=$(cd "$1" && pwd)
seconds=$2
source_dir=$(cd "$(dirname "$0")" && pwd)
harnesses=(gltf pov params descriptor)
work=$build/fuzz-run
rm -rf "$work"

run() {
  local h=$1
  mkdir -p "$work/$h/corpus" "$work/$h/findings"
  "$build/bin/filmback_fuzz_$h" "$work/$h/corpus" "$source_dir/corpus/$h" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$work/$h/findings/" >"$work/$h/log" 2>&1
}

status=0
for ((i = 0; i < ${#harnesses[@]}; i += 2)); do
  pids=()
  for h in "${harnesses[@]:i:2}"; do
    run "$h" &
    pids+=($!)
  done
  for pid in "${pids[@]}"; do wait "$pid" || status=1; done
done

for h in "${harnesses[@]}"; do
  log=$work/$h/log
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")
  corpus=$(ls "$work/$h/corpus" | wc -l)
  findings=$(ls "$work/$h/findings" | wc -l)
  echo "fuzz $h: ${executions:-?} executions in ${seconds} s, cov ${cov:-?}, ft ${ft:-?}, corpus +${corpus} inputs, ${findings} findings"
  if [ "$findings" -gt 0 ] || ! grep -q '^stat::number_of_executed_units' "$log"; then
    status=1
    echo "fuzz $h: FAILED; the end of its log ($log):"
    tail -40 "$log"
    ls -l "$work/$h/findings"
  fi
done
exit $status
