"""filmback's Vector pass against Cycles' on the same shot (issue 20; docs/blender.md, "Passes"):

    vector_test.py --filmback EXE --scratch DIR

vector_shot.py builds a shot where the camera, a sliding plane and a turning plane all move, and
renders it with Cycles 3.4 (motion blur off, Vector and Z passes); filmback renders the add-on's
export with `--passes Depth,Vector`. On interior pixels (the pixel and its 8 neighbours all hit
something in both renders) every channel must agree within 0.05 px. Edge pixels are compared
too, within 0.1 px: there both renderers average the motion of the samples that hit, leaving the
background's out (a pixel whose samples hit in one renderer only is counted, not compared). Exit 77 (CTest's skip) when `blender` is not installed.
"""

import os
import subprocess
import sys

import OpenImageIO as oiio

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from roundtrip_test import blender, driver_arguments  # noqa: E402

INTERIOR_TOLERANCE_PX = 0.05  # issue 20
# Edge pixels: both average the hits of 16 samples, which land at different places in each
# renderer, over a turning plane whose vector changes by 0.05 px per pixel: a few hundredths.
EDGE_TOLERANCE_PX = 0.1
MISS_DEPTH_M = 1e9  # both write 1e10 m where nothing was hit
VECTOR = ["ViewLayer.Vector." + c for c in "XYZW"]


def read_passes(path):
    """(width, height, {channel: [values, rows top first]}) of the Vector and Depth channels."""
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"cannot read {path}: {oiio.geterror()}")
    spec = image.spec()
    pixels = image.read_image(0, 0, 0, spec.nchannels, "float")
    image.close()
    names = list(spec.channelnames)
    wanted = VECTOR + ["ViewLayer.Depth.Z"]
    missing = [n for n in wanted if n not in names]
    if missing:
        sys.exit(f"{path}: no channel {missing} among {names}")
    return spec.width, spec.height, {n: pixels[:, :, names.index(n)] for n in wanted}


def main():
    a = driver_arguments()
    out = a.scratch
    r = blender("--python-exit-code", "1", "--python", os.path.join(HERE, "vector_shot.py"), "--",
                out)
    if r.returncode != 0:
        sys.exit(f"vector_shot.py failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    filmback_exr = os.path.join(out, "filmback.exr")
    r = subprocess.run([a.filmback, "render", os.path.join(out, "shot.gltf"), "-o", filmback_exr,
                        "--spp", "16", "--filter", "box", "-q", "--passes", "Depth,Vector"],
                       capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        sys.exit(f"filmback render failed ({r.returncode}):\n{r.stderr}")
    width, height, ours = read_passes(filmback_exr)
    cycles_size = read_passes(os.path.join(out, "cycles.exr"))
    if cycles_size[:2] != (width, height):
        sys.exit(f"sizes differ: filmback {width}x{height}, Cycles {cycles_size[:2]}")
    cycles = cycles_size[2]

    # Depth says where a pixel hit something: filmback's is its nearest sample's, Cycles' its
    # first sample's, so along edges one may say hit and the other not.
    def hit(x, y, need=all):
        return (0 <= x < width and 0 <= y < height and
                need(r["ViewLayer.Depth.Z"][y, x] < MISS_DEPTH_M for r in (ours, cycles)))

    failures = []
    worst = {"interior": 0.0, "edge": 0.0}
    counts = {"interior": 0, "edge": 0, "one-sided": 0, "background": 0}
    for y in range(height):
        for x in range(width):
            if not hit(x, y, need=any):
                counts["background"] += 1
                for n in VECTOR:
                    if ours[n][y, x] != 0.0:
                        failures.append(f"{n} at {x},{y}: {ours[n][y, x]} on the background")
                continue
            kind = ("interior" if all(hit(x + i, y + j) for i in (-1, 0, 1) for j in (-1, 0, 1))
                    else "edge")
            # A pixel an object barely touches may have hits in one renderer's samples and none
            # in the other's: all four channels exactly 0 on one side only.
            if kind == "edge" and sum(all(r[n][y, x] == 0.0 for n in VECTOR)
                                      for r in (ours, cycles)) == 1:
                counts["one-sided"] += 1
                continue
            counts[kind] += 1
            for n in VECTOR:
                difference = abs(float(ours[n][y, x]) - float(cycles[n][y, x]))
                worst[kind] = max(worst[kind], difference)
                limit = INTERIOR_TOLERANCE_PX if kind == "interior" else EDGE_TOLERANCE_PX
                if difference > limit:
                    failures.append(f"{n} at {x},{y} ({kind}): filmback {ours[n][y, x]:.4f}, "
                                    f"Cycles {cycles[n][y, x]:.4f}")
    largest = max(abs(float(v)) for n in VECTOR for v in cycles[n].flat)
    print(f"{counts['interior']} interior pixels (worst {worst['interior']:.4f} px from Cycles), "
          f"{counts['edge']} on edges (worst {worst['edge']:.4f} px), {counts['one-sided']} "
          f"edge pixels hit in one renderer only, "
          f"{counts['background']} background; Cycles' largest component {largest:.3f} px")
    if counts["interior"] < 50 or largest < 1.0:
        failures.append("the shot does not show what it should: too few interior pixels or "
                        "too little motion")
    if failures:
        sys.exit("\n".join(failures[:20]))


if __name__ == "__main__":
    main()
