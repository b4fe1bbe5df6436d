"""Light sampling, issue 17: tree against power on full paths (max_depth 8), 128x72, 64 spp, three
seeds, renders interleaved (tree, power per seed); errors against a 1024-spp tree render (seed 99)."""
import json, re, subprocess, sys
import numpy as np
import OpenImageIO as oiio
FB = "/work/wt-lighttree17/build/bin/filmback"
def load(p): return oiio.ImageBuf(p).get_pixels(oiio.FLOAT)[..., :3].astype(np.float64)
rows = []
for scene in ("many_lamps", "glossy_interior"):
    ref = load(f"/tmp/lt/ref_{scene}.exr")
    for seed in (1, 2, 3):
        for way in ("tree", "power"):
            out = f"/tmp/lt/f_{scene}_{way}_{seed}.exr"
            r = subprocess.run([FB, "render", f"/tmp/lt/shots/{scene}/shot.gltf", "-o", out, "--res", "128x72",
                                "--spp", "64", "-q", "--seed", str(seed), "--light-sampler", way],
                               capture_output=True, text=True, check=True)
            t = float(re.search(r"in ([0-9.]+) s", r.stdout + r.stderr).group(1))
            d = np.abs(load(out) - ref).mean(-1)
            rows.append(dict(scene=scene, way=way, seed=seed, time_s=t, rmse=float(np.sqrt((d**2).mean())),
                             mae=float(d.mean()), median=float(np.median(d)), max=float(d.max())))
            print(json.dumps(rows[-1]), flush=True)
json.dump(rows, open("/tmp/lt/final.json", "w"), indent=1)
for scene in ("many_lamps", "glossy_interior"):
    for way in ("tree", "power"):
        rs = [r for r in rows if r["scene"] == scene and r["way"] == way]
        print(scene, way, "RMSE %.4f MAE %.4f median %.4f time %.2f" % (
            np.sqrt(np.mean([r["rmse"]**2 for r in rs])), np.mean([r["mae"] for r in rs]),
            np.mean([r["median"] for r in rs]), np.median([r["time_s"] for r in rs])))
