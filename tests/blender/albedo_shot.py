"""The Blender side of the directional-albedo test (tests/blender/blender_albedo_test.cpp).

A grid of unit spheres, one material each, under a uniform white world (radiance 1) seen by an
orthographic camera straight down -Z: the view direction is the same for every pixel and a
pixel's normal is known from its place on its sphere, and a convex sphere sees only the world, so
each pixel is the material's directional albedo, the integral of f cos over the sphere of
directions, at that pixel's angle. The spheres see only the camera (their other ray visibility is
off), so that they do not see each other. The world is not sampled as a light (sampling method
None): every path reaches it by BSDF sampling, the estimator the test reproduces. One bounce,
no clamping, Filter Glossy 0, a 1 px box filter, no denoising.

    blender -b --factory-startup --python albedo_shot.py -- OUTDIR

(ALBEDO_SAMPLES in the environment overrides the 512 samples, for a quicker look while working.)

writes OUTDIR/cycles.exr and OUTDIR/manifest.txt: a `shot` record (samples, width_px,
height_px) and one `sphere` record per material: its name, the pixel centre and radius of its
disk, the node (principled, diffuse, glossy) and the node's inputs.
"""

import math
import os
import sys

import bpy

COLUMNS = 4
SPHERE_PX = 96  # pixels per grid cell; the sphere's radius is RADIUS_FRACTION of half of it
RADIUS_FRACTION = 0.94
SAMPLES = int(os.environ.get("ALBEDO_SAMPLES", "512"))
SPHERE_SEGMENTS, SPHERE_RINGS = 256, 128

GREY = (0.8, 0.8, 0.8)


def principled(roughness, **inputs):
    values = {"base_color": GREY, "specular": 0.5, "roughness": roughness, "metallic": 0.0,
              "specular_tint": 0.0, "sheen": 0.0, "sheen_tint": 0.5, "clearcoat": 0.0,
              "clearcoat_roughness": 0.03, "distribution": "GGX"}
    values.update(inputs)
    return ("principled", values)


# name -> (node, inputs); the names are what the test reports.
MATERIALS = [
    ("principled_r0.2", principled(0.2)),
    ("principled_r0.5", principled(0.5)),
    ("principled_r0.9", principled(0.9)),
    ("principled_multiscatter_r0.5", principled(0.5, distribution="MULTI_GGX")),
    ("metal_r0.3", principled(0.3, metallic=1.0, base_color=(0.9, 0.6, 0.3))),
    ("metal_multiscatter_r0.7",
     principled(0.7, metallic=1.0, base_color=(0.9, 0.6, 0.3), distribution="MULTI_GGX")),
    ("sheen_r0.5", principled(0.5, sheen=1.0)),
    ("clearcoat_r0.5", principled(0.5, clearcoat=1.0, clearcoat_roughness=0.2)),
    ("specular_tint_r0.4", principled(0.4, base_color=(0.8, 0.3, 0.1), specular_tint=1.0)),
    ("diffuse_r0", ("diffuse", {"color": GREY, "roughness": 0.0})),
    ("diffuse_r0.5", ("diffuse", {"color": GREY, "roughness": 0.5})),
    ("glossy_ggx_r0.3", ("glossy", {"color": GREY, "roughness": 0.3, "distribution": "GGX"})),
    ("glossy_beckmann_r0.4",
     ("glossy", {"color": GREY, "roughness": 0.4, "distribution": "BECKMANN"})),
    ("glossy_multiscatter_r0.6",
     ("glossy", {"color": GREY, "roughness": 0.6, "distribution": "MULTI_GGX"})),
]

SOCKETS = {"base_color": "Base Color", "specular": "Specular", "roughness": "Roughness",
           "metallic": "Metallic", "specular_tint": "Specular Tint", "sheen": "Sheen",
           "sheen_tint": "Sheen Tint", "clearcoat": "Clearcoat",
           "clearcoat_roughness": "Clearcoat Roughness", "color": "Color"}
NODES = {"principled": "ShaderNodeBsdfPrincipled", "diffuse": "ShaderNodeBsdfDiffuse",
         "glossy": "ShaderNodeBsdfGlossy"}


def make_material(name, node_kind, inputs):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    node = tree.nodes.new(NODES[node_kind])
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(node.outputs[0], out.inputs["Surface"])
    for key, value in inputs.items():
        if key == "distribution":
            node.distribution = value
        elif isinstance(value, tuple):
            node.inputs[SOCKETS[key]].default_value = (*value, 1.0)
        else:
            node.inputs[SOCKETS[key]].default_value = value
    return material


def record(kind, **fields):
    def text(v):
        if isinstance(v, tuple):
            return ",".join(repr(float(c)) for c in v)
        return repr(v) if isinstance(v, float) else str(v)
    return kind + " " + " ".join(f"{k}={text(v)}" for k, v in fields.items())


def main():
    out_dir = sys.argv[sys.argv.index("--") + 1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    rows = math.ceil(len(MATERIALS) / COLUMNS)
    width, height = COLUMNS * SPHERE_PX, rows * SPHERE_PX
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = SAMPLES
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.seed = 0
    cycles.max_bounces = 1
    cycles.diffuse_bounces = cycles.glossy_bounces = 1
    cycles.transmission_bounces = cycles.volume_bounces = cycles.transparent_max_bounces = 0
    cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0
    cycles.blur_glossy = 0.0
    cycles.caustics_reflective = cycles.caustics_refractive = True
    cycles.filter_type = "BOX"
    cycles.filter_width = 1.0
    cycles.pixel_filter_type = "BOX"
    scene.render.filter_size = 1.0
    scene.view_settings.view_transform = "Standard"

    world = bpy.data.worlds.new("white")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    background.inputs["Strength"].default_value = 1.0
    world.cycles.sampling_method = "NONE"
    scene.world = world

    # One world unit per grid cell: cell (col, row) is centred at x = col + 0.5 - COLUMNS / 2,
    # y = rows / 2 - row - 0.5 (row 0 at the top of the image).
    camera_data = bpy.data.cameras.new("camera")
    camera_data.type = "ORTHO"
    camera_data.ortho_scale = float(max(COLUMNS, rows))
    camera_data.sensor_fit = "AUTO"
    camera = bpy.data.objects.new("camera", camera_data)
    camera.location = (0.0, 0.0, 10.0)
    scene.collection.objects.link(camera)
    scene.camera = camera

    radius = 0.5 * RADIUS_FRACTION
    lines = [record("shot", samples=SAMPLES, width_px=width, height_px=height)]
    for i, (name, (kind, inputs)) in enumerate(MATERIALS):
        col, row = i % COLUMNS, i // COLUMNS
        x, y = col + 0.5 - COLUMNS / 2, rows / 2 - row - 0.5
        bpy.ops.mesh.primitive_uv_sphere_add(segments=SPHERE_SEGMENTS, ring_count=SPHERE_RINGS,
                                             radius=radius, location=(x, y, 0.0))
        sphere = bpy.context.active_object
        bpy.ops.object.shade_smooth()
        sphere.data.materials.append(make_material(name, kind, inputs))
        sphere.visible_diffuse = sphere.visible_glossy = False
        sphere.visible_transmission = sphere.visible_volume_scatter = False
        sphere.visible_shadow = False
        lines.append(record("sphere", name=name, node=kind,
                            centre_x_px=(col + 0.5) * SPHERE_PX,
                            centre_y_px=(row + 0.5) * SPHERE_PX,
                            radius_px=radius * SPHERE_PX, **inputs))

    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)
    with open(os.path.join(out_dir, "manifest.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")


main()
