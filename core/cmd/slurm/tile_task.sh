#!/bin/bash
# One tile of one frame of a `filmback submit` job (docs/distributed.md), run by Slurm as an
# element of a tile array: `sbatch --array=0-(COUNT-1) tile_task.sh JOB_DIR OFFSET`. It renders
# its part (resuming from the part's checkpoint when an earlier try left one) and, when the render
# fails, requeues itself while retries remain: an array element that ends FAILED poisons the merge
# job's `afterok` dependency for good, even after a successful requeue of that element
# (shared/notes/slurm.md, section 3, option 3).
set -uo pipefail
job_dir=$1
index=$(($2 + SLURM_ARRAY_TASK_ID))
source "$job_dir/job.env"                                   # FILMBACK, RETRIES, THREADS_FROM_SLURM
source "$(printf '%s/tasks/%06d.sh' "$job_dir" "$index")"  # name, part, checkpoint, log, render_args
exec >>"$log" 2>&1
try=${SLURM_RESTART_COUNT:-0}
# Array elements share the array's name until they run: a running task names itself. It names
# itself as ARRAY_INDEX: the element that holds the array's own job id would rename them all. In
# the background: the render need not wait for slurmctld's answer (a busy controller takes
# seconds), and a name not set before the task ends is no loss.
scontrol update JobId="${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}" JobName="$name" \
  Comment="filmback ${name#fb:} try $((try + 1))" >/dev/null 2>&1 &
echo "$(date -u +%FT%T.%3NZ) $name: try $((try + 1)) of $((RETRIES + 1)), job ${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID} ($SLURM_JOB_ID) on $(hostname)"
if [ -s "$part" ]; then
  echo "$part exists (an earlier try or submission wrote it): nothing to render"
  exit 0
fi
resume=()
if [ -n "$checkpoint" ] && [ -f "$checkpoint" ]; then
  echo "resuming from checkpoint $checkpoint"
  resume=(--resume)
fi
threads=()
[ "$THREADS_FROM_SLURM" = 1 ] && threads=(--threads "${SLURM_CPUS_PER_TASK:-1}")
"$FILMBACK" render "${render_args[@]}" "${threads[@]}" "${resume[@]}"
status=$?
echo "processor time, user and system (this script's line, then the render's):"
times
if [ $status -eq 0 ]; then
  echo "$(date -u +%FT%T.%3NZ) $name: done"
  exit 0
fi
echo "$(date -u +%FT%T.%3NZ) $name: filmback render failed (exit status $status)"
# Exit status 2 is a usage error: the same command line fails again, so it is not retried.
if [ $status -ne 2 ] && [ "$try" -lt "$RETRIES" ]; then
  echo "requeueing (retry $((try + 1)) of $RETRIES)"
  # The requeue ends this script; the sleep only keeps it from exiting (and so failing) first.
  # ARRAY_INDEX, not SLURM_JOB_ID: the element that holds the array's own job id (the last one,
  # usually) would requeue the whole array.
  scontrol requeue "${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}" && sleep 600
  echo "scontrol requeue failed: not retried"
fi
exit $status
