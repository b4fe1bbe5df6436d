"""The Blender side of cryptomatte_test.py, in two modes:

    blender -b --factory-startup --python cryptomatte_shot.py -- shot OUTDIR
    blender -b --factory-startup --python cryptomatte_shot.py -- matte OUTDIR EXR LAYER NAME...

`shot` builds two planes side by side, "Left" (material "RedMat") and "Right" ("BlueMat"), and a
third above them, "Badge" ("GreenMat"), a child of Left, seen square-on by a camera 5 m away,
exports them through filmback's add-on to OUTDIR/shot.gltf and renders them with Cycles, its
CryptoObject, CryptoMaterial and CryptoAsset passes on, to OUTDIR/cycles.exr (multi-layer). OUTDIR/silhouettes.json gives each plane's image as a raster rectangle [x0, y0, x1,
y1] in pixels (Blender's own projection, world_to_camera_view; origin top-left, y down).

`matte` reads EXR's Cryptomatte layer LAYER (e.g. ViewLayer.CryptoObject) with Blender's
Cryptomatte node (the compositor's CryptomatteV2, source Image) and writes, for each NAME, the
node's Matte output to OUTDIR/matte_<NAME>.exr, and its values, top row first, to
OUTDIR/matte_<NAME>.json (a list of rows): Blender's own decoding of the file's ids, ranks and
manifest, for a driver without an image library.
"""

import json
import os
import sys
from types import SimpleNamespace

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_shot import configure_cycles, export_and_render_layers  # noqa: E402

WIDTH_PX, HEIGHT_PX = 64, 48
SAMPLES = 64
# Each plane: its name, material, centre (x, y) and half-size (x, y) in metres, on the z = 0 plane,
# and its parent (Blender's CryptoAsset names an object by its topmost parent); their edges fall
# inside pixels, not on pixel boundaries.
PLANES = [("Left", "RedMat", (-1.03, 0.07), (0.93, 0.81), None),
          ("Right", "BlueMat", (0.97, -0.11), (0.94, 0.62), None),
          ("Badge", "GreenMat", (0.13, 1.11), (0.57, 0.14), "Left")]


def build_shot(out_dir):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    # make_shot's Cycles: a 1 px box filter (a pixel's coverage is the share of its square, as
    # filmback's `box`), no adaptive sampling, no denoising.
    configure_cycles(scene, SimpleNamespace(width_px=WIDTH_PX, height_px=HEIGHT_PX,
                                            samples=SAMPLES))
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(camera)
    camera.location = (0.0, 0.0, 5.0)  # looking down -z
    scene.camera = camera
    for name, material_name, centre, half, parent in PLANES:
        bpy.ops.mesh.primitive_plane_add(size=2.0, location=(centre[0], centre[1], 0.0))
        plane = bpy.context.object
        plane.name = name
        plane.scale = (half[0], half[1], 1.0)
        if parent:  # kept where it is in the world
            bpy.context.view_layer.update()
            plane.parent = bpy.data.objects[parent]
            plane.matrix_parent_inverse = plane.parent.matrix_world.inverted()
        material = bpy.data.materials.new(material_name)
        material.use_nodes = True
        plane.data.materials.append(material)
    view_layer = scene.view_layers[0]
    view_layer.use_pass_cryptomatte_object = True
    view_layer.use_pass_cryptomatte_material = True
    view_layer.use_pass_cryptomatte_asset = True
    bpy.context.view_layer.update()

    silhouettes = {}
    for name, _, centre, half, _ in PLANES:
        corners = [world_to_camera_view(scene, camera, Vector((centre[0] + sx * half[0],
                                                               centre[1] + sy * half[1], 0.0)))
                   for sx in (-1, 1) for sy in (-1, 1)]
        xs = [c.x * WIDTH_PX for c in corners]
        ys = [(1.0 - c.y) * HEIGHT_PX for c in corners]
        silhouettes[name] = [min(xs), min(ys), max(xs), max(ys)]
    with open(os.path.join(out_dir, "silhouettes.json"), "w") as f:
        json.dump({"width_px": WIDTH_PX, "height_px": HEIGHT_PX, "samples": SAMPLES,
                   "planes": silhouettes}, f)

    export_and_render_layers(scene, out_dir)


def write_mattes(out_dir, exr, layer, names):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    image = bpy.data.images.load(exr)
    scene.render.resolution_x, scene.render.resolution_y = WIDTH_PX, HEIGHT_PX
    scene.render.resolution_percentage = 100
    scene.render.engine = "BLENDER_WORKBENCH"  # nothing to render: the compositor's input is `exr`
    scene.use_nodes = True
    tree = scene.node_tree
    tree.nodes.clear()
    crypto = tree.nodes.new("CompositorNodeCryptomatteV2")
    crypto.source = "IMAGE"
    crypto.image = image
    crypto.layer_name = layer
    composite = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(crypto.outputs["Matte"], composite.inputs["Image"])
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_mode = "RGB"
    settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    for name in names:
        crypto.matte_id = name
        scene.render.filepath = os.path.join(out_dir, f"matte_{name}.exr")
        bpy.ops.render.render(write_still=True)
        matte = bpy.data.images.load(scene.render.filepath, check_existing=False)
        values = list(matte.pixels)  # RGBA, bottom row first
        rows = [[values[4 * (y * WIDTH_PX + x)] for x in range(WIDTH_PX)]
                for y in reversed(range(HEIGHT_PX))]
        with open(os.path.join(out_dir, f"matte_{name}.json"), "w") as f:
            json.dump(rows, f)


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    if args[:1] == ["shot"] and len(args) == 2:
        build_shot(args[1])
    elif args[:1] == ["matte"] and len(args) >= 5:
        write_mattes(args[1], args[2], args[3], args[4:])
    else:
        sys.stderr.write(__doc__)
        sys.exit(2)


if __name__ == "__main__":
    main()
