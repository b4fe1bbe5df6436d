"""A benchmark shot for `filmback bench` (scenes/bench/README.md): a room under 64 small lamps.

The room of interior.py (floor, two walls, ceiling, open towards the camera) with a rough glossy
floor (roughness 0.3), a glossy sphere (0.1) and a matte box, lit by 64 point lamps hung at
random (a fixed seed) between 0.4 and 2.6 m: half of them points, half spheres of 1 to 4 cm,
of 0.5 to 50 W (two decades, uniform in the logarithm), and a very dim world. From any point a
few nearby lamps bring most of the light: the shot for a light sampler that finds many lights.

Builds the shot in the current (empty) Blender file:

    blender -b --factory-startup --python scenes/bench/many_lamps.py
"""

import math
import os
import random
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import glossy_interior  # noqa: E402  (dim_room)
import sunlit_objects as common  # noqa: E402  (materials, world, Cycles settings, look_at)


def build():
    scene = bpy.context.scene
    glossy_interior.dim_room(scene, common.principled("Floor", (0.42, 0.27, 0.15), 0.3))

    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=0.45,
                                         location=(-0.9, 1.0, 0.45))
    bpy.ops.object.shade_smooth()
    bpy.context.object.data.materials.append(common.principled("Glaze", (0.1, 0.3, 0.6), 0.1))
    bpy.ops.mesh.primitive_cube_add(size=0.7, location=(1.5, 0.3, 0.35),
                                    rotation=(0, 0, math.radians(25.0)))
    bpy.context.object.data.materials.append(common.principled("Box", (0.6, 0.55, 0.2), 0.7))

    rng = random.Random(64)
    for i in range(64):
        light = bpy.data.lights.new(f"Lamp{i}", "POINT")
        light.energy = 0.5 * 10 ** (2 * rng.random())
        light.shadow_soft_size = 0.0 if i % 2 == 0 else 0.01 + 0.03 * rng.random()
        light.color = (1.0, 0.75 + 0.25 * rng.random(), 0.5 + 0.5 * rng.random())
        lamp = bpy.data.objects.new(f"Lamp{i}", light)
        scene.collection.objects.link(lamp)
        lamp.location = (rng.uniform(-2.8, 2.8), rng.uniform(-2.8, 2.8), rng.uniform(0.4, 2.6))


if __name__ == "__main__":
    build()
