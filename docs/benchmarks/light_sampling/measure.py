"""Light sampling: RMSE against a 1024-spp reference at equal spp, and efficiency (1 / (MSE x time))
of the tree against power sampling, renders interleaved (tree, power, tree, power, ...)."""
import re, subprocess, sys, json
import numpy as np
import OpenImageIO as oiio

FB = "/work/wt-lighttree17/build/bin/filmback"
def load(p):
    return oiio.ImageBuf(p).get_pixels(oiio.FLOAT)[..., :3].astype(np.float64)
rows = []
for scene in sys.argv[1].split(","):
    ref = load(f"/tmp/lt/ref_{scene}.exr")
    for spp in [int(s) for s in sys.argv[2].split(",")]:
        for seed in (1, 2):
            for way in ("tree", "power"):
                out = f"/tmp/lt/m_{scene}_{way}_{spp}_{seed}.exr"
                r = subprocess.run([FB, "render", f"/tmp/lt/shots/{scene}/shot.gltf", "-o", out,
                                    "--res", "128x72", "--spp", str(spp), "-q", "--seed", str(seed),
                                    "--light-sampler", way], capture_output=True, text=True, check=True)
                t = float(re.search(r"in ([0-9.]+) s", r.stdout + r.stderr).group(1))
                img = load(out)
                rmse = float(np.sqrt(np.mean((img - ref) ** 2)))
                rows.append(dict(scene=scene, way=way, spp=spp, seed=seed, time_s=t, rmse=rmse,
                                 mean=float(img.mean()), ref_mean=float(ref.mean())))
                print(json.dumps(rows[-1]), flush=True)
json.dump(rows, open(f"/tmp/lt/measure_{sys.argv[3]}.json", "w"), indent=1)
