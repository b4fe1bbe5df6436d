"""A benchmark shot for `filmback bench` (scenes/bench/README.md): a glossy room lit by small lamps.

Floor, two walls and a ceiling open towards the camera, as in interior.py, but the floor and the
back wall are glossy (roughness 0.12 and 0.2); on the floor a mirror-like sphere (roughness
0.03), a polished metal cylinder (0.08), a rough metal cylinder (0.4) and a matte box. Sixteen
small lamps of different sizes and powers light it and nothing else but a very dim world: a row
of eight 2 cm bulbs of 4 W along the back wall, four point lamps of radius 1, 3, 5 and 10 cm
(8 to 60 W), two spot lights of radius 2 cm, and two small area lights. Their highlights on the
glossy surfaces are reached mostly by light sampling, and from each point only a few of the
lamps matter: the shot for a light sampler that finds small and many lights (issue 17, goal 1).
Cycles is set to estimate what filmback's path integrator estimates, as in sunlit_objects.py.

Builds the shot in the current (empty) Blender file:

    blender -b --factory-startup --python scenes/bench/glossy_interior.py
"""

import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import interior  # noqa: E402  (wall)
import sunlit_objects as common  # noqa: E402  (materials, world, Cycles settings, look_at)


def lamp(name, kind, energy_w, location, colour=(1.0, 0.9, 0.75), radius_m=None, rotation=None,
         **settings):
    light = bpy.data.lights.new(name, kind)
    light.energy, light.color = energy_w, colour
    if radius_m is not None:
        light.shadow_soft_size = radius_m
    for key, value in settings.items():
        setattr(light, key, value)
    obj = bpy.data.objects.new(name, light)
    bpy.context.scene.collection.objects.link(obj)
    obj.location = location
    if rotation is not None:
        obj.rotation_euler = rotation


def dim_room(scene, floor, back_wall=None):
    """interior.py's room and camera under an almost black world, Cycles set as filmback: the
    floor and back wall of the given materials (the back wall plaster if None), the rest plaster."""
    common.cycles_like_filmback(scene)
    common.world(scene, (0.5, 0.5, 0.5), 0.01)
    plaster = common.principled("Plaster", (0.75, 0.72, 0.66), 0.9)
    interior.wall("Floor", (6.0, 6.0), (0, 0, 0), (0, 0, 0), floor)
    interior.wall("Ceiling", (6.0, 6.0), (0, 0, 2.8), (math.pi, 0, 0), plaster)
    interior.wall("BackWall", (6.0, 2.8), (0, 3.0, 1.4), (math.pi / 2, 0, 0), back_wall or plaster)
    interior.wall("LeftWall", (6.0, 2.8), (-3.0, 0, 1.4), (math.pi / 2, 0, math.pi / 2), plaster)
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = 24.0
    scene.collection.objects.link(camera)
    common.look_at(camera, (1.8, -3.2, 1.6), (-0.4, 1.6, 0.8))
    scene.camera = camera


def build():
    scene = bpy.context.scene
    dim_room(scene, common.principled("GlossyFloor", (0.30, 0.18, 0.10), 0.12),
             common.principled("Tiles", (0.55, 0.60, 0.62), 0.2))

    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=0.45,
                                         location=(-0.9, 1.0, 0.45))
    bpy.ops.object.shade_smooth()
    bpy.context.object.data.materials.append(common.principled("Mirror", (0.8, 0.8, 0.8), 0.03,
                                                               1.0))
    bpy.ops.mesh.primitive_cylinder_add(vertices=64, radius=0.3, depth=1.1,
                                        location=(0.6, 1.6, 0.55))
    bpy.ops.object.shade_smooth()
    bpy.context.object.data.materials.append(
        common.principled("Chrome", (0.8, 0.8, 0.82), 0.08, 1.0))
    bpy.ops.mesh.primitive_cylinder_add(vertices=64, radius=0.2, depth=0.6,
                                        location=(-0.2, 0.0, 0.3))
    bpy.ops.object.shade_smooth()
    bpy.context.object.data.materials.append(
        common.principled("Brass", (0.9, 0.7, 0.35), 0.4, 1.0))
    bpy.ops.mesh.primitive_cube_add(size=0.7, location=(1.5, 0.3, 0.35),
                                    rotation=(0, 0, math.radians(25.0)))
    bpy.context.object.data.materials.append(common.principled("Box", (0.6, 0.55, 0.2), 0.7))

    for i in range(8):  # a row of bulbs along the back wall
        lamp(f"Bulb{i}", "POINT", 4.0, (-2.6 + 0.7 * i, 2.85, 2.3), radius_m=0.02)
    for name, radius_m, energy_w, location, colour in (
            ("Tiny", 0.01, 8.0, (-2.6, 0.2, 0.9), (1.0, 0.8, 0.55)),
            ("Small", 0.03, 15.0, (2.2, 2.4, 1.2), (0.8, 0.9, 1.0)),
            ("Medium", 0.05, 30.0, (-1.8, -1.2, 2.2), (1.0, 0.95, 0.9)),
            ("Large", 0.10, 60.0, (1.2, -0.8, 2.5), (1.0, 0.85, 0.7))):
        lamp(name, "POINT", energy_w, location, colour, radius_m=radius_m)
    for i, (x, y) in enumerate(((-1.2, 1.8), (1.0, 1.0))):  # spots from the ceiling, down
        lamp(f"Spot{i}", "SPOT", 80.0, (x, y, 2.7), radius_m=0.02,
             spot_size=math.radians(40.0), spot_blend=0.3)
    lamp("Panel", "AREA", 20.0, (0.4, 2.2, 2.75), shape="SQUARE", size=0.25)
    lamp("Strip", "AREA", 15.0, (-2.9, 1.0, 1.6), shape="RECTANGLE", size=0.4, size_y=0.1,
         rotation=(0, -math.pi / 2, 0))  # shines along +X


if __name__ == "__main__":
    build()
