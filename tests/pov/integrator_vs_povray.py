#!/usr/bin/python3
"""`filmback render --integrator povray` against POV-Ray's own render of twenty of its sample
scenes (issue 19; docs/pov.md "The povray integrator"). Each scene is rendered at the same size by

  povray    +W +H -D -A +FN16 File_Gamma=1.0: one ray through each pixel centre, linear 16-bit
            PNG (as tests/support/povray_render.cpp), run in a scratch folder with the scene's
            folder as a library path (povray.conf lets it write only there and in /tmp);
  filmback  render --integrator povray --filter box:radius=0.001 --spp 1 --seed 1: one sample
            through each pixel centre too, in the scene's folder; --spp 16 for a scene that has an
            `area_light`, whose shadow filmback takes from one grid point per sample (POV-Ray
            from the grid at once), so that the grid is averaged.

and compared, linear RGB, filmback's values clipped to [0, 1] as the PNG clips POV-Ray's. A
legacy scene (before 3.7, no assumed_gamma: POV-Ray's log says "gamma_correction is turned off")
is rendered by POV-Ray in display values whatever File_Gamma says; filmback decodes its colours
as c^2.2 (docs/pov.md "Colours and assumed_gamma"), so POV-Ray's values are decoded so too.


  mean relative difference  the mean of |f - p| / p over the values (R, G, B of every pixel) that
                            POV-Ray renders in (0.02, 0.98), as PovRayIntegrator.* do: darker
                            values would divide by almost nothing, brighter ones are clipped;
  95th-percentile pixel     per pixel, the largest over R, G, B of |f - p| / max(p, 0.02) (a
                            black pixel counts an absolute difference of 0.02 as 100 %); the 95th
                            percentile of that over all the pixels.

A scene passes with mean <= 3 % and 95th percentile <= 10 % (issue 19's evidence).

    integrator_vs_povray.py --filmback EXE --out DIR [--res WxH] [--check] [SCENE...]
    integrator_vs_povray.py --filmback EXE --choose

SCENE is a path under Debian's povray-examples (default: the twenty of SCENES). Writes
DIR/integrator_vs_povray.md, the table with both renderers' wall-clock times, the machine and its
load. --check exits 1 when a scene fails; exit 77 (CTest's skip) without povray or
povray-examples. --choose prints the twenty that the rule below picks (how SCENES was made).
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

import peer_table
import sweep  # the sample scenes, and whether filmback renders their geometry

SKIP = 77
MOST_MEAN_RELATIVE = 0.03
MOST_P95_PIXEL = 0.10
LIT_LOW, LIT_HIGH = 0.02, 0.98  # the values the mean is taken over, as PovRayIntegrator.*
PIXEL_FLOOR = 0.02              # the least denominator of a pixel's relative difference
LEGACY_GAMMA = 2.2              # POV-Ray's output of a scene without gamma handling, decoded
LEGACY_LOG = "gamma_correction is turned off"
AREA_LIGHT_SPP = 16
TIMEOUT_S = 600

# The rule, applied once before any scene was compared (--choose reproduces it):
#  1. every sample scene outside animations/ (their clock drives them), portfolio/ (they need
#     their .ini files) and radiosity/, whose own file and the .inc files of its folder that it
#     includes name none of `radiosity`, `photons`, `media` (issue 19: none of those);
#  2. of those, the ones sweep.py renders with no error and complete geometry (80x60, 1 spp);
#  3. twenty of them evenly spaced through the sorted list (index round(i * n / 20)), which takes
#     them from every folder in proportion and so varies finishes, patterns and lights.
EXCLUDED_FOLDERS = ("animations/", "portfolio/", "radiosity/")
EXCLUDED_FEATURES = re.compile(r"\b(radiosity|photons|media)\b")
INCLUDE = re.compile(r'#include\s+"([^"]+)"')

# --choose on 2026-11-29 (main at 7138630): 317 candidates, 293 complete.
SCENES = (
    "advanced/bwstripe.pov",
    "advanced/pawns.pov",
    "camera/cylinder2.pov",
    "camera/shear.pov",
    "incdemo/shapes2.pov",
    "incdemo/woods/ash.pov",
    "incdemo/woods/wood_12.pov",
    "incdemo/woods/wood_9.pov",
    "interior/magglass.pov",
    "language/macros/macro4.pov",
    "objectmods/double_illuminate.pov",
    "objects/lathe2.pov",
    "objects/quartic/lemnisca.pov",
    "objects/superel2.pov",
    "templates/Basic_Scenes/Rainy_S_Cloud4.pov",
    "textures/finishes/cluster.pov",
    "textures/patterns/brick.pov",
    "textures/patterns/leopard.pov",
    "textures/patterns/spotted.pov",
    "textures/pigments/matmap.pov",
)


def uses_excluded_feature(scene):
    text = scene.read_text(errors="replace")
    for name in INCLUDE.findall(text):
        local = scene.parent / name
        if local.is_file():
            text += local.read_text(errors="replace")
    return EXCLUDED_FEATURES.search(text) is not None


def choose(filmback, count=20):
    candidates = [s for s in sweep.sample_scenes(1)
                  if not str(s.relative_to(sweep.EXAMPLES)).startswith(EXCLUDED_FOLDERS)
                  and not uses_excluded_feature(s)]
    probe = argparse.Namespace(res="80x60", spp=1, timeout=60)
    complete = []
    with tempfile.TemporaryDirectory() as scratch:
        for scene in candidates:
            row = sweep.run_scene(filmback, scene, probe, Path(scratch))
            if row["status"] == "ok" and row["geometry"] == "complete":
                complete.append(str(scene.relative_to(sweep.EXAMPLES)))
    print("%d candidates, %d render complete" % (len(candidates), len(complete)), file=sys.stderr)
    return [complete[round(i * len(complete) / count)] for i in range(min(count, len(complete)))]


def read_rgb(image_file):
    """The first three channels of `image_file` as an H x W x 3 float array."""
    image = oiio.ImageInput.open(str(image_file))
    if image is None:
        sys.exit(f"{image_file}: {oiio.geterror()}")
    pixels = image.read_image(0, 3, "float")
    image.close()
    return pixels


def timed(command, cwd, log):
    """Wall-clock seconds of `command`; on failure exits naming it and its log."""
    start = time.monotonic()
    with open(log, "w", encoding="utf-8") as out:
        r = subprocess.run([str(c) for c in command], cwd=cwd, stdout=out,
                           stderr=subprocess.STDOUT, timeout=TIMEOUT_S)
    seconds = time.monotonic() - start
    if r.returncode != 0:
        sys.exit(f"{' '.join(map(str, command))} failed ({r.returncode}), see {log}:\n"
                 + Path(log).read_text(encoding="utf-8", errors="replace")[-2000:])
    return seconds


def differences(ours, theirs):
    """(mean relative difference, 95th-percentile pixel difference), as the docstring defines."""
    ours = np.clip(ours, 0, 1)
    lit = (theirs > LIT_LOW) & (theirs < LIT_HIGH)
    mean = float(np.mean(np.abs(ours[lit] - theirs[lit]) / theirs[lit])) if lit.any() else 0.0
    per_pixel = np.max(np.abs(ours - theirs) / np.maximum(theirs, PIXEL_FLOOR), axis=-1)
    return mean, float(np.percentile(per_pixel, 95))


def measure(filmback, scene, work, args):
    pov = sweep.EXAMPLES / scene
    work.mkdir(parents=True, exist_ok=True)
    width, height = args.res.split("x")
    povray_s = timed(["povray", f"+W{width}", f"+H{height}", "-D", "-A", "+FN16",
                      "File_Gamma=1.0", f"+L{pov.parent}", f"+I{pov}", "+Opovray.png"],
                     work, work / "povray.log")
    spp = AREA_LIGHT_SPP if "area_light" in pov.read_text(errors="replace") else 1
    filmback_s = timed([filmback, "render", pov, "-o", work / "filmback.exr", "--res", args.res,
                        "--spp", spp, "--seed", 1, "--filter", "box:radius=0.001",
                        "--integrator", "povray", "-q"], pov.parent, work / "filmback.log")
    theirs = read_rgb(work / "povray.png")
    legacy = LEGACY_LOG in (work / "povray.log").read_text(errors="replace")
    if legacy:
        theirs = theirs ** LEGACY_GAMMA
    ours = read_rgb(work / "filmback.exr")
    if ours.shape != theirs.shape:
        sys.exit(f"{scene}: filmback's image is {ours.shape}, POV-Ray's {theirs.shape}")
    mean, p95 = differences(ours, theirs)
    return mean, p95, spp, legacy, filmback_s, povray_s


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--filmback", required=True)
    parser.add_argument("--out", type=Path, default=Path("."))
    parser.add_argument("--res", default="160x120")
    parser.add_argument("--check", action="store_true", help="exit 1 when a scene fails")
    parser.add_argument("--choose", action="store_true", help="print the scenes the rule picks")
    parser.add_argument("scenes", nargs="*", default=list(SCENES))
    args = parser.parse_args()
    filmback = os.path.abspath(args.filmback)
    if not sweep.EXAMPLES.is_dir():
        print(f"skipped: no {sweep.EXAMPLES} (Debian package povray-examples)")
        return SKIP
    if args.choose:
        print("\n".join(choose(filmback)))
        return 0
    if shutil.which("povray") is None:
        print("skipped: no povray on PATH (Debian package povray)")
        return SKIP

    load_before = os.getloadavg()[0]
    rows, failed = [], []
    for scene in args.scenes:
        load = os.getloadavg()[0]
        mean, p95, spp, legacy, filmback_s, povray_s = measure(filmback, scene,
                                                       args.out / Path(scene).stem, args)
        passed = mean <= MOST_MEAN_RELATIVE and p95 <= MOST_P95_PIXEL
        if not passed:
            failed.append(scene)
        rows.append(f"| {scene}{' (legacy)' if legacy else ''} | {100 * mean:.2f} % | "
                    f"{100 * p95:.1f} % | {spp} | "
                    f"{filmback_s:.2f} | {povray_s:.2f} | {load:.1f} | "
                    f"{'yes' if passed else '**no**'} |")
        print(rows[-1], flush=True)
    return peer_table.report(
        args.out / "integrator_vs_povray.md", f"{args.res}; {peer_table.machine(load_before)}",
        ["scene", "mean relative difference", "95th-percentile pixel", "filmback spp",
         "filmback s", "POV-Ray s", "load", "passes"], rows, failed, args.check,
        ["", f"{len(args.scenes) - len(failed)} of {len(args.scenes)} pass (mean <= 3 %, "
         "95th percentile <= 10 %)."])


if __name__ == "__main__":
    sys.exit(main())
