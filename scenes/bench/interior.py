"""A benchmark shot for `filmback bench` (scenes/bench/README.md): a room lit by an area light.

Floor, two walls and a ceiling open towards the camera; on the floor a glossy dielectric sphere,
a rough metal cylinder and a matte box; lit by a 1.2 x 0.6 m area light under the ceiling and a
small warm point light (radius 5 cm) in a corner, and a dim grey world through the open sides.
Most of the light arrives after one or more diffuse bounces, and each sample lights its point
with one of the two lights, so this shot converges slowly. Cycles is set to estimate what
filmback's path integrator estimates, as in sunlit_objects.py.

Builds the shot in the current (empty) Blender file:

    blender -b --factory-startup --python scenes/bench/interior.py
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sunlit_objects as common  # noqa: E402  (materials, world, Cycles settings, look_at)


def wall(name, size, location, rotation, material):
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=location, rotation=rotation)
    plane = bpy.context.object
    plane.name = name
    plane.scale = (*size, 1.0)
    plane.data.materials.append(material)


def build():
    scene = bpy.context.scene
    common.cycles_like_filmback(scene)
    common.world(scene, (0.5, 0.5, 0.5), 0.15)

    plaster = common.principled("Plaster", (0.75, 0.72, 0.66), 0.9)
    wood = common.principled("Floor", (0.42, 0.27, 0.15), 0.45)
    wall("Floor", (6.0, 6.0), (0, 0, 0), (0, 0, 0), wood)
    wall("Ceiling", (6.0, 6.0), (0, 0, 2.8), (math.pi, 0, 0), plaster)
    wall("BackWall", (6.0, 2.8), (0, 3.0, 1.4), (math.pi / 2, 0, 0), plaster)
    wall("LeftWall", (6.0, 2.8), (-3.0, 0, 1.4), (math.pi / 2, 0, math.pi / 2), plaster)

    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=0.45,
                                         location=(-0.9, 1.0, 0.45))
    bpy.ops.object.shade_smooth()
    bpy.context.object.data.materials.append(common.principled("Glaze", (0.1, 0.3, 0.6), 0.05))

    bpy.ops.mesh.primitive_cylinder_add(vertices=64, radius=0.3, depth=1.1,
                                        location=(0.6, 1.6, 0.55))
    bpy.context.object.data.materials.append(
        common.principled("Steel", (0.8, 0.8, 0.82), 0.35, 1.0))

    bpy.ops.mesh.primitive_cube_add(size=0.7, location=(1.5, 0.3, 0.35),
                                    rotation=(0, 0, math.radians(25.0)))
    bpy.context.object.data.materials.append(common.principled("Box", (0.6, 0.55, 0.2), 0.7))

    area = bpy.data.lights.new("Panel", "AREA")
    area.shape, area.size, area.size_y = "RECTANGLE", 1.2, 0.6
    area.energy = 60.0
    area.color = (1.0, 0.97, 0.92)
    panel = bpy.data.objects.new("Panel", area)
    scene.collection.objects.link(panel)
    panel.location = (-0.5, 1.0, 2.75)  # facing down: a light shines along its -Z

    point = bpy.data.lights.new("Lamp", "POINT")
    point.energy, point.shadow_soft_size, point.color = 40.0, 0.05, (1.0, 0.8, 0.55)
    lamp = bpy.data.objects.new("Lamp", point)
    scene.collection.objects.link(lamp)
    lamp.location = (-2.5, 2.5, 1.8)

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = 24.0
    scene.collection.objects.link(camera)
    common.look_at(camera, (1.8, -3.2, 1.6), (-0.4, 1.6, 0.8))
    scene.camera = camera


if __name__ == "__main__":
    build()
