"""A benchmark shot for `filmback bench` (scenes/bench/README.md): objects moving under an open shutter.

A glossy sphere crossing the view (1.6 m in one frame) and a matte cube spinning half a turn in
one frame, in front of a back wall, on a ground; the shutter is open for the whole frame (Cycles'
Motion Blur, shutter 1.0, centred on frame 1). Lit by a 1 x 1 m area light and a dim world. The
time integral dominates the noise along the streaks. Cycles is set to estimate what filmback's
path integrator estimates, as in sunlit_objects.py.

Builds the shot in the current (empty) Blender file:

    blender -b --factory-startup --python scenes/bench/motion_blur.py
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sunlit_objects as common  # noqa: E402  (materials, world, Cycles settings, look_at)


def keyed(obj, path, frames_values):
    """Linear keys of `path` at (frame, value) pairs, so the motion is uniform in the shutter."""
    for frame, value in frames_values:
        setattr(obj, path, value)
        obj.keyframe_insert(data_path=path, frame=frame)
    for curve in obj.animation_data.action.fcurves:
        for key in curve.keyframe_points:
            key.interpolation = "LINEAR"


def build():
    scene = bpy.context.scene
    common.cycles_like_filmback(scene)
    common.world(scene, (0.5, 0.5, 0.5), 0.2)
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = 1.0
    scene.frame_start, scene.frame_end = 0, 2
    scene.frame_set(1)

    bpy.ops.mesh.primitive_plane_add(size=20.0, location=(0, 0, 0))
    bpy.context.object.data.materials.append(common.principled("Ground", (0.55, 0.5, 0.45), 0.8))
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0, 3.0, 1.5), rotation=(math.pi / 2, 0, 0))
    back = bpy.context.object
    back.scale = (8.0, 3.0, 1.0)
    back.data.materials.append(common.principled("Wall", (0.7, 0.7, 0.68), 0.9))

    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=0.35,
                                         location=(0, 1.0, 0.35))
    bpy.ops.object.shade_smooth()
    ball = bpy.context.object
    ball.data.materials.append(common.principled("Ball", (0.8, 0.15, 0.1), 0.15))
    keyed(ball, "location", [(0, (-2.4, 1.0, 0.35)), (2, (0.8, 1.0, 0.35))])

    bpy.ops.mesh.primitive_cube_add(size=0.6, location=(1.2, 1.8, 0.3))
    cube = bpy.context.object
    cube.data.materials.append(common.principled("Cube", (0.2, 0.5, 0.25), 0.6))
    keyed(cube, "rotation_euler", [(0, (0, 0, 0)), (2, (0, 0, math.pi))])

    area = bpy.data.lights.new("Panel", "AREA")
    area.shape, area.size = "SQUARE", 1.0
    area.energy = 150.0
    panel = bpy.data.objects.new("Panel", area)
    scene.collection.objects.link(panel)
    common.look_at(panel, (1.5, -0.5, 2.6), (0.0, 1.5, 0.3))

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = 32.0
    scene.collection.objects.link(camera)
    common.look_at(camera, (0.0, -3.0, 1.3), (0.0, 1.5, 0.5))
    scene.camera = camera


if __name__ == "__main__":
    build()
