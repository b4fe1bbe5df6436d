"""The Blender side of the look shot test (tests/blender/blender_look_test.cpp, BlenderLookShot).

Builds radiometry_shot.py's diffuse-only shot SHOT (the renderers agree there at the noise floor)
with Blender's Filmic view, a look, an exposure and the default dither (VIEW), exports it through
filmback's add-on, which carries those settings, and renders it once with Cycles:

    blender -b --factory-startup --python look_shot.py -- OUTDIR SHOT

writes OUTDIR/shot.gltf, OUTDIR/manifest.txt, OUTDIR/cycles.png (the 8-bit PNG Blender writes for
a render, `render.render(write_still=True)`) and OUTDIR/cycles.exr (the same render result,
scene-linear float). SAMPLES is lower than the radiometry test's: the test compares the PNGs only
where the linear images agree, so noise thins the pixels compared, not the comparison.
"""

import dataclasses
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import look_transform  # noqa: E402  (Blender runs this file as __main__, so import by path)
import radiometry_shot  # noqa: E402

VIEW = {"view_transform": "Filmic", "look": "Medium High Contrast", "exposure": 0.5, "gamma": 1.0}
DITHER = 1.0  # Blender's default
SAMPLES = 256


def set_view(scene):
    scene.display_settings.display_device = "sRGB"
    for key, value in VIEW.items():
        setattr(scene.view_settings, key, value)
    scene.render.dither_intensity = DITHER


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 2 or args[1] not in radiometry_shot.SHOTS:
        raise SystemExit("usage: blender -b --factory-startup --python look_shot.py -- OUTDIR SHOT"
                         "\nshots: " + " ".join(radiometry_shot.SHOTS))
    out_dir, name = os.path.abspath(args[0]), args[1]
    shot = dataclasses.replace(radiometry_shot.SHOTS[name], samples=SAMPLES)
    scene = radiometry_shot.build(out_dir, name, shot, before_export=set_view)
    look_transform.render_png_and_exr(scene, os.path.join(out_dir, "cycles.png"),
                                      os.path.join(out_dir, "cycles.exr"))


if __name__ == "__main__":
    main()
