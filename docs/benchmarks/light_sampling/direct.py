import os, subprocess, numpy as np, OpenImageIO as oiio, sys, re
FB="/work/wt-lighttree17/build/bin/filmback"
def load(p): return oiio.ImageBuf(p).get_pixels(oiio.FLOAT)[..., :3].astype(np.float64)
def render(scene, out, spp, seed, way, alpha="0.1"):
    r = subprocess.run([FB, "render", f"/tmp/lt/shots/{scene}/shot.gltf", "-o", out, "--res", "128x72", "--spp", str(spp), "-q", "--seed", str(seed), "--light-sampler", way, "--integrator", "path:max_depth=1"], env=dict(os.environ, FB_ALPHA=alpha), check=True, capture_output=True, text=True)
    return float(re.search(r"in ([0-9.]+) s", r.stdout + r.stderr).group(1))
for scene in sys.argv[1].split(","):
    refp = f"/tmp/lt/dref_{scene}.exr"
    if not os.path.exists(refp): render(scene, refp, 512, 77, "power", "0.1")
    ref = load(refp)
    for way, alpha in (("power", "0"), ("tree", "0.1")):
        m = []; rel = []; ts = []
        for seed in (1, 2, 3, 4):
            out = f"/tmp/lt/d_{scene}_{way}_{alpha}_{seed}.exr"
            ts.append(render(scene, out, 16, seed, way, alpha))
            d = load(out) - ref
            m.append(np.mean(d**2)); rel.append(np.mean(d**2/(ref**2+1e-2)))
        print(scene, way, alpha, "RMSE %.4f relMSE %.5f time %.2f" % (np.sqrt(np.mean(m)), np.mean(rel), np.median(ts)), flush=True)
