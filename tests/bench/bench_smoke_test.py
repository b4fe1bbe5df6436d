"""Smoke test of `filmback bench` (label bench): a tiny run writes the report with one row per
render and finite numbers in it. Nothing about speed is asserted (docs/benchmarks.md).

    python3 bench_smoke_test.py --filmback EXE --scratch DIR [--against-cycles] SCENE

With --against-cycles the scene is a Blender shot and Cycles renders it too; the test exits 77
(a skip) when `blender` is not on PATH.
"""

import argparse
import csv
import math
import os
import shutil
import subprocess
import sys

SPP = (1, 2, 4)
CYCLES_SPP = (1, 2)  # each a Blender process of a second or more
SAMPLERS = ("sobol", "independent")
FILMBACK_NUMBERS = ("render_s", "total_s", "samples_per_s", "rays_per_s", "rmse", "relmse",
                    "max_abs_error", "reference_noise_rmse")
CYCLES_NUMBERS = ("render_s", "total_s", "samples_per_s", "rmse", "relmse", "max_abs_error",
                  "reference_noise_rmse")
# Against Cycles' reference: every row of a Blender shot run against Cycles (the filmback rows
# render with the shot's pixel filter, the one Cycles uses).
COMMON_NUMBERS = ("cycles_ref_rmse", "cycles_ref_relmse", "cycles_ref_max_abs_error",
                  "cycles_ref_noise_rmse")


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def finite(row, keys):
    for key in keys:
        try:
            value = float(row[key])
        except ValueError:
            fail(f"{key} is '{row[key]}' in {row}")
        if not math.isfinite(value) or value < 0:
            fail(f"{key} is {value} in {row}")


def check_plots(summary, stderr, name, report):
    """Either the plot is drawn and the summary names an interpreter that has matplotlib, or the
    warning names the interpreters that lack it."""
    marker = "Plots drawn by `"
    if marker in summary:
        python = summary.split(marker, 1)[1].split("`", 1)[0]
        has = subprocess.run([python, "-c", "import matplotlib"], capture_output=True)
        if has.returncode != 0:
            fail(f"the summary names {python}, which has no matplotlib")
        if not os.path.isfile(os.path.join(report, name + ".png")):
            fail("the summary names a plot interpreter but no plot is written")
    elif "matplotlib is not installed for " not in stderr:
        fail(f"no plot and no warning naming the interpreters:\n{stderr}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--filmback", required=True)
    parser.add_argument("--scratch", required=True)
    parser.add_argument("--against-cycles", action="store_true")
    parser.add_argument("scene")
    args = parser.parse_args()
    if args.against_cycles and shutil.which("blender") is None:
        print("skipped: blender (Debian package blender) is not installed")
        sys.exit(77)
    shutil.rmtree(args.scratch, ignore_errors=True)
    os.makedirs(args.scratch)
    report = os.path.join(args.scratch, "report")
    spp = CYCLES_SPP if args.against_cycles else SPP
    command = [args.filmback, "bench", args.scene, "--res", "48x27", "--spp",
               ",".join(map(str, spp)), "--reference-spp", "8", "--sampler", ",".join(SAMPLERS),
               "-o", report]
    if args.against_cycles:
        command += ["--against", "cycles"]
    # A Python launched through a version manager's shim (pyenv) has its own bin folder first on
    # PATH; Blender's embedded Python would then take that installation's modules for its own
    # and miss Debian's numpy. The renderers run with the PATH this script was started with.
    own_bin = os.path.dirname(os.path.realpath(sys.executable))
    path = [p for p in os.environ.get("PATH", "").split(os.pathsep)
            if os.path.realpath(p) != own_bin]
    env = dict(os.environ, PATH=os.pathsep.join(path))
    run = subprocess.run(command, capture_output=True, text=True, env=env)
    if run.returncode != 0:
        fail(f"exit status {run.returncode}\n{run.stdout}\n{run.stderr}")

    name = os.path.splitext(os.path.basename(args.scene))[0]
    with open(os.path.join(report, "renders.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    filmback = [r for r in rows if r["renderer"] == "filmback"]
    cycles = [r for r in rows if r["renderer"] == "cycles"]
    expected = sorted((s, n) for s in SAMPLERS for n in spp)
    if sorted((r["sampler"], int(r["spp"])) for r in filmback) != expected:
        fail(f"filmback rows {[(r['sampler'], r['spp']) for r in filmback]}, expected {expected}")
    if sorted(int(r["spp"]) for r in cycles) != (list(spp) if args.against_cycles else []):
        fail(f"Cycles rows at {[r['spp'] for r in cycles]}")
    for row in rows:
        if row["scene"] != name:
            fail(f"scene '{row['scene']}', expected '{name}'")
        finite(row, FILMBACK_NUMBERS if row["renderer"] == "filmback" else CYCLES_NUMBERS)
        if args.against_cycles:
            finite(row, COMMON_NUMBERS)
        elif row["cycles_ref_rmse"]:
            fail(f"an error against Cycles' reference without Cycles: {row}")
    # Cycles' own reference is Cycles' reference: both measures of a Cycles row are one.
    for row in cycles:
        if row["rmse"] != row["cycles_ref_rmse"]:
            fail(f"Cycles' two errors differ: {row}")
    for row in filmback:
        if not row["nonfinite_dropped"].isdigit():
            fail(f"nonfinite_dropped is '{row['nonfinite_dropped']}'")
    with open(os.path.join(report, "scenes.csv"), newline="") as f:
        scenes = list(csv.DictReader(f))
    if [s["scene"] for s in scenes] != [name]:
        fail(f"scenes.csv lists {[s['scene'] for s in scenes]}")
    finite(scenes[0], ("import_s", "build_s", "peak_rss_bytes", "geometry_bvh_bytes",
                       "film_bytes", "target_rmse"))
    if args.against_cycles:
        finite(scenes[0], ("prepare_s", "cycles_rmse", "bias_rmse", "mean_ratio",
                           "mean_relative_difference", "mean_relative_noise", "worst_block",
                           "worst_block_noise"))
        if scenes[0]["target_reference"] != "cycles":
            fail(f"the target is on the '{scenes[0]['target_reference']}' reference")
    with open(os.path.join(report, "summary.md")) as f:
        summary = f.read()
    if f"## {name}" not in summary or "| configuration |" not in summary:
        fail("summary.md lacks the scene's section or its table")
    if args.against_cycles and ("Against Cycles, on one reference" not in summary or
                                "Against Cycles, each against its own reference" not in summary):
        fail("summary.md lacks a comparison with Cycles")
    check_plots(summary, run.stderr, name, report)
    print(f"ok: {len(rows)} renders, summary.md written")


if __name__ == "__main__":
    main()
