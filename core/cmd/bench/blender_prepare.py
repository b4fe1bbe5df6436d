"""`filmback bench`: prepares a Blender shot for both renderers (docs/cli.md, "bench").

    blender -b --factory-startup [SHOT.blend] --python blender_prepare.py -- \
        SOURCE WORKDIR WxH|shot THREADS

SOURCE is the .blend Blender opened, or a bpy script that builds the shot in the empty file it
runs in (run as __main__). Sets what the benchmark needs and nothing else: the resolution (at
100 %; "shot" keeps the shot's), Cycles on the CPU with THREADS threads (0: all), adaptive
sampling (cycles_render.py sets it per render), denoising and the time limit off. Light paths, clamping, the pixel filter and the
sampling pattern stay the shot's, and are written as one line to WORKDIR/cycles_settings.txt for
the report. Saves WORKDIR/shot.blend (what Cycles renders) and exports WORKDIR/shot.gltf through
filmback's add-on (what filmback renders).
"""

import os
import runpy
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
# The add-on and its export entry, installed beside this folder (share/filmback/blender).
sys.path.insert(0, os.path.normpath(os.path.join(HERE, "..", "blender")))
import export_shot  # noqa: E402


def configure(scene, size, threads):
    render = scene.render
    if size != "shot":
        width, height = (int(v) for v in size.split("x"))
        render.resolution_x, render.resolution_y = width, height
        render.resolution_percentage = 100
    render.engine = "CYCLES"
    render.threads_mode = "FIXED" if threads > 0 else "AUTO"
    if threads > 0:
        render.threads = threads
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.time_limit = 0.0
    cycles.use_animated_seed = False


def settings_line(scene):
    c = scene.cycles
    r = scene.render
    return (f"Cycles {bpy.app.version_string}, CPU, {r.resolution_x}x{r.resolution_y} at "
            f"{r.resolution_percentage} %, pattern {c.sampling_pattern}, filter "
            f"{c.pixel_filter_type} {c.filter_width:g} px, bounces max {c.max_bounces} (diffuse "
            f"{c.diffuse_bounces}, glossy {c.glossy_bounces}, transmission "
            f"{c.transmission_bounces}), clamp direct {c.sample_clamp_direct:g} indirect "
            f"{c.sample_clamp_indirect:g}, filter glossy {c.blur_glossy:g}, light threshold "
            f"{c.light_sampling_threshold:g}, caustics reflective {c.caustics_reflective} "
            f"refractive {c.caustics_refractive}, adaptive sampling as each render sets it (bench --adaptive), "
            f"denoising off")


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 4:
        raise SystemExit("usage: blender -b --factory-startup [SHOT.blend] --python "
                         "blender_prepare.py -- SOURCE WORKDIR WxH|shot THREADS")
    source, work, size, threads = args[0], args[1], args[2], int(args[3])
    if source.endswith(".py"):
        bpy.ops.wm.read_factory_settings(use_empty=True)
        runpy.run_path(source, run_name="__main__")
    scene = bpy.context.scene
    configure(scene, size, threads)
    bpy.context.view_layer.update()
    with open(os.path.join(work, "cycles_settings.txt"), "w") as f:
        f.write(settings_line(scene) + "\n")
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(work, "shot.blend"), copy=True)
    export_shot.export(os.path.join(work, "shot.gltf"))


if __name__ == "__main__":
    main()
