"""A benchmark shot for `filmback bench` (scenes/bench/README.md): strong defocus through a thin lens.

A 50 mm lens at f/1.4 focused at 3.8 m on the fourth one of a row of matte and glossy spheres
receding from 2 m to 13 m from the camera along a ground; small bright metal spheres far behind, whose sun
highlights blur into wide bokeh discs that only a few lens samples reach. Lit by a 2-degree sun and
a blue sky world. The lens integral dominates the noise: most pixels are out of focus. Cycles is
set to estimate what filmback's path integrator estimates, as in sunlit_objects.py.

Builds the shot in the current (empty) Blender file:

    blender -b --factory-startup --python scenes/bench/depth_of_field.py
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sunlit_objects as common  # noqa: E402  (materials, world, Cycles settings, look_at)


def sphere(location, radius, material):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=radius,
                                         location=location)
    bpy.ops.object.shade_smooth()
    bpy.context.object.data.materials.append(material)


def build():
    scene = bpy.context.scene
    common.cycles_like_filmback(scene)
    common.world(scene, (0.45, 0.6, 0.9), 0.6)

    bpy.ops.mesh.primitive_plane_add(size=60.0, location=(0, 0, 0))
    bpy.context.object.data.materials.append(common.principled("Ground", (0.5, 0.48, 0.45), 0.8))

    matte = common.principled("Matte", (0.7, 0.25, 0.2), 0.7)
    glossy = common.principled("Glossy", (0.2, 0.35, 0.7), 0.1)
    # Along the view: 2 m to 13 m from the camera, alternating matte and glossy.
    for i, distance in enumerate((1.2, 1.8, 2.4, 3.0, 4.5, 6.5, 9.0, 12.0)):
        x = 0.35 * (-1) ** i
        sphere((x, distance, 0.25), 0.25, glossy if i % 2 else matte)
    chrome = common.principled("Chrome", (0.95, 0.93, 0.9), 0.02, 1.0)
    for x in (-2.0, -1.2, 0.9, 1.7):  # far behind: their highlights become bokeh
        sphere((x, 16.0, 0.6), 0.12, chrome)

    sun = bpy.data.lights.new("Sun", "SUN")
    sun.energy, sun.angle = 3.0, math.radians(2.0)
    sun_object = bpy.data.objects.new("Sun", sun)
    scene.collection.objects.link(sun_object)
    sun_object.rotation_euler = (math.radians(55.0), 0.0, math.radians(160.0))

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = 50.0
    camera.data.dof.use_dof = True
    camera.data.dof.focus_distance = 3.8
    camera.data.dof.aperture_fstop = 1.4
    scene.collection.objects.link(camera)
    common.look_at(camera, (0.0, -0.8, 0.45), (0.0, 3.0, 0.25))
    scene.camera = camera


if __name__ == "__main__":
    build()
