#!/usr/bin/env bash
# The overhead of rendering through a one-node Slurm cluster against a plain render
# (docs/distributed.md, "Overhead on one node"): the same frame rendered once by `filmback render`
# with every core, and once by `filmback submit --tiles TILES` plus its merge, timed from the
# submit to the merge job's end, and that time split into its pieces. Appends a row to OUT.csv.
#
# The cluster is started, then given one trivial job, before anything is timed: a fresh slurmctld
# makes its first scheduling pass about 2 s after it starts (shared/notes/slurm.md, section 1),
# which a long-running cluster never pays.
#
# Pieces (each task's log has millisecond timestamps: core/cmd/slurm/*.sh):
#   submit_s      `filmback submit` itself: the tile plan (plan_s, its pre-pass) and the sbatch calls
#   queue_s       the submit's end to the first task's start: the scheduler's first pass
#   tiles_s       the first task's start to the last task's end: the tasks in waves of
#                 (cores / CPUS_PER_TASK), each paying its process start, scene load and BVH
#   merge_wait_s  the last task's end to the merge's start: the dependency's release
#   merge_s       the merge task: `filmback merge` of the parts into the image
#   seen_s        the merge's end to this script seeing it (a 0.5 s squeue poll)
#
# Usage: [TILES=8] [CPUS_PER_TASK=1] [TILE_PLAN=auto|none|FILE] \
#          measure_overhead.sh FILMBACK SCENE OUT.csv [render options]
# (run on an idle machine: the row records the load average before)
set -euo pipefail
FILMBACK=$(realpath "$1")
SCENE=$(realpath "$2")
CSV=$3
shift 3
OPTIONS=("$@")
TILES=${TILES:-8}
CPUS_PER_TASK=${CPUS_PER_TASK:-1}
TILE_PLAN=${TILE_PLAN:-auto}
HERE=$(cd "$(dirname "$0")" && pwd)
W=$(mktemp -d "${TMPDIR:-/tmp}/filmback-overhead.XXXXXX")
source "$HERE/one_node_cluster.sh"
trap 'cluster_stop; rm -rf "$W"' EXIT
now() { date +%s.%N; }
seconds() { date -d "$1" +%s.%N; }  # an ISO time from a task's log
minus() { printf %.2f "$(echo "$1 - $2" | bc)"; }

cluster_start "$W/cluster"
warm=$(sbatch --parsable -o /dev/null --wrap true)
[ "$(job_final_state "$warm" $(($(date +%s) + 60)))" = COMPLETED ] || {
  echo "the warm-up job did not complete" >&2
  exit 1
}

load_before=$(cut -d' ' -f1 /proc/loadavg)
t=$(now)
/usr/bin/time -f '%U %S' -o "$W/plain.cpu" "$FILMBACK" render "$SCENE" "${OPTIONS[@]}" \
  -o "$W/plain.exr" >"$W/plain.log" 2>&1
plain_s=$(echo "$(now) - $t" | bc)
plain_render_s=$(sed -n 's/.* in \([0-9.]*\) s:.*/\1/p' "$W/plain.log")
plain_cpu_s=$(awk '{print $1 + $2}' "$W/plain.cpu")

t=$(now)
"$FILMBACK" submit "$SCENE" --tiles "$TILES" -o "$W/cluster.exr" --tile-plan "$TILE_PLAN" \
  --cpus-per-task "$CPUS_PER_TASK" "${OPTIONS[@]}" >"$W/submit.txt" 2>"$W/submit.err"
submitted=$(now)
merge=$(sed -n 's/^merge array \([0-9]*\):.*/\1/p' "$W/submit.txt")
state=$(job_final_state "$merge" $(($(date +%s) + 3600)))
seen=$(now)
[ "$state" = COMPLETED ] || { echo "the merge ended $state" >&2; exit 1; }
cluster_s=$(echo "$seen - $t" | bc)
plan_s=$(sed -n 's/^submit: tile plan made in \([0-9.e-]*\) s:.*/\1/p' "$W/submit.err")

LOGS=$W/cluster.filmback-job/logs
starts=$(for f in "$LOGS"/t*.log; do seconds "$(grep -m1 ': try 1 of' "$f" | cut -d' ' -f1)"; done | sort -n)
ends=$(for f in "$LOGS"/t*.log; do seconds "$(grep -m1 ': done$' "$f" | cut -d' ' -f1)"; done | sort -n)
first_start=$(head -1 <<<"$starts")
last_end=$(tail -1 <<<"$ends")
merge_start=$(seconds "$(head -1 "$LOGS/merge.log" | cut -d' ' -f1)")
merge_end=$(seconds "$(grep -m1 'filmback merge exit status' "$LOGS/merge.log" | cut -d' ' -f1)")
task_s=$(sed -n 's/.* in \([0-9.]*\) s:.*/\1/p' "$LOGS"/t*.log | paste -sd' ')
# Processor seconds of the tasks' renders (bash's `times` in each task's log: the line after the
# script's own), summed.
tasks_cpu_s=$(for f in "$LOGS"/t*.log; do
  grep -A2 '^processor time' "$f" | tail -1; done |
  awk '{ for (i = 1; i <= 2; ++i) { split($i, p, /[ms]/); s += 60 * p[1] + p[2] } } END { print s }')
overhead=$(echo "scale=1; 100 * ($cluster_s - $plain_s) / $plain_s" | bc)
header="date_utc,machine,cores,load_before,tiles,cpus_per_task,tile_plan,options,plain_s,plain_render_s,cluster_s,overhead_percent,submit_s,plan_s,queue_s,tiles_s,merge_wait_s,merge_s,seen_s,task_render_s,plain_cpu_s,tasks_cpu_s"
[ -f "$CSV" ] || echo "$header" >"$CSV"
echo "$(date -u +%FT%TZ),$(uname -n),$(nproc),$load_before,$TILES,$CPUS_PER_TASK,$TILE_PLAN,${OPTIONS[*]},$(printf %.2f "$plain_s"),$plain_render_s,$(printf %.2f "$cluster_s"),$overhead,$(minus "$submitted" "$t"),$plan_s,$(minus "$first_start" "$submitted"),$(minus "$last_end" "$first_start"),$(minus "$merge_start" "$last_end"),$(minus "$merge_end" "$merge_start"),$(minus "$seen" "$merge_end"),$task_s,$plain_cpu_s,$tasks_cpu_s" >>"$CSV"
tail -n 1 "$CSV"
