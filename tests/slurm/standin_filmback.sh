#!/bin/bash
# A stand-in for the filmback that `filmback submit`'s tasks run (submit --filmback), for
# slurm_cluster_test.sh while `render --tile` and `merge` (issue 18, parts18) are not in the build:
# `render ... --tile I/N [--tile-plan P] ...` renders the whole frame with the real filmback
# ($FILMBACK_REAL) into the part, with its checkpoints; `merge PARTS... -o OUT...` checks that every
# part is there and writes the first one to each output. The Slurm mechanics (arrays, requeue,
# resume from a checkpoint, the merge's dependency) are the real ones; only the split is not.
# STANDIN_SPP_DIVISOR=D (measure_overhead.sh): a part renders the frame at 1/D of --spp, a tile's
# sample count with a tile's fixed costs (start, scene, BVH), as a proxy of a tile's time.
set -euo pipefail
real=${FILMBACK_REAL:?the real filmback}
command=$1
shift
if [ "$command" = render ]; then
  args=()
  while [ $# -gt 0 ]; do
    case $1 in
      --tile | --tile-plan) shift 2 ;;
      --spp) args+=(--spp $(($2 / ${STANDIN_SPP_DIVISOR:-1}))); shift 2 ;;
      *) args+=("$1"); shift ;;
    esac
  done
  exec "$real" render "${args[@]}"  # exec: the task's render is a filmback process, as for real
fi
[ "$command" = merge ] || { echo "standin_filmback.sh: $command: not stood in for" >&2; exit 2; }
parts=() outputs=()
while [ $# -gt 0 ]; do
  case $1 in
    -o) outputs+=("$2"); shift 2 ;;
    *) parts+=("$1"); shift ;;
  esac
done
for part in "${parts[@]}"; do [ -s "$part" ] || { echo "$part: missing part" >&2; exit 1; }; done
for output in "${outputs[@]}"; do
  cp "${parts[0]}" "$output.standin-tmp"
  mv "$output.standin-tmp" "$output"
done
