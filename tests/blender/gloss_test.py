"""filmback's DiffCol and GlossCol passes against Cycles' on the same shot (issue 20;
docs/blender.md, "Passes"):

    gloss_test.py --filmback EXE --scratch DIR

gloss_shot.py builds a row of patches (Principled BSDF settings, a Glossy BSDF, a Mix of Diffuse
and Glossy), exports it through the add-on and renders it with Cycles' Diffuse Color and Glossy
Color passes on; filmback renders the export with `--passes DiffCol,GlossCol`. Each patch's mean
of each pass, away from its edges (OpenImageIO's `oiiotool --printstats`, to 6 decimals), must be
Cycles' within TOLERANCE. Exit 77 (CTest's skip) when `blender` or `oiiotool` is missing.
"""

import json
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from roundtrip_test import blender, driver_arguments, skip_unless_installed  # noqa: E402

# Both renderers write the first hit's closure weights: measured in full float, the means agree
# within 1.5e-8 (Fresnel's 0.0337 of the glass included), except the Sheen patch's DiffCol, 1.1e-4
# off: Cycles tints the sheen by the luminance of its OCIO config's scene-linear to XYZ
# (rgb_to_y), filmback by Rec. 709's rounded weights.
TOLERANCE = 2e-4
EDGE_PX = 2  # each patch's border left out: pixels there may see its neighbour too
PASSES = ("DiffCol", "GlossCol")


def patch_means(exr, shot):
    """{patch: {pass: [R, G, B]}}, each the mean over the patch's inner pixels."""
    channels = ",".join(f"ViewLayer.{name}.{c}" for name in PASSES for c in "RGB")
    means = {}
    for patch in shot["patches"]:
        x0, y0, x1, y1 = patch["rect"]
        region = f"{x1 - x0 - 2 * EDGE_PX}x{y1 - y0 - 2 * EDGE_PX}+{x0 + EDGE_PX}+{y0 + EDGE_PX}"
        r = subprocess.run(["oiiotool", exr, "--ch", channels, "--cut", region, "--printstats"],
                           capture_output=True, text=True)
        averages = re.search(r"Stats Avg: ([-0-9.e ]+)", r.stdout)
        if r.returncode != 0 or not averages:
            sys.exit(f"oiiotool on {exr} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
        values = [float(v) for v in averages.group(1).split()]
        means[patch["name"]] = {name: values[3 * i:3 * i + 3] for i, name in enumerate(PASSES)}
    return means


def main():
    a = driver_arguments()
    skip_unless_installed(("oiiotool", "openimageio-tools"))
    out = a.scratch
    r = blender("--python-exit-code", "1", "--python", os.path.join(HERE, "gloss_shot.py"), "--",
                out)
    if r.returncode != 0:
        sys.exit(f"gloss_shot.py failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    with open(os.path.join(out, "patches.json")) as f:
        shot = json.load(f)
    filmback_exr = os.path.join(out, "filmback.exr")
    r = subprocess.run([a.filmback, "render", os.path.join(out, "shot.gltf"), "-o", filmback_exr,
                        "--spp", str(shot["samples"]), "--filter", "box", "-q",
                        "--passes", "DiffCol,GlossCol"], capture_output=True, text=True,
                       timeout=120)
    if r.returncode != 0:
        sys.exit(f"filmback render failed ({r.returncode}):\n{r.stderr}")
    ours = patch_means(filmback_exr, shot)
    cycles = patch_means(os.path.join(out, "cycles.exr"), shot)
    failures = []
    for patch, passes in cycles.items():
        for name, theirs in passes.items():
            mine = ours[patch][name]
            worst = max(abs(m - t) for m, t in zip(mine, theirs))
            print(f"{patch:18s} {name:8s} Cycles {' '.join(f'{v:.4f}' for v in theirs)}  "
                  f"filmback {' '.join(f'{v:.4f}' for v in mine)}  differ by {worst:.2e}")
            if worst > TOLERANCE:
                failures.append(f"{patch}: {name} {worst:.2e} from Cycles'")
    if failures:
        sys.exit("\n".join(failures))


if __name__ == "__main__":
    main()
