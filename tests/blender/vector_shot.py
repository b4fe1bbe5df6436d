"""The Blender side of vector_test.py:

    blender -b --factory-startup --python vector_shot.py -- OUTDIR

builds a shot where everything moves at constant speed (linear keyframes, motion blur off): a
perspective camera travelling sideways, a plane ("Slide") sliding across the image and another
("Turn") turning about the view axis, so that its vectors vary across it. It exports the shot
through filmback's add-on to OUTDIR/shot.gltf (its frame and fps in the FILMBACK_blender
extension) and renders it with Cycles at FRAME, its Vector and Z passes on, to OUTDIR/cycles.exr
(multi-layer, 32-bit float).
"""

import math
import os
import sys
from types import SimpleNamespace

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_shot  # noqa: E402  (Cycles' settings and the add-on's export)

WIDTH_PX, HEIGHT_PX = 64, 48
SAMPLES = 16
FPS = 24
FRAME = 10
KEY_FRAMES = (1, 20)


def keyed_linearly(thing, path, at_frame, per_frame):
    """Keys `path` of `thing` at KEY_FRAMES so that it passes `at_frame` at FRAME and changes by
    `per_frame` every frame, LINEAR, so that Blender's motion and the exporter's per-frame samples
    agree exactly."""
    for key in KEY_FRAMES:
        setattr(thing, path, [a + d * (key - FRAME) for a, d in zip(at_frame, per_frame)])
        thing.keyframe_insert(path, frame=key)
    for curve in thing.animation_data.action.fcurves:
        for point in curve.keyframe_points:
            point.interpolation = "LINEAR"


def main():
    out_dir = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
    os.makedirs(out_dir, exist_ok=True)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    make_shot.configure_cycles(scene, SimpleNamespace(width_px=WIDTH_PX, height_px=HEIGHT_PX,
                                                      samples=SAMPLES))
    scene.render.use_motion_blur = False  # Cycles writes no Vector pass with it on
    scene.render.fps, scene.render.fps_base = FPS, 1.0
    scene.frame_start, scene.frame_end = KEY_FRAMES

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    keyed_linearly(camera, "location", (0.0, 0.0, 8.0), (0.04, 0.0, 0.0))  # looking down -z
    for name, centre, velocity, turn_deg in [("Slide", (-1.3, 0.4, 0.0), (0.06, 0.035, 0.0), 0.0),
                                             ("Turn", (1.2, -0.3, 0.8), (0.0, 0.0, 0.0), 3.0)]:
        bpy.ops.mesh.primitive_plane_add(size=1.6, location=centre)
        plane = bpy.context.object
        plane.name = name
        keyed_linearly(plane, "location", centre, velocity)
        if turn_deg:
            keyed_linearly(plane, "rotation_euler", (0.0, 0.0, 0.0),
                           (0.0, 0.0, math.radians(turn_deg)))
    view_layer = scene.view_layers[0]
    view_layer.use_pass_vector = True
    view_layer.use_pass_z = True
    scene.frame_set(FRAME)
    bpy.context.view_layer.update()

    make_shot.export(os.path.join(out_dir, "shot.gltf"))
    scene.frame_set(FRAME)
    image = scene.render.image_settings
    image.file_format = "OPEN_EXR_MULTILAYER"
    image.color_depth = "32"
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main()
