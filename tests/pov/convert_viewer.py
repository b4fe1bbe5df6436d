#!/usr/bin/python3
"""Converted POV-Ray scenes as another glTF viewer sees them (docs/pov.md "Conversion", issue 19):
each sample scene is converted with `filmback convert`, imported into Blender with its own glTF
importer and rendered by Cycles (convert_viewer_shot.py), and compared with filmback's render of
the .pov at the same size:

  brightness  the mean over all pixels of the linear luminance Y = 0.2126 R + 0.7152 G + 0.0722 B
              (scene-linear EXR of each renderer); ratio = Cycles' mean / filmback's mean;
  silhouette  the pixels whose depth pass (filmback's `aov:show=depth`, box filter; Cycles' Depth
              pass) is below 5e9 m: more than half the pixel sees geometry, both renderers giving
              escaping rays 1e10 m; overlap = |A and B| / |A or B| (intersection over union).

A scene passes when |ratio - 1| <= 0.25 and overlap >= 0.95.

    convert_viewer.py --filmback EXE --out DIR [--res WxH] [--spp N] [--check] [SCENE...]

SCENE is a path under Debian's povray-examples (default: the ten of SCENES). Writes
DIR/convert_viewer.md, the table with the machine and its load. --check exits 1 when a scene
misses; exit 77 (CTest's skip) when Blender or povray-examples is missing.
"""

import argparse
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

import peer_table

HERE = Path(__file__).resolve().parent
EXAMPLES = Path("/usr/share/doc/povray/examples")
SKIP = 77
MOST_RATIO_OFF = 0.25
LEAST_OVERLAP = 0.95
BACKGROUND_DEPTH_M = 5e9  # half of the 1e10 m both renderers give escaping rays

# Ten sample scenes whose features filmback renders completely (docs/pov.md "Sample scenes": no
# unsupported object or function), chosen for their lights: point, spot, parallel, area, fading.
SCENES = (
    "lights/spotlite.pov",          # three spotlights
    "lights/arealit1.pov",          # area spotlights
    "lights/shadows.pov",           # an area light
    "lights/parallel_lights.pov",   # parallel lights
    "lights/fillite.pov",           # a shadowless fill light
    "lights/laser.pov",             # spotlights with fade_distance/fade_power
    "interior/ballbox1.pov",        # three point lights, glass
    "objects/csg/cliptst2.pov",     # CSG with clipped_by
    "language/macros/macro1.pov",   # one point light, many spheres
    "textures/pigments/pigmap.pov", # pigment maps
)


def blender_env():
    """Without pyenv's or a venv's interpreter on PATH: Blender's Python takes its home from the
    first python3 there, and such an interpreter hides Debian's numpy from it (tests/blender)."""
    venv = os.path.realpath(os.path.join(sys.prefix, "bin")) if sys.prefix != sys.base_prefix else None
    path = [p for p in os.environ.get("PATH", "").split(os.pathsep)
            if p and os.path.realpath(p) != venv and ".pyenv" not in p]
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONHOME", "PYTHONPATH")}
    env["PATH"] = os.pathsep.join(path)
    return env


def run(command, cwd, log):
    """Runs `command`; on failure exits naming it and its log."""
    with open(log, "w", encoding="utf-8") as out:
        r = subprocess.run(command, cwd=cwd, stdout=out, stderr=subprocess.STDOUT, timeout=600,
                           env=blender_env() if command[0] == "blender" else None)
    if r.returncode != 0:
        sys.exit(f"{' '.join(map(str, command))} failed ({r.returncode}), see {log}:\n"
                 + Path(log).read_text(encoding="utf-8")[-2000:])


def channels(exr, names):
    """The named channels of `exr` as an H x W x len(names) float array."""
    image = oiio.ImageInput.open(str(exr))
    if image is None:
        sys.exit(f"{exr}: {oiio.geterror()}")
    spec = image.spec()
    pixels = image.read_image(0, spec.nchannels, "float")
    image.close()
    found = list(spec.channelnames)
    missing = [n for n in names if n not in found]
    if missing:
        sys.exit(f"{exr}: no channel {missing[0]} (channels: {', '.join(found)})")
    return np.stack([pixels[:, :, found.index(n)] for n in names], axis=-1)


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def measure(filmback, scene, work, args):
    """(filmback mean, Cycles mean, overlap, filmback s, Cycles s) for one sample scene."""
    pov = EXAMPLES / scene
    work.mkdir(parents=True, exist_ok=True)
    gltf = work / "scene.gltf"
    width, height = args.res.split("x")
    run([filmback, "convert", pov, gltf, "--res", args.res], pov.parent, work / "convert.log")
    start = time.monotonic()
    run([filmback, "render", pov, "-o", work / "filmback.exr", "--res", args.res, "--spp",
         str(args.spp), "--seed", "1", "-q"], pov.parent, work / "filmback.log")
    filmback_s = time.monotonic() - start
    run([filmback, "render", pov, "-o", work / "filmback_depth.exr", "--res", args.res, "--spp",
         "16", "--filter", "box", "--integrator", "aov:show=depth", "-q"], pov.parent,
        work / "filmback_depth.log")
    start = time.monotonic()
    run(["blender", "-b", "--factory-startup", "--python", HERE / "convert_viewer_shot.py", "--",
         gltf, work / "cycles.exr", width, height, str(args.spp)], work, work / "cycles.log")
    cycles_s = time.monotonic() - start

    ours = luminance(channels(work / "filmback.exr", ["R", "G", "B"])).mean()
    cycles = channels(work / "cycles.exr", ["ViewLayer.Combined.R", "ViewLayer.Combined.G",
                                             "ViewLayer.Combined.B", "ViewLayer.Depth.Z"])
    theirs = luminance(cycles[:, :, :3]).mean()
    a = channels(work / "filmback_depth.exr", ["Z"])[:, :, 0] < BACKGROUND_DEPTH_M
    b = cycles[:, :, 3] < BACKGROUND_DEPTH_M
    union = np.count_nonzero(a | b)
    overlap = np.count_nonzero(a & b) / union if union else 1.0
    return ours, theirs, overlap, filmback_s, cycles_s


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--filmback", required=True)
    parser.add_argument("--out", type=Path, required=True)
    parser.add_argument("--res", default="320x240")
    parser.add_argument("--spp", type=int, default=64, help="for both renderers")
    parser.add_argument("--check", action="store_true", help="exit 1 when a scene misses")
    parser.add_argument("scenes", nargs="*", default=list(SCENES))
    args = parser.parse_args()
    if shutil.which("blender") is None:
        print("skipped: no blender on PATH (Debian package blender)")
        return SKIP
    if not EXAMPLES.is_dir():
        print(f"skipped: no {EXAMPLES} (Debian package povray-examples)")
        return SKIP

    load_before = os.getloadavg()[0]
    rows, missed = [], []
    for scene in args.scenes:
        ours, theirs, overlap, filmback_s, cycles_s = measure(
            os.path.abspath(args.filmback), scene, args.out / Path(scene).stem, args)
        ratio = theirs / ours if ours > 0 else float("inf")
        passed = abs(ratio - 1) <= MOST_RATIO_OFF and overlap >= LEAST_OVERLAP
        if not passed:
            missed.append(scene)
        rows.append(f"| {scene} | {ours:.4f} | {theirs:.4f} | {ratio:.3f} | {overlap:.3f} | "
                    f"{filmback_s:.1f} | {cycles_s:.1f} | {'yes' if passed else '**no**'} |")
        print(rows[-1], flush=True)
    return peer_table.report(
        args.out / "convert_viewer.md",
        f"{args.res}, {args.spp} spp in both; {peer_table.machine(load_before)}",
        ["scene", "filmback mean", "Cycles mean", "ratio", "overlap", "filmback s", "Blender s",
         "passes"], rows, missed, args.check)


if __name__ == "__main__":
    sys.exit(main())
