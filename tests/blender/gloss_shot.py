"""The Blender side of gloss_test.py:

    blender -b --factory-startup --python gloss_shot.py -- OUTDIR

Builds a row of square patches, each with one material (PATCHES: Principled BSDF settings, a
Glossy BSDF, a Mix of Diffuse and Glossy), seen square-on by an orthographic camera, exports them
through filmback's add-on to OUTDIR/shot.gltf and renders them with Cycles, its Diffuse Color and
Glossy Color passes on, to OUTDIR/cycles.exr (multi-layer). OUTDIR/patches.json gives each patch's
name and its image as a raster rectangle [x0, y0, x1, y1] in pixels (origin top-left, y down).
"""

import json
import os
import sys
from types import SimpleNamespace

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_shot import configure_cycles, export_and_render_layers  # noqa: E402

PATCH_PX = 16  # each patch's side, in pixels; the camera sees one metre per PATCH_PX pixels
SAMPLES = 4    # the passes are the first hit's: the samples only average a patch's pixels
COLOUR = (0.8, 0.3, 0.1, 1.0)
# name: the Principled BSDF's inputs and distribution (others at Blender's defaults: GGX), or a
# node tree's kind.
PATCHES = [
    ("Dielectric", {"Base Color": COLOUR, "Metallic": 0.0, "Specular": 0.5, "Roughness": 0.4}),
    ("Specular1", {"Base Color": COLOUR, "Metallic": 0.0, "Specular": 1.0, "Roughness": 0.4}),
    ("Metal", {"Base Color": COLOUR, "Metallic": 1.0, "Roughness": 0.3}),
    ("HalfMetal", {"Base Color": COLOUR, "Metallic": 0.5, "Roughness": 0.3}),
    ("Glass", {"Base Color": COLOUR, "Transmission": 1.0, "Roughness": 0.0}),
    ("RoughGlass", {"Base Color": COLOUR, "Transmission": 1.0, "Roughness": 0.5}),
    ("HalfGlass", {"Base Color": COLOUR, "Transmission": 0.5, "Roughness": 0.2}),
    ("MultiGlass", {"Base Color": COLOUR, "Transmission": 1.0, "Roughness": 0.5,
                    "distribution": "MULTI_GGX"}),
    ("Clearcoat", {"Base Color": COLOUR, "Clearcoat": 1.0, "Roughness": 0.4}),
    ("Sheen", {"Base Color": COLOUR, "Sheen": 1.0, "Roughness": 0.4}),
    ("Glossy", "glossy"),
    ("MixDiffuseGlossy", "mix"),
]


def principled_material(name, inputs):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    for key, value in inputs.items():
        if key == "distribution":
            bsdf.distribution = value
        else:
            bsdf.inputs[key].default_value = value
    return material


def graph_material(name, kind):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    output = nodes["Material Output"]
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.inputs["Color"].default_value = (0.3, 0.6, 0.9, 1.0)
    glossy.inputs["Roughness"].default_value = 0.3
    if kind == "glossy":
        links.new(glossy.outputs["BSDF"], output.inputs["Surface"])
        return material
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = COLOUR
    mix = nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.3  # 0.7 diffuse, 0.3 glossy
    links.new(diffuse.outputs["BSDF"], mix.inputs[1])
    links.new(glossy.outputs["BSDF"], mix.inputs[2])
    links.new(mix.outputs["Shader"], output.inputs["Surface"])
    return material


def build_shot(out_dir):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    width_px, height_px = PATCH_PX * len(PATCHES), PATCH_PX
    configure_cycles(scene, SimpleNamespace(width_px=width_px, height_px=height_px,
                                            samples=SAMPLES))
    camera_data = bpy.data.cameras.new("Camera")
    camera_data.type = "ORTHO"
    camera_data.ortho_scale = float(len(PATCHES))  # the image's width, m
    camera = bpy.data.objects.new("Camera", camera_data)
    scene.collection.objects.link(camera)
    camera.location = (0.0, 0.0, 5.0)  # looking down -z
    scene.camera = camera
    patches = []
    for i, (name, setting) in enumerate(PATCHES):
        x = i - (len(PATCHES) - 1) / 2.0
        bpy.ops.mesh.primitive_plane_add(size=1.0, location=(x, 0.0, 0.0))
        plane = bpy.context.object
        plane.name = name
        material = (principled_material(name, setting) if isinstance(setting, dict)
                    else graph_material(name, setting))
        plane.data.materials.append(material)
        patches.append({"name": name, "rect": [i * PATCH_PX, 0, (i + 1) * PATCH_PX, PATCH_PX]})
    view_layer = scene.view_layers[0]
    view_layer.use_pass_diffuse_color = True
    view_layer.use_pass_glossy_color = True
    bpy.context.view_layer.update()
    with open(os.path.join(out_dir, "patches.json"), "w") as f:
        json.dump({"width_px": width_px, "height_px": height_px, "samples": SAMPLES,
                   "patches": patches}, f)

    export_and_render_layers(scene, out_dir)


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    if len(args) != 1:
        sys.stderr.write(__doc__)
        sys.exit(2)
    os.makedirs(args[0], exist_ok=True)
    build_shot(os.path.abspath(args[0]))


if __name__ == "__main__":
    main()
