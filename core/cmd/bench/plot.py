"""`filmback bench`: one plot per scene from the report's CSV files (docs/cli.md, "bench").

    python3 plot.py REPORT_DIR

Reads REPORT_DIR/renders.csv, fits.csv and scenes.csv and writes REPORT_DIR/SCENE.png: RMSE
against render time (left) and against total time (right), log-log, one line per configuration
with its fitted line dashed (on the right plus the configuration's fixed cost), the references'
own RMSE dotted, and the error level the summary compares times at. A scene measured against
Cycles' reference gets two rows: errors against Cycles' reference (one reference for both
renderers) on top, against each renderer's own below. Each image is written to a temporary name
and renamed into place. Exits with status 3, naming the interpreter, when matplotlib is not
installed for it (Debian package python3-matplotlib, for /usr/bin/python3); `filmback bench` then
tries the next interpreter.
"""

import csv
import math
import os
import sys
from collections import defaultdict

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.stderr.write(f"plot.py: matplotlib is not installed for {sys.executable} (Debian package "
                     "python3-matplotlib, for /usr/bin/python3)\n")
    sys.exit(3)


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    return float(text) if text else None


# (column prefix of renders.csv, reference key of fits.csv, what the row of plots shows)
OWN = ("", "own", "against each renderer's own reference")
CYCLES = ("cycles_ref_", "cycles", "against Cycles' reference (one reference for both)")


def plot_scene(scene, rows, fits, info, out_path):
    measures = [CYCLES, OWN] if any(r["cycles_ref_rmse"] for r in rows) else [OWN]
    figure, axes = plt.subplots(len(measures), 2, figsize=(12, 4.8 * len(measures)),
                                sharey="row", squeeze=False)
    for row_axes, measure in zip(axes, measures):
        plot_measure(row_axes, measure, rows, fits, info)
    title = (f"{scene}: error against time (dashed: fitted lines; dotted: the references' own "
             f"RMSE; dash-dot: the summary's target")
    if info.get("cycles_spp"):
        title += f"; thin: Cycles' RMSE at {info['cycles_spp']} spp"
    figure.suptitle(title + ")", fontsize=9)
    figure.tight_layout()
    folder, name = os.path.split(out_path)
    temporary = os.path.join(folder, f".{name}.filmback-{os.getpid()}.png")
    try:
        figure.savefig(temporary, dpi=80)
        os.replace(temporary, out_path)
    finally:
        plt.close(figure)
        if os.path.exists(temporary):
            os.remove(temporary)


def plot_measure(row_axes, measure, rows, fits, info):
    prefix, reference, what = measure
    by_configuration = defaultdict(list)
    for row in rows:
        if row[prefix + "rmse"]:
            by_configuration[(row["renderer"], row["configuration"])].append(row)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    noise_key = prefix + ("noise_rmse" if prefix else "reference_noise_rmse")
    for axis, x_key, label in ((row_axes[0], "render_s", "render time (s)"),
                               (row_axes[1], "total_s", "total time (s)")):
        floors = {}
        for index, ((renderer, configuration), points) in enumerate(by_configuration.items()):
            # Cycles in black, grey when it samples adaptively (bench --adaptive).
            cycles_colour = "black" if configuration == "cycles" else "grey"
            colour = cycles_colour if renderer == "cycles" else colours[index % len(colours)]
            name = configuration.replace("cycles", "Cycles") if renderer == "cycles" else configuration
            xs = [float(p[x_key]) for p in points]
            ys = [float(p[prefix + "rmse"]) for p in points]
            axis.plot(xs, ys, "o-", color=colour, label=name, markersize=3,
                      linewidth=2 if renderer == "cycles" else 1.2)
            fit = fits.get((renderer, configuration, reference, "render_s"))
            if fit:
                # RMSE = exp(intercept) render_s^slope over the fitted range; total time adds
                # the configuration's fixed cost, which bends the line on the right.
                lo, hi = float(fit["x_min"]), float(fit["x_max"])
                slope, intercept = float(fit["slope"]), float(fit["intercept"])
                fixed = float(fit["fixed_s"]) if x_key == "total_s" else 0.0
                line_x = [lo * (hi / lo) ** (i / 20) for i in range(21)]
                line_y = [math.exp(intercept) * x ** slope for x in line_x]
                axis.plot([x + fixed for x in line_x], line_y, "--", color=colour, linewidth=0.8)
            noise = number(points[0][noise_key])
            if noise:
                floors[(renderer, noise)] = colour
        for (renderer, noise), colour in floors.items():
            axis.axhline(noise, linestyle=":", color=colour, linewidth=0.8)
        target = number(info.get("target_rmse", ""))
        if target and info.get("target_reference", "own") == reference:
            axis.axhline(target, linestyle="-.", color="grey", linewidth=0.8)
        cycles = number(info.get("cycles_rmse", ""))
        if cycles:
            axis.axhline(cycles, linestyle="-", color="black", linewidth=0.5)
        axis.set_xscale("log")
        axis.set_yscale("log")
        axis.set_xlabel(label)
        axis.grid(True, which="both", linewidth=0.3)
    row_axes[0].set_ylabel("RMSE " + what, fontsize=8)
    row_axes[0].legend(fontsize=7)


def main():
    if len(sys.argv) != 2:
        sys.stderr.write("usage: python3 plot.py REPORT_DIR\n")
        sys.exit(2)
    folder = sys.argv[1]
    renders = read(os.path.join(folder, "renders.csv"))
    fits = {}
    for fit in read(os.path.join(folder, "fits.csv")):
        if fit["error"] == "rmse":
            fits[(fit["scene"], fit["renderer"], fit["configuration"], fit["reference"],
                  fit["x"])] = fit
    scenes = {row["scene"]: row for row in read(os.path.join(folder, "scenes.csv"))}
    for scene, info in scenes.items():
        rows = [r for r in renders if r["scene"] == scene]
        scene_fits = {key[1:]: value for key, value in fits.items() if key[0] == scene}
        plot_scene(scene, rows, scene_fits, info, os.path.join(folder, scene + ".png"))


if __name__ == "__main__":
    main()
