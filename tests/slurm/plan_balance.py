#!/usr/bin/python3
"""How evenly a tile plan splits a frame (docs/distributed.md, "Balance"), by measurement.

For each source of costs (`none`: the equal-area bands of `--tile I/N`; `K`: `filmback tile-plan`
with a pre-pass of K spp), it makes the plan (timing the tile-plan process: the pre-pass's own
cost), renders the N parts one after another with every core, and reads from each partial film
the seconds its 16x16 tiles took (`filmback/part/tile_seconds`, one worker thread's time per
tile) and its render loop's wall time (`filmback/part/render_seconds`). A part's cost is the sum
of its tiles' seconds: unlike its wall time it does not depend on how many threads the part had.

balance = the costliest part / the mean part (1.0: perfectly even; the frame waits for the
costliest). Each run appends one row per source to the CSV; the medians over the runs are printed.

Usage (Debian's python for OpenImageIO):
  /usr/bin/python3 tests/slurm/plan_balance.py --filmback build/bin/filmback --scene SCENE \
      --parts 8 --sources none,1,2,4 --runs 3 --csv OUT.csv -- --res 320x180 --spp 64 ...
"""

import argparse
import csv
import datetime
import os
import platform
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import OpenImageIO as oiio


def part_costs(part):
    """(sum of the part's tile seconds, its render loop's wall seconds) from a partial film."""
    spec = oiio.ImageInput.open(str(part)).spec()
    tiles = spec.get_string_attribute("filmback/part/tile_seconds").split()
    return (sum(float(s) for s in tiles),
            float(spec.get_string_attribute("filmback/part/render_seconds")))


def run(argv):
    subprocess.run([str(a) for a in argv], check=True, stdout=subprocess.DEVNULL)


def measure(args, source, folder):
    """One source's plan and parts: (plan seconds, part costs, part wall seconds)."""
    plan_args, plan_s = [], 0.0
    if source != "none":
        plan = folder / f"plan_{source}.json"
        start = time.monotonic()
        run([args.filmback, "tile-plan", args.scene, "--tiles", args.parts, "--pre-pass-spp",
             source, "-o", plan, "--", *args.render])
        plan_s = time.monotonic() - start
        plan_args = ["--tile-plan", plan]
    costs, walls = [], []
    for i in range(args.parts):
        part = folder / f"part_{source}_{i}.exr"
        run([args.filmback, "render", args.scene, *args.render, "-q", "--tile",
             f"{i}/{args.parts}", *plan_args, "-o", part])
        cost, wall = part_costs(part)
        costs.append(cost)
        walls.append(wall)
        part.unlink()
    return plan_s, costs, walls


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--filmback", type=Path, required=True)
    parser.add_argument("--scene", type=Path, required=True)
    parser.add_argument("--parts", type=int, default=8)
    parser.add_argument("--sources", default="none,1,2,4",
                        help="comma-separated: none (equal-area bands) or a pre-pass spp")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--csv", type=Path, required=True)
    parser.add_argument("render", nargs="*", help="after --: the render options")
    args = parser.parse_args()
    sources = args.sources.split(",")
    fields = ["date_utc", "machine", "cores", "load_before", "scene", "options", "parts", "run",
              "source", "plan_s", "balance", "wall_balance", "mean_part_s", "max_part_s",
              "frame_thread_s"]
    new_file = not args.csv.exists()
    results = {s: [] for s in sources}
    with open(args.csv, "a", newline="") as out, tempfile.TemporaryDirectory() as tmp:
        writer = csv.DictWriter(out, fields)
        if new_file:
            writer.writeheader()
        for r in range(args.runs):
            for source in sources:
                load = os.getloadavg()[0]
                plan_s, costs, walls = measure(args, source, Path(tmp))
                mean = statistics.mean(costs)
                row = {
                    "date_utc": datetime.datetime.utcnow().strftime("%Y-%m-%dT%H:%M:%SZ"),
                    "machine": platform.node(), "cores": os.cpu_count(),
                    "load_before": f"{load:.1f}", "scene": args.scene.name,
                    "options": " ".join(args.render), "parts": args.parts, "run": r,
                    "source": source, "plan_s": f"{plan_s:.2f}",
                    "balance": f"{max(costs) / mean:.3f}",
                    "wall_balance": f"{max(walls) / statistics.mean(walls):.3f}",
                    "mean_part_s": f"{mean:.3f}", "max_part_s": f"{max(costs):.3f}",
                    "frame_thread_s": f"{sum(costs):.3f}"}
                writer.writerow(row)
                out.flush()
                results[source].append(row)
                print(", ".join(f"{k} {row[k]}" for k in
                                ("run", "source", "load_before", "plan_s", "balance",
                                 "wall_balance", "frame_thread_s")), flush=True)
    print(f"medians over {args.runs} runs ({args.scene.name}, {args.parts} parts):")
    for source, rows in results.items():
        med = {k: statistics.median(float(row[k]) for row in rows)
               for k in ("plan_s", "balance", "wall_balance", "frame_thread_s")}
        print(f"  {source:>4}: balance {med['balance']:.3f} (wall {med['wall_balance']:.3f}), "
              f"plan {med['plan_s']:.2f} s, frame {med['frame_thread_s']:.2f} thread-s")


if __name__ == "__main__":
    main()
