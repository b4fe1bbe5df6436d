"""Speed-up of a frame rendered as N parts on N nodes, from measured inputs (docs/distributed.md,
"Speed-up at N nodes").

The model: every node renders one part of `filmback tile-plan`'s cost-balanced split with all its
cores, after its fixed costs (process start, scene import and set-up, writing its part); the
frame is done when the costliest part is, plus the scheduler's cost of starting the array and the
merge job, plus the merge. One node renders the whole frame without a merge or a scheduler:

    T(1) = fixed + total / cores
    T(N) = scheduler + fixed + max_i(part_i) / cores + merge
    speed-up S(N) = T(1) / T(N), efficiency S(N) / N

The per-tile seconds come from a render's --stats-json report (`tiles.seconds`: each 16x16 tile's
time on one thread), scaled by --scale (the production frame's samples over the measured one's;
time per tile grows linearly with the sample count). The parts are the ones filmback would plan
for those costs (`filmback tile-plan --report`), so the model's imbalance is the planner's.

Run with Debian's python3 (no packages beyond the standard library):
    /usr/bin/python3 tests/bench/distributed_model.py --filmback build/bin/filmback \
        --report r.json --scale 64 --fixed-s 1.2 --merge-s 3.0 --scheduler-s 2.0 -o model.csv
"""

import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--filmback", required=True, help="the filmback executable")
    p.add_argument("--report", required=True, help="--stats-json of a render of the frame")
    p.add_argument("--scale", type=float, default=1.0,
                   help="production samples over the measured render's (default 1)")
    p.add_argument("--cores", type=int, default=2, help="cores per node (default 2)")
    p.add_argument("--fixed-s", type=float, required=True,
                   help="a task's fixed seconds: process start, import, set-up, part written")
    p.add_argument("--merge-s", type=float, required=True, help="the merge job's seconds")
    p.add_argument("--scheduler-s", type=float, required=True,
                   help="the scheduler's seconds to start the array and release the merge")
    p.add_argument("--nodes", default="1,2,4,8,16,32,64", help="node counts (default 1..64)")
    p.add_argument("-o", "--output", required=True, help="CSV written")
    return p.parse_args()


def planned_part_seconds(filmback, report, parts, folder):
    plan = os.path.join(folder, "plan_%d.json" % parts)
    subprocess.run([filmback, "tile-plan", "--report", report, "--tiles", str(parts), "-o", plan],
                   check=True, stdout=subprocess.DEVNULL)
    with open(plan) as f:
        return [p["estimated_seconds"] for p in json.load(f)["parts"]]


def main():
    a = parse_args()
    with open(a.report) as f:
        total = sum(json.load(f)["tiles"]["seconds"]) * a.scale
    t1 = a.fixed_s + total / a.cores
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for n in (int(x) for x in a.nodes.split(",")):
            parts = [s * a.scale for s in planned_part_seconds(a.filmback, a.report, n, folder)]
            tn = t1 if n == 1 else a.scheduler_s + a.fixed_s + max(parts) / a.cores + a.merge_s
            rows.append({"nodes": n, "one_node_s": round(t1, 3), "makespan_s": round(tn, 3),
                         "costliest_part_over_mean": round(max(parts) * n / sum(parts), 4),
                         "speedup": round(t1 / tn, 3), "efficiency": round(t1 / tn / n, 4)})
    with open(a.output, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    for r in rows:
        print("%3d nodes: %8.1f s, speed-up %6.2f (%.3f N), costliest part %.3f x the mean"
              % (r["nodes"], r["makespan_s"], r["speedup"], r["efficiency"],
                 r["costliest_part_over_mean"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
