#!/usr/bin/env bash
# What Slurm's own cadence costs on the one-node test cluster (docs/distributed.md, "Overhead on
# one node"): 8 array tasks that do nothing and a merge job after them (afterok), timed from the
# submit, three times for each SchedulerParameters value given (applied by scontrol reconfigure).
# The cluster is warm when timing starts: its first scheduling pass (about 2 s after slurmctld
# starts) is not counted.
# Usage: scheduler_cadence.sh "batch_sched_delay=0,bf_interval=5,sched_interval=5" [MORE...]
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
W=$(mktemp -d "${TMPDIR:-/tmp}/filmback-cadence.XXXXXX")
source "$HERE/one_node_cluster.sh"
trap 'cluster_stop; rm -rf "$W"' EXIT
cluster_start "$W/cluster"
now() { date +%s.%N; }
since() { printf %.2f "$(echo "$1 - $2" | bc)"; }
printf '#!/bin/bash\ndate +%%s.%%N > "$1/start.$SLURM_ARRAY_TASK_ID"\n' >"$W/tile.sh"
printf '#!/bin/bash\ndate +%%s.%%N > "$1/merge"\n' >"$W/merge.sh"
for params in "$@"; do
  sed -i "s/^SchedulerParameters=.*/SchedulerParameters=$params/" "$SLURM_CONF"
  scontrol reconfigure
  sleep 3
  for trial in 1 2 3; do
    rm -f "$W"/start.* "$W/merge"
    t=$(now)
    tiles=$(sbatch --parsable --array=0-7 -o /dev/null "$W/tile.sh" "$W")
    merge=$(sbatch --parsable -o /dev/null --dependency=afterok:"$tiles" --kill-on-invalid-dep=yes \
      "$W/merge.sh" "$W")
    state=$(job_final_state "$merge" $(($(date +%s) + 120)))
    seen=$(now)
    first=$(sort -n "$W"/start.* | head -1)
    last=$(sort -n "$W"/start.* | tail -1)
    echo "$params, trial $trial ($state, load $(cut -d' ' -f1 /proc/loadavg)): from the submit," \
      "first task $(since "$first" "$t") s, last task $(since "$last" "$t") s," \
      "merge $(since "$(cat "$W/merge")" "$t") s, seen ended $(since "$seen" "$t") s"
  done
done
