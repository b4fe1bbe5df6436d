"""The Blender side of convert_viewer.py: a converted POV-Ray scene as a viewer that knows only
standard glTF sees it. Imports the .gltf with Blender's own glTF importer (its default lighting
mode, "Standard": W = cd * 4 pi / 683 for point and spot lights, W/m^2 = lux / 683 for suns) and
renders it with Cycles through the imported camera.

    blender -b --factory-startup --python convert_viewer_shot.py -- SCENE.gltf OUT.exr W H SAMPLES

OUT.exr is a multilayer EXR (32-bit float, scene-linear) with the combined pass and the depth
pass (1e10 where a ray escapes). glTF has no background: the world gets the colour the file
carries in FILMBACK_blender's world_color (black without it), as a viewer's background setting
would, and nothing else of FILMBACK_blender or FILMBACK_povray is read.
"""

import json
import sys

import bpy
import numpy

# Debian 12's numpy 1.24 dropped numpy.bool, which Blender 3.4's glTF importer still uses.
numpy.bool = bool


def main(argv):
    gltf, out, width, height, samples = argv[0], argv[1], int(argv[2]), int(argv[3]), int(argv[4])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=gltf)
    scene = bpy.context.scene
    cameras = [o for o in scene.objects if o.type == "CAMERA"]
    if not cameras:
        sys.exit(f"{gltf}: the importer made no camera")
    scene.camera = cameras[0]

    with open(gltf, encoding="utf-8") as f:
        root = json.load(f)
    colour = [0.0, 0.0, 0.0]
    for s in root.get("scenes", []):
        colour = s.get("extensions", {}).get("FILMBACK_blender", {}).get("world_color", colour)
    world = bpy.data.worlds.new("background")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (*colour[:3], 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world

    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.seed = 1
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2
    scene.view_layers[0].use_pass_z = True
    scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = out
    bpy.ops.render.render(write_still=True)


main(sys.argv[sys.argv.index("--") + 1:])
