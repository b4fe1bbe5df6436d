#!/usr/bin/env bash
# `filmback submit` without a cluster (docs/distributed.md): --dry-run writes the job folder and
# prints the sbatch commands; the task files hold each task's command line exactly (a quote in a
# path included); arrays stay within --max-array-size and the merge depends on every one of them;
# usage errors exit 2 and bad input 1, each writing nothing; without sbatch on PATH, exit 1
# suggesting --dry-run; --tile-plan auto makes the plan every task reads. Usage: submit_cli_test.sh FILMBACK SCENE SCRATCH
set -euo pipefail
FILMBACK=$(realpath "$1")
SCENE=$(realpath "$2")
mkdir -p "$3"
W=$(mktemp -d "$3/submit.XXXXXX")
trap 'status=$?; [ $status -eq 0 ] && rm -rf "$W" || echo "FAILED; the test folder is kept: $W"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# expect STATUS TEXT COMMAND...: the exit status and a text in its messages, and no job folder left.
expect() {
  local status=$1 text=$2 got=0
  shift 2
  "$@" >"$W/out.txt" 2>&1 || got=$?
  [ "$got" = "$status" ] || { cat "$W/out.txt"; fail "exit status $got, expected $status: $*"; }
  grep -qF -- "$text" "$W/out.txt" || { cat "$W/out.txt"; fail "no '$text' in the messages of: $*"; }
  [ -z "$(find "$W" -name '*.filmback-job*')" ] || fail "a job folder was left by: $*"
}

mkdir "$W/it's here"
OUT="$W/it's here/shot.####.exr"
JOB="$W/it's here/shot.filmback-job"
# Usage errors (2) and bad input (1), nothing written.
expect 2 "--frames '5-3'" "$FILMBACK" submit "$SCENE" --tiles 8 --frames 5-3 -o "$OUT" --dry-run
expect 2 "run of '#'" "$FILMBACK" submit "$SCENE" --tiles 8 --frames 1-2 -o "$W/shot.exr" --dry-run
expect 2 "'--tile' is set by submit" "$FILMBACK" submit "$SCENE" --tiles 8 -o "$OUT" --tile 1/2 --dry-run
expect 2 "--tiles" "$FILMBACK" submit "$SCENE" --tiles 0 -o "$OUT" --dry-run
expect 1 "no such scene file" "$FILMBACK" submit "$W/none.gltf" --tiles 8 -o "$OUT" --dry-run
expect 1 "sbatch is not on PATH" env PATH=/nonexistent "$FILMBACK" submit "$SCENE" --tiles 8 -o "$OUT"
grep -qF -- "--dry-run writes the job folder" "$W/out.txt" || fail "no --dry-run suggested"

# A dry run: 2 frames x 8 tiles in arrays of at most 5: 4 tile arrays, 1 merge array after all 4.
"$FILMBACK" submit "$SCENE" --tiles 8 --frames 4-6:2 -o "$OUT" --tile-plan none --dry-run \
  --max-array-size 5 --checkpoint-every 30s --spp 16 --res 64x48 >"$W/dry.txt"
[ "$(grep -c "^tiles_[0-9]=\$('sbatch'" "$W/dry.txt")" = 4 ] || fail "not 4 tile arrays"
grep -q "^merges_0=\$('sbatch' '--parsable' --dependency=afterok:\$tiles_0:\$tiles_1:\$tiles_2:\$tiles_3 " \
  "$W/dry.txt" || fail "the merge does not depend on every tile array"
grep -q "'--kill-on-invalid-dep=yes'" "$W/dry.txt" || fail "no --kill-on-invalid-dep"
cmp -s <(sed 1d "$W/dry.txt") "$JOB/submit.sh" || fail "the printed commands are not submit.sh"
[ "$(ls "$JOB/tasks" | wc -l)" = 16 ] && [ "$(ls "$JOB/merges" | wc -l)" = 2 ] ||
  fail "not 16 task files and 2 merge files"
# Task 13: frame index 1 (frame 6), tile 5: its command line, word for word, as bash reads it.
(
  source "$JOB/tasks/000013.sh"
  part="$JOB/parts/f0006.t5.exr"
  expected=("$SCENE" --spp 16 --res 64x48 --frame 6 --tile 5/8 -o "$part" --checkpoint
            "$JOB/parts/f0006.t5.checkpoint.exr" --checkpoint-every 30s --quiet)
  [ "${render_args[*]}" = "${expected[*]}" ] && [ ${#render_args[@]} = ${#expected[@]} ] ||
    fail "task 13 renders: ${render_args[*]}"
  [ "$name" = "fb:default:f0006:t5/8" ] || fail "task 13's name: $name"
  source "$JOB/merges/000001.sh"
  [ "${outputs[*]}" = "$W/it's here/shot.0006.exr" ] || fail "frame 6's output: ${outputs[*]}"
  [ ${#parts[@]} = 8 ] && [ "${parts[5]}" = "$part" ] || fail "frame 6's parts: ${parts[*]}"
) || exit 1
bash -n "$JOB/submit.sh" && bash -n "$JOB/tile_task.sh" && bash -n "$JOB/merge_task.sh" ||
  fail "a script of the job folder does not parse"
# A job folder is never reused.
expect_reuse=0
"$FILMBACK" submit "$SCENE" --tiles 8 -o "$OUT" --frames 4-6:2 --dry-run --tile-plan none \
  >"$W/out.txt" 2>&1 || expect_reuse=$?
[ $expect_reuse = 1 ] && grep -qF "the job folder exists" "$W/out.txt" || fail "a job folder was reused"
# --tile-plan auto: the plan is made in submit's own process (its pre-pass one render process)
# and every task reads it; a pre-pass that fails (a bad render option) leaves no job folder.
status=0
"$FILMBACK" submit "$SCENE" --tiles 4 -o "$W/auto.exr" --dry-run --res 64x48 --no-such-option \
  >"$W/out.txt" 2>&1 || status=$?
[ $status = 1 ] && grep -qF -- "submit: --tile-plan auto: tile-plan: the pre-pass render" "$W/out.txt" ||
  { cat "$W/out.txt"; fail "a failing pre-pass: exit $status"; }
[ -z "$(find "$W" -maxdepth 1 -name '*auto.filmback-job*')" ] || fail "a failing pre-pass left files"
"$FILMBACK" submit "$SCENE" --tiles 4 -o "$W/auto.exr" --dry-run --res 64x48 --spp 4 \
  >"$W/auto.txt" 2>"$W/auto.err" || { cat "$W/auto.err"; fail "submit --tile-plan auto failed"; }
grep -q "^submit: tile plan made in [0-9.e-]* s: filmback: wrote .*: 4 parts of 64x48 from a pre-pass" \
  "$W/auto.err" || { cat "$W/auto.err"; fail "no tile plan line"; }
/usr/bin/python3 -c 'import json, sys; assert len(json.load(open(sys.argv[1]))["parts"]) == 4' \
  "$W/auto.filmback-job/plan.json" || fail "the job folder's plan.json has not 4 parts"
(
  source "$W/auto.filmback-job/tasks/000002.sh"
  [[ " ${render_args[*]} " == *" --tile 2/4 --tile-plan $W/auto.filmback-job/plan.json "* ]] ||
    fail "task 2 does not read the plan: ${render_args[*]}"
) || exit 1
[ -z "$(find "$W" -maxdepth 1 -name '.auto.filmback-job*')" ] || fail "the made plan was left beside the folder"
echo "OK: dry run, task command lines, array split, refusals, the tile plan"
