#!/usr/bin/env bash
# The overhead of rendering through a one-node Slurm cluster against a plain render
# (docs/distributed.md, "Overhead on one node"): the same frame rendered once by `filmback render`
# with every core, and once by `filmback submit --tiles 8` (one core per task) plus its merge,
# timed from the submit to the merge job's end. Appends a row to OUT.csv.
# Until `render --tile` and `merge` are in the build, each task renders the whole frame at 1/8 of
# the samples through tests/slurm/standin_filmback.sh: a tile's samples and a tile's fixed costs
# (process start, scene load, BVH build), which is what the overhead is made of ("proxy" rows).
# Usage: [TILE_PLAN=auto|none|FILE] measure_overhead.sh FILMBACK SCENE OUT.csv [render options]
# (run on an idle machine; TILE_PLAN is submit's --tile-plan, default auto)
set -euo pipefail
FILMBACK=$(realpath "$1")
SCENE=$(realpath "$2")
CSV=$3
shift 3
OPTIONS=("$@")
HERE=$(cd "$(dirname "$0")" && pwd)
W=$(mktemp -d "${TMPDIR:-/tmp}/filmback-overhead.XXXXXX")
source "$HERE/one_node_cluster.sh"
trap 'cluster_stop; rm -rf "$W"' EXIT
now() { date +%s.%N; }

load_before=$(cut -d' ' -f1 /proc/loadavg)
t=$(now)
/usr/bin/time -f '%U %S' -o "$W/plain.cpu" "$FILMBACK" render "$SCENE" "${OPTIONS[@]}" \
  -o "$W/plain.exr" >"$W/plain.log" 2>&1
plain_s=$(echo "$(now) - $t" | bc)
plain_render_s=$(sed -n 's/.* in \([0-9.]*\) s:.*/\1/p' "$W/plain.log")
plain_cpu_s=$(awk '{print $1 + $2}' "$W/plain.cpu")

TASK_FILMBACK=$FILMBACK mode=tiles
if ! "$FILMBACK" --help | grep -q '^  merge '; then
  export FILMBACK_REAL=$FILMBACK STANDIN_SPP_DIVISOR=8
  TASK_FILMBACK=$HERE/standin_filmback.sh mode=proxy
fi
cluster_start "$W/cluster"
t=$(now)
"$FILMBACK" submit "$SCENE" --tiles 8 -o "$W/cluster.exr" --filmback "$TASK_FILMBACK" \
  --tile-plan "${TILE_PLAN:-auto}" --cpus-per-task 1 "${OPTIONS[@]}" >"$W/submit.txt"
merge=$(sed -n 's/^merge array \([0-9]*\):.*/\1/p' "$W/submit.txt")
state=$(job_final_state "$merge" $(($(date +%s) + 3600)))
cluster_s=$(echo "$(now) - $t" | bc)
[ "$state" = COMPLETED ] || { echo "the merge ended $state" >&2; exit 1; }
task_s=$(sed -n 's/.* in \([0-9.]*\) s:.*/\1/p' "$W"/cluster.filmback-job/logs/t*.log | paste -sd' ')
# Processor seconds of the tasks' renders (bash's `times` in each task's log: the line after the
# script's own), summed.
tasks_cpu_s=$(for f in "$W"/cluster.filmback-job/logs/t*.log; do
  grep -A2 '^processor time' "$f" | tail -1; done |
  awk '{ for (i = 1; i <= 2; ++i) { split($i, p, /[ms]/); s += 60 * p[1] + p[2] } } END { print s }')
# Each tile task's wall time in Slurm (StartTime to EndTime, whole seconds; jobcomp/filetxt).
task_wall_s=$(grep -F ':tiles' -v "$W/cluster/log/jobcomp.txt" | grep -o 'Name=fb:[^ ]*:t[0-9]*/8 .*' |
  sed -n 's/.*StartTime=\([^ ]*\) EndTime=\([^ ]*\).*/\1 \2/p' |
  while read -r start end; do echo $(($(date -d "$end" +%s) - $(date -d "$start" +%s))); done | paste -sd' ')
overhead=$(echo "scale=1; 100 * ($cluster_s - $plain_s) / $plain_s" | bc)
[ -f "$CSV" ] || echo "date_utc,machine,cores,load_before,mode,options,plain_s,plain_render_s,cluster_s,overhead_percent,task_render_s,task_wall_s,plain_cpu_s,tasks_cpu_s" >"$CSV"
echo "$(date -u +%FT%TZ),$(uname -n),$(nproc),$load_before,$mode,${OPTIONS[*]},$(printf %.2f "$plain_s"),$plain_render_s,$(printf %.2f "$cluster_s"),$overhead,$task_s,$task_wall_s,$plain_cpu_s,$tasks_cpu_s" >>"$CSV"
tail -n 1 "$CSV"
