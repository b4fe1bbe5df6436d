"""A benchmark shot for `filmback bench` (scenes/bench/README.md): objects on a ground in the sun.

A rough diffuse ground, a glossy gold metal sphere, a glossy red dielectric Suzanne refined by a
Subdivision Surface modifier (render level 2), a matte box, lit by a 4-degree sun and a blue sky
world. Principled BSDFs throughout, as a Blender user makes them. Cycles is set to estimate what
filmback's path integrator estimates: 7 bounces of every kind (filmback's max_depth 8 counts the
direct-light bounce), no clamping, no light threshold, no glossy filtering.

Builds the shot in the current (empty) Blender file:

    blender -b --factory-startup --python scenes/bench/sunlit_objects.py
"""

import math

import bpy
from mathutils import Vector

WIDTH_PX, HEIGHT_PX = 480, 270


def look_at(obj, location, target):
    obj.location = location
    obj.rotation_euler = (Vector(target) - Vector(location)).to_track_quat("-Z", "Y").to_euler()


def principled(name, colour, roughness, metallic=0.0):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Metallic"].default_value = metallic
    return material


def world(scene, colour, strength):
    w = bpy.data.worlds.new("World")
    w.use_nodes = True
    background = w.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*colour, 1.0)
    background.inputs["Strength"].default_value = strength
    scene.world = w


def cycles_like_filmback(scene):
    render = scene.render
    render.engine = "CYCLES"
    render.resolution_x, render.resolution_y, render.resolution_percentage = WIDTH_PX, HEIGHT_PX, 100
    cycles = scene.cycles
    cycles.max_bounces = 7
    cycles.diffuse_bounces = cycles.glossy_bounces = cycles.transmission_bounces = 7
    cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0
    cycles.light_sampling_threshold = 0.0
    cycles.blur_glossy = 0.0
    scene.view_settings.view_transform = "Standard"


def build():
    scene = bpy.context.scene
    cycles_like_filmback(scene)
    world(scene, (0.45, 0.6, 0.9), 0.8)

    bpy.ops.mesh.primitive_plane_add(size=30.0, location=(0, 0, 0))
    bpy.context.object.data.materials.append(principled("Ground", (0.5, 0.45, 0.38), 0.9))

    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=0.7,
                                         location=(-1.1, 0.4, 0.7))
    bpy.ops.object.shade_smooth()
    bpy.context.object.data.materials.append(principled("Gold", (1.0, 0.77, 0.34), 0.25, 1.0))

    bpy.ops.mesh.primitive_monkey_add(size=1.3, location=(0.75, -0.2, 0.75),
                                      rotation=(0.0, 0.0, math.radians(-20.0)))
    monkey = bpy.context.object
    modifier = monkey.modifiers.new("Subdivision", "SUBSURF")
    modifier.levels = modifier.render_levels = 2
    bpy.ops.object.shade_smooth()
    monkey.data.materials.append(principled("RedPlastic", (0.7, 0.06, 0.05), 0.15))

    bpy.ops.mesh.primitive_cube_add(size=0.8, location=(2.3, 1.4, 0.4),
                                    rotation=(0.0, 0.0, math.radians(30.0)))
    bpy.context.object.data.materials.append(principled("Box", (0.2, 0.35, 0.6), 0.6))

    sun = bpy.data.lights.new("Sun", "SUN")
    sun.energy = 3.0
    sun.angle = math.radians(4.0)
    sun.color = (1.0, 0.95, 0.85)
    sun_object = bpy.data.objects.new("Sun", sun)
    scene.collection.objects.link(sun_object)
    look_at(sun_object, (4.0, -2.0, 6.0), (0.0, 0.0, 0.0))

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = 40.0
    scene.collection.objects.link(camera)
    look_at(camera, (1.2, -7.5, 2.6), (0.4, 0.3, 0.6))
    scene.camera = camera


if __name__ == "__main__":
    build()
