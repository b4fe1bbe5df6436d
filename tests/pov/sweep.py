"""Renders POV-Ray's sample scenes (Debian's povray-examples) with filmback and tabulates, per
scene: whether it imported and rendered, how long it took, and the unsupported features it met
(docs/pov.md "Sample scenes"). Two counts are tracked: scenes that render with no error, and
scenes that render with complete geometry (no object skipped or approximated away).

    sweep.py --filmback build/bin/filmback [--every 20] [--matching REGEX] [--timeout 60] [--out DIR]

--every N takes every Nth scene of the sorted list (CI: a fixed sample of 20); without it,
all 396. --matching REGEX keeps only the scenes whose own file matches it (not their includes):
'\b(text|prism)\s*\{' re-runs the scenes a change to those shapes concerns. Writes DIR/sweep.csv and DIR/sweep.md. Exits non-zero only if filmback crashed (killed
by a signal) or left a non-finite pixel: an unsupported scene is a result, not a failure.
"""

import argparse
import csv
import math
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

EXAMPLES = Path("/usr/share/doc/povray/examples")
# Warnings the POV-Ray importer prints (importers/pov/pov_importer.cpp): an object left out or
# replaced, or a function evaluated as zero (trace(), a user function: what the scene computes
# with it, often where objects go, is wrong), makes the geometry incomplete; a feature "ignored"
# only changes the look.
UNSUPPORTED = re.compile(r"unsupported (object|function|feature) '([^']+)'")


def sample_scenes(every, matching=None):
    scenes = sorted(EXAMPLES.rglob("*.pov"))
    if matching:
        pattern = re.compile(matching)
        scenes = [s for s in scenes if pattern.search(s.read_text(errors="replace"))]
    return scenes[::every] if every > 1 else scenes


def nonfinite_pixels(exr, oiiotool="oiiotool"):
    """Count of NaN/Inf pixel values, from oiiotool --stats (OpenImageIO)."""
    out = subprocess.run([oiiotool, "--stats", str(exr)], capture_output=True, text=True).stdout
    found = re.search(r"NanCount:\s*([\d ]+)", out), re.search(r"InfCount:\s*([\d ]+)", out)
    return sum(int(v) for m in found if m for v in m.group(1).split())


def run_scene(filmback, scene, args, scratch):
    exr = scratch / (scene.stem + ".exr")
    command = [filmback, "render", str(scene), "-o", str(exr), "--res", args.res, "--spp",
               str(args.spp), "-q"]
    start = time.monotonic()
    try:
        result = subprocess.run(command, capture_output=True, text=True, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        return {"status": "timeout", "seconds": args.timeout, "unsupported": "", "geometry": ""}
    seconds = time.monotonic() - start
    found = UNSUPPORTED.findall(result.stderr)
    objects = sorted({name for kind, name in found if kind in ("object", "function")})
    features = sorted({name for kind, name in found if kind == "feature"})
    row = {"seconds": round(seconds, 2),
           "unsupported": " ".join(objects + features),
           "geometry": "complete" if not objects else "incomplete"}
    if result.returncode < 0:
        row["status"] = "crash (signal %d)" % -result.returncode
    elif result.returncode != 0:
        lines = [l for l in result.stderr.splitlines() if "error" in l]
        row["status"] = "error: " + (lines[-1] if lines else "exit %d" % result.returncode)
    elif nonfinite_pixels(exr):
        row["status"] = "non-finite pixels"
    else:
        row["status"] = "ok"
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--filmback", required=True)
    parser.add_argument("--every", type=int, default=1)
    parser.add_argument("--matching", help="only scenes whose own file matches this regex")
    parser.add_argument("--timeout", type=float, default=60)
    parser.add_argument("--res", default="80x60")
    parser.add_argument("--spp", type=int, default=1)
    parser.add_argument("--out", type=Path, default=Path("."))
    args = parser.parse_args()
    if not EXAMPLES.is_dir():
        print("sweep: %s is missing (install povray-examples)" % EXAMPLES, file=sys.stderr)
        return 2
    args.out.mkdir(parents=True, exist_ok=True)
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for scene in sample_scenes(args.every, args.matching):
            row = {"scene": str(scene.relative_to(EXAMPLES))}
            row.update(run_scene(args.filmback, scene, args, Path(scratch)))
            rows.append(row)
            print("%-50s %-8s %6.2f s  %s" % (row["scene"], row["status"][:60], row["seconds"],
                                             row["unsupported"]), flush=True)

    fields = ["scene", "status", "geometry", "seconds", "unsupported"]
    with open(args.out / "sweep.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)
    rendered = [r for r in rows if r["status"] == "ok"]
    complete = [r for r in rendered if r["geometry"] == "complete"]
    times = sorted(r["seconds"] for r in rendered)
    summary = ("%d scenes: %d render with no error (%.0f %%), %d with complete geometry (%.0f %%); "
               "median time %.2f s at %s, %d spp" %
               (len(rows), len(rendered), 100 * len(rendered) / len(rows), len(complete),
                100 * len(complete) / len(rows), times[len(times) // 2] if times else math.nan,
                args.res, args.spp))
    with open(args.out / "sweep.md", "w") as f:
        f.write(summary + "\n\n| scene | result | geometry | s | unsupported |\n|---|---|---|---:|---|\n")
        for r in rows:
            f.write("| %s | %s | %s | %s | %s |\n" % (r["scene"], r["status"].replace("|", "/"),
                                                     r["geometry"], r["seconds"], r["unsupported"]))
    print(summary)
    bad = [r for r in rows if r["status"].startswith(("crash", "non-finite"))]
    for r in bad:
        print("sweep: %s: %s" % (r["scene"], r["status"]), file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
