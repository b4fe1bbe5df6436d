"""`filmback bench`: one Cycles render of a prepared shot (blender_prepare.py).

    blender -b --factory-startup WORKDIR/shot.blend --python cycles_render.py -- \
        OUT.exr SPP SEED [ADAPTIVE_THRESHOLD]

Renders at SPP samples with Cycles' seed SEED, with Cycles' adaptive sampling at
ADAPTIVE_THRESHOLD (0 or none: off; its minimum samples automatic, as Blender's default), and writes OUT.exr (32-bit float, scene-linear RGB)
and OUT.exr.render_s: the seconds bpy.ops.render.render() took (Cycles' scene sync, BVH build and
sampling; not Blender's start, loading the file or writing the image).
"""

import sys
import time

import bpy


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) not in (3, 4):
        raise SystemExit("usage: blender -b --factory-startup shot.blend --python "
                         "cycles_render.py -- OUT.exr SPP SEED [ADAPTIVE_THRESHOLD]")
    out, spp, seed = args[0], int(args[1]), int(args[2])
    threshold = float(args[3]) if len(args) == 4 else 0.0
    scene = bpy.context.scene
    scene.cycles.samples = spp
    scene.cycles.seed = seed
    scene.cycles.use_adaptive_sampling = threshold > 0
    scene.cycles.adaptive_threshold = threshold
    scene.cycles.adaptive_min_samples = 0
    image = scene.render.image_settings
    image.file_format = "OPEN_EXR"
    image.color_depth = "32"
    image.color_mode = "RGB"
    image.exr_codec = "ZIP"
    start = time.perf_counter()
    bpy.ops.render.render()
    seconds = time.perf_counter() - start
    bpy.data.images["Render Result"].save_render(out, scene=scene)
    with open(out + ".render_s", "w") as f:
        f.write(f"{seconds:.6f}\n")


if __name__ == "__main__":
    main()
