# Builds filmback's bundled default scene in Blender and writes it with Blender's own glTF
# exporter, so the default scene is exactly what a Blender user's export looks like.
#   blender -b --factory-startup --python scenes/default/make_default.py -- scenes/default/default.gltf
import math
import sys

import bpy

out = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.resolution_x, scene.render.resolution_y = 1280, 720


def material(name, color, emission=None, strength=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1)
    bsdf.inputs["Roughness"].default_value = 1.0
    bsdf.inputs["Specular"].default_value = 0.0
    if emission:
        bsdf.inputs["Emission"].default_value = (*emission, 1)
        bsdf.inputs["Emission Strength"].default_value = strength
    return m


def box(name, size, location, mat, rotation_z=0.0):
    bpy.ops.mesh.primitive_cube_add(size=1, location=location, rotation=(0, 0, rotation_z))
    obj = bpy.context.object
    obj.name = name
    obj.scale = size
    obj.data.materials.append(mat)
    return obj


def plane(name, size, location, rotation, mat):
    bpy.ops.mesh.primitive_plane_add(size=1, location=location, rotation=rotation)
    obj = bpy.context.object
    obj.name = name
    obj.scale = (*size, 1)
    obj.data.materials.append(mat)
    return obj


white = material("White", (0.73, 0.73, 0.73))
red = material("Red", (0.63, 0.065, 0.05))
green = material("Green", (0.14, 0.45, 0.091))
lamp = material("Lamp", (0.0, 0.0, 0.0), emission=(1.0, 0.85, 0.6), strength=12.0)

# A 4 m wide, 3 m deep, 2.5 m high room open towards the camera (Blender: Z up, -Y towards camera).
plane("Floor", (4, 3), (0, 0, 0), (0, 0, 0), white)
plane("Ceiling", (4, 3), (0, 0, 2.5), (math.pi, 0, 0), white)
plane("BackWall", (4, 2.5), (0, 1.5, 1.25), (math.pi / 2, 0, 0), white)
plane("LeftWall", (3, 2.5), (-2, 0, 1.25), (math.pi / 2, 0, -math.pi / 2), red)
plane("RightWall", (3, 2.5), (2, 0, 1.25), (math.pi / 2, 0, math.pi / 2), green)
plane("CeilingLamp", (1.2, 0.8), (0, 0.2, 2.49), (math.pi, 0, 0), lamp)
box("TallBox", (0.7, 0.7, 1.4), (-0.7, 0.5, 0.7), white, math.radians(20))
box("ShortBox", (0.7, 0.7, 0.7), (0.7, -0.2, 0.35), white, math.radians(-18))
bpy.ops.mesh.primitive_uv_sphere_add(radius=0.3, location=(0.7, -0.2, 1.0), segments=48, ring_count=24)
sphere = bpy.context.object
sphere.name = "Sphere"
bpy.ops.object.shade_smooth()
sphere.data.materials.append(white)

bpy.ops.object.light_add(type="POINT", location=(1.2, -0.8, 2.0))
bpy.context.object.data.energy = 60.0  # W
bpy.context.object.name = "FillLight"

bpy.ops.object.camera_add(location=(0, -6.2, 1.25), rotation=(math.pi / 2, 0, 0))
camera = bpy.context.object
camera.name = "Camera"
camera.data.lens = 35.0
scene.camera = camera

bpy.ops.export_scene.gltf(filepath=out, export_format="GLTF_SEPARATE", export_cameras=True,
                          export_lights=True, export_apply=True)
