#!/usr/bin/env bash
# `filmback submit` on a real one-node Slurm cluster (docs/distributed.md, docs/testing.md): starts
# slurmctld and slurmd on free loopback ports with a configuration in a folder of its own
# (one_node_cluster.sh), submits one frame of a small shot twice at once as an
# 8-tile array plus a merge, and compares each merged EXR with a one-process render of the frame,
# bit for bit. In one job the last task's render (the element that holds the array's own job id)
# is killed (SIGKILL) once its checkpoint exists: the task must requeue itself alone, resume from
# the checkpoint (its log says so), and the merge must still be bit-identical; the other job's
# tasks must show their own names in squeue (fb:SCENE:fFFFF:tT/N). The daemons are stopped by pid at the end, also on failure, after
# scancel. Exit 77 (CTest's skip) only when Slurm's daemons are not installed.
#
# Usage: slurm_cluster_test.sh FILMBACK SCENE SCRATCH
# Until `render --tile` and `merge` are in the build, the tasks run tests/slurm/standin_filmback.sh
# (whole-frame parts): said on stdout.
set -euo pipefail
FILMBACK=$(realpath "$1")
SCENE=$(realpath "$2")
SCRATCH=$3
HERE=$(cd "$(dirname "$0")" && pwd)
PYTHON=/usr/bin/python3  # Debian's, with OpenImageIO and numpy
TIMEOUT_S=${TIMEOUT_S:-100}
source "$HERE/one_node_cluster.sh"
for program in slurmctld slurmd sbatch squeue scontrol scancel sinfo; do
  if ! command -v $program >/dev/null; then
    echo "skipped: $program is not installed (./setup.sh test installs slurmctld, slurmd and slurm-client)"
    exit 77
  fi
done

mkdir -p "$SCRATCH"
W=$(mktemp -d "$SCRATCH/slurm.XXXXXX")
mkdir -p "$W/out"
T0=$(date +%s%N)
log() { printf '[%6.1fs] %s\n' "$(( ($(date +%s%N) - T0) / 1000000 ))e-3" "$*"; }

cleanup() {
  local status=$?
  set +e
  cluster_stop
  log "daemons stopped"
  if [ $status -ne 0 ]; then
    squeue -t all 2>/dev/null
    tail -n 20 "$W"/cluster/log/slurmctld.log "$W"/cluster/log/jobcomp.txt "$W"/out/*/logs/*.log 2>/dev/null
    echo "FAILED; the test's folder is kept: $W"
  else
    rm -rf "$W"
  fi
  exit $status
}
trap cleanup EXIT
trap 'exit 130' INT TERM

fail() { echo "FAIL: $*" >&2; exit 1; }

# The shot: small, one frame, with adaptive sampling at Blender's default threshold (0.01: 8 checks,
# so each part samples an 8-pixel apron) and checkpoints.
# A task renders for about a second on one core (2026-11-28, this 2-core machine): long enough
# for the killed task to have written a checkpoint (every 0.05 s) and still be running. 8 rows of
# 16-pixel tiles, so that 8 parts of equal area exist without a plan.
FRAME=3
SPP=192
TASK_FILMBACK=$FILMBACK
PLAN=auto
has_command() { "$FILMBACK" --help | grep -q "^  $1 "; }
if ! has_command merge; then
  echo "filmback merge is not in this build: the tasks run the stand-in tests/slurm/standin_filmback.sh"
  export FILMBACK_REAL=$FILMBACK
  TASK_FILMBACK=$HERE/standin_filmback.sh
  PLAN=none
  SPP=24  # the stand-in's parts are whole frames: 8 times a tile's work
fi
has_command tile-plan || PLAN=none
RENDER_OPTIONS=(--res 96x128 --spp $SPP --adaptive-threshold 0.01 --seed 7)

log "one-process render of frame $FRAME"
"$FILMBACK" render "$SCENE" "${RENDER_OPTIONS[@]}" --frame $FRAME --quiet -o "$W/out/reference.exr"

log "starting a one-node Slurm cluster"
cluster_start "$W/cluster" || fail "the cluster did not come up"
log "cluster up: slurmctld $CTLD_PID on port $CTLD_PORT, slurmd $SLURMD_PID on port $SLURMD_PORT"

submit() {  # NAME [options]: the merge array's job id on stdout
  local name=$1
  shift
  "$FILMBACK" submit "$SCENE" --tiles 8 --frames $FRAME -o "$W/out/$name.####.exr" \
    --filmback "$TASK_FILMBACK" --tile-plan "$PLAN" --name "$name" "$@" "${RENDER_OPTIONS[@]}" \
    >"$W/out/$name.submit.txt"
  sed -n 's/^merge array \([0-9]*\):.*/\1/p' "$W/out/$name.submit.txt"
}
# The killed job first, so that its requeue's wait overlaps the other job. Its parts are bands of
# 16 rows from a plan whose last part is the 4th band, where the shot's objects are: the last task
# (the one that holds the array's own job id) renders for a while, long enough to be killed.
PLAN_FILE=$W/out/bands.json
/usr/bin/python3 -c '
import json, sys
bands = [0, 1, 2, 4, 5, 6, 7, 3]
parts = [{"crop": [0, 16 * b, 96, 16 * b + 16], "estimated_seconds": 1.0} for b in bands]
json.dump({"format": "filmback-tile-plan", "version": 1, "width": 96, "height": 128,
           "parts": parts}, open(sys.argv[1], "w"))' "$PLAN_FILE"
# The other job's plan is made before either is submitted (as `--tile-plan auto` would make it):
# its pre-pass takes seconds, in which the killed job's tasks would run past their checkpoints
# before the watch below starts.
WHOLE_PLAN=$PLAN
if [ "$PLAN" = auto ]; then
  WHOLE_PLAN=$W/out/whole_plan.json
  "$FILMBACK" tile-plan "$SCENE" --tiles 8 -o "$WHOLE_PLAN" -- "${RENDER_OPTIONS[@]}" \
    --frame $FRAME >/dev/null || fail "filmback tile-plan failed"
fi
MERGE_KILLED=$(PLAN=$PLAN_FILE submit killed --checkpoint-every 0.05s --retries 2)
MERGE_WHOLE=$(PLAN=$WHOLE_PLAN submit whole)
[ -n "$MERGE_WHOLE" ] && [ -n "$MERGE_KILLED" ] || fail "submit printed no merge job id"
log "submitted: merges $MERGE_WHOLE (whole) and $MERGE_KILLED (one task killed)"

# The killed job's tile 7: SIGKILL its render once its first checkpoint is written. The render is
# killed by pid: the process of this filmback executable whose command line writes the part (the
# part's path is in this test's own folder).
JOB=$W/out/killed.filmback-job
PART=$JOB/parts/f000$FRAME.t7.exr
CHECKPOINT=$JOB/parts/f000$FRAME.t7.checkpoint.exr
TILE_LOG=$JOB/logs/f000$FRAME.t7.log
render_pid() {
  local pid
  for pid in $(pgrep -f -- " render .* -o $PART "); do
    [ "$(readlink "/proc/$pid/exe" 2>/dev/null)" = "$FILMBACK" ] && { echo "$pid"; return; }
  done
}
deadline=$(($(date +%s) + TIMEOUT_S))
killed=
while [ -z "$killed" ]; do
  [ "$(date +%s)" -lt "$deadline" ] || fail "tile 7's checkpoint never appeared"
  [ -s "$PART" ] && fail "tile 7 finished before its checkpoint was seen: make its render longer"
  grep -qs "render failed" "$TILE_LOG" && fail "tile 7 failed by itself ($TILE_LOG)"
  if [ -f "$CHECKPOINT" ]; then
    pid=$(render_pid)
    if [ -n "$pid" ]; then
      kill -KILL "$pid" && killed=$pid
    fi
  fi
  sleep 0.02
done
log "tile 7 of the killed job: render pid $killed killed with its checkpoint written ($(grep -o 'job [0-9_]* ([0-9]*)' "$TILE_LOG" | head -1))"

STATE_WHOLE=$(job_final_state "$MERGE_WHOLE" $deadline)
STATE_KILLED=$(job_final_state "$MERGE_KILLED" $deadline)
log "merges: whole $STATE_WHOLE, killed $STATE_KILLED"
[ "$STATE_WHOLE" = COMPLETED ] || fail "the merge of the whole job ended $STATE_WHOLE"
[ "$STATE_KILLED" = COMPLETED ] || fail "the merge of the killed job ended $STATE_KILLED"

"$PYTHON" "$HERE/compare_exr.py" "$W/out/reference.exr" "$W/out/whole.000$FRAME.exr" ||
  fail "the merged frame differs from the one-process render"
"$PYTHON" "$HERE/compare_exr.py" "$W/out/reference.exr" "$W/out/killed.000$FRAME.exr" ||
  fail "the merged frame of the job with a killed task differs from the one-process render"
grep -q "try 2 of 3" "$TILE_LOG" || fail "tile 7 was not tried a second time ($TILE_LOG)"
grep -q "^resuming from checkpoint $CHECKPOINT" "$TILE_LOG" ||
  fail "tile 7's second try did not resume from its checkpoint ($TILE_LOG)"
# Only tile 7 ran twice: its element holds the array's own job id (Slurm gives it to the last
# index), and a requeue of that id rather than of ARRAY_7 would have requeued every element.
for t in 0 1 2 3 4 5 6; do
  [ "$(grep -c ": try " "$JOB/logs/f000$FRAME.t$t.log")" = 1 ] || fail "tile $t ran more than once"
done
# Each task renamed itself (in the background, the render not waiting for it): squeue shows
# scene, frame and tile.
names=$(squeue -h -t all -o %j | grep -c "^fb:whole:f000$FRAME:t[0-7]/8\$" || true)
[ "$names" = 8 ] || fail "$names of the whole job's 8 tile tasks show their own name in squeue"
log "OK: both merges bit-identical to the one-process render; the killed task resumed from its checkpoint"
