#!/bin/bash
# The merge of one frame of a `filmback submit` job (docs/distributed.md), run by Slurm as an
# element of the merge array once every tile task has succeeded (`afterok`):
# `sbatch --array=0-(COUNT-1) merge_task.sh JOB_DIR OFFSET`. It checks that every part of its
# frame is there, naming the ones that are not, and merges them into the frame's outputs.
set -uo pipefail
job_dir=$1
index=$(($2 + SLURM_ARRAY_TASK_ID))
source "$job_dir/job.env"                                    # FILMBACK
source "$(printf '%s/merges/%06d.sh' "$job_dir" "$index")"  # name, log, parts, outputs
exec >>"$log" 2>&1
# In the background, as a tile task names itself (tile_task.sh): the merge need not wait for it.
scontrol update JobId="${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}" JobName="$name" \
  Comment="filmback ${name#fb:}" >/dev/null 2>&1 &
echo "$(date -u +%FT%T.%3NZ) $name: job ${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID} ($SLURM_JOB_ID) on $(hostname)"
missing=0
for part in "${parts[@]}"; do
  if [ ! -s "$part" ]; then
    echo "$name: part $part is missing (its task's log is in $job_dir/logs/)"
    missing=1
  fi
done
[ $missing -eq 0 ] || exit 1
output_args=()
for output in "${outputs[@]}"; do output_args+=(-o "$output"); done
"$FILMBACK" merge "${parts[@]}" "${output_args[@]}"
status=$?
echo "$(date -u +%FT%T.%3NZ) $name: filmback merge exit status $status"
exit $status
