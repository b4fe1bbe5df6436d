import json, sys, numpy as np, OpenImageIO as oiio
def load(p): return oiio.ImageBuf(p).get_pixels(oiio.FLOAT)[..., :3].astype(np.float64)
rows = json.load(open(sys.argv[1]))
refs = {}
out = {}
for r in rows:
    s = r["scene"]
    if s not in refs: refs[s] = load(f"/tmp/lt/ref_{s}.exr")
    ref = refs[s]
    img = load(f"/tmp/lt/m_{s}_{r['way']}_{r['spp']}_{r['seed']}.exr")
    d = img - ref
    key = (s, r["spp"], r["way"])
    o = out.setdefault(key, dict(mse=[], rel=[], mae=[], t=[]))
    o["mse"].append(np.mean(d**2)); o["rel"].append(np.mean(d**2 / (ref**2 + 1e-2)))
    o["mae"].append(np.mean(np.abs(d))); o["t"].append(r["time_s"])
print("scene spp way  RMSE  relMSE  MAE  time_s(median)")
for k in sorted(out):
    o = out[k]
    print(k[0], k[1], k[2], "%.4f %.5f %.4f %.2f" % (np.sqrt(np.mean(o["mse"])), np.mean(o["rel"]), np.mean(o["mae"]), np.median(o["t"])))
