"""The Blender side of the alignment test (tests/blender/blender_alignment_test.cpp).

Builds a shot of small emissive spheres on a black world, seen by a rotated, displaced camera with a
landscape 320x200 frame; exports it with Blender's own glTF exporter and renders it with Cycles.

    blender -b --factory-startup --python make_shot.py -- OUTDIR [SAMPLES]

writes OUTDIR/shot.gltf (+ shot.bin), OUTDIR/cycles.exr (32-bit float, scene-linear) and
OUTDIR/spheres.txt: one line "name x_px y_px" per sphere, where Blender projects its centre
(raster convention of docs/conventions.md: origin at the top-left corner, y down).
"""

import math
import os
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Euler, Vector

WIDTH_PX, HEIGHT_PX = 320, 200
LENS_MM, SENSOR_WIDTH_MM = 35.0, 36.0

# (name, target centre x_px, y_px, depth along the view axis m, radius px, linear colour, strength).
# Targets sit at fractional pixel positions, some a dozen pixels from the frame's corners and edges
# where the projection is most off-axis; depths span 3-40 m. Strengths above 1 make the exporter
# write KHR_materials_emissive_strength, those below 1 a plain emissiveFactor.
SPHERES = [
    ("corner_top_left", 18.3, 16.7, 6.0, 5.0, (1.0, 1.0, 1.0), 1.0),
    ("corner_bottom_right", 300.6, 185.2, 14.0, 4.5, (1.0, 0.6, 0.3), 5.0),
    ("edge_right", 305.4, 70.9, 3.0, 6.5, (0.2, 0.5, 1.0), 0.8),
    ("edge_top", 150.8, 12.4, 25.0, 3.5, (1.0, 1.0, 1.0), 12.0),
    ("centre", 160.2, 99.6, 4.0, 9.0, (0.9, 0.9, 0.2), 2.5),
    ("corner_bottom_left", 22.7, 181.3, 9.0, 5.5, (0.4, 1.0, 0.4), 1.5),
    ("far", 231.1, 128.8, 40.0, 3.0, (1.0, 0.3, 0.8), 20.0),
]


def build_camera(scene):
    data = bpy.data.cameras.new("Camera")
    data.type = "PERSP"
    data.lens = LENS_MM
    data.sensor_width = SENSOR_WIDTH_MM
    data.sensor_fit = "AUTO"
    data.clip_start = 0.1
    data.clip_end = 200.0
    camera = bpy.data.objects.new("Camera", data)
    camera.location = (3.2, -6.5, 2.1)
    camera.rotation_euler = Euler((math.radians(74.0), math.radians(-8.0), math.radians(23.0)), "XYZ")
    scene.collection.objects.link(camera)
    scene.camera = camera
    return camera


def emission_material(name, colour, strength):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (*colour, 1.0)
    emission.inputs["Strength"].default_value = strength
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(emission.outputs["Emission"], output.inputs["Surface"])
    return material


def add_sphere(scene, camera, name, x_px, y_px, depth_m, radius_px, colour, strength):
    # Camera space: looks down -Z, +Y up; horizontal sensor fit, so fx = fy = W / (sensor / lens).
    focal_px = WIDTH_PX * LENS_MM / SENSOR_WIDTH_MM
    in_camera = Vector(((x_px - WIDTH_PX / 2) / focal_px * depth_m,
                        -(y_px - HEIGHT_PX / 2) / focal_px * depth_m,
                        -depth_m))
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32,
                                         radius=radius_px / focal_px * depth_m,
                                         location=camera.matrix_world @ in_camera)
    sphere = bpy.context.active_object
    sphere.name = name
    bpy.ops.object.shade_smooth()
    sphere.data.materials.append(emission_material(name, colour, strength))
    return sphere


def configure_cycles(scene, samples):
    scene.render.engine = "CYCLES"
    scene.render.resolution_x, scene.render.resolution_y = WIDTH_PX, HEIGHT_PX
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0
    scene.render.use_motion_blur = False
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = samples
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.seed = 1
    cycles.max_bounces = 1
    # A 1 px box: each pixel is the plain mean of radiance over its square, as filmback's `box`.
    cycles.pixel_filter_type = "BOX"
    cycles.filter_width = 1.0
    cycles.film_exposure = 1.0
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    image = scene.render.image_settings
    image.file_format = "OPEN_EXR"
    image.color_depth = "32"
    image.color_mode = "RGB"
    image.exr_codec = "ZIP"


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if not args:
        raise SystemExit("usage: blender -b --factory-startup --python make_shot.py -- OUTDIR [SAMPLES]")
    out_dir = os.path.abspath(args[0])
    samples = int(args[1]) if len(args) > 1 else 256
    os.makedirs(out_dir, exist_ok=True)

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world

    configure_cycles(scene, samples)
    camera = build_camera(scene)
    bpy.context.view_layer.update()
    spheres = [add_sphere(scene, camera, *row) for row in SPHERES]
    bpy.context.view_layer.update()

    with open(os.path.join(out_dir, "spheres.txt"), "w") as manifest:
        for sphere in spheres:
            uv = world_to_camera_view(scene, camera, sphere.matrix_world.translation)
            manifest.write(f"{sphere.name} {uv.x * WIDTH_PX:.4f} {(1.0 - uv.y) * HEIGHT_PX:.4f}\n")

    bpy.ops.export_scene.gltf(filepath=os.path.join(out_dir, "shot.gltf"), export_format="GLTF_SEPARATE",
                              export_cameras=True, export_lights=False, export_materials="EXPORT")

    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


main()
