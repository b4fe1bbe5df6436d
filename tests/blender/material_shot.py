"""The Blender side of the materials shot (tests/blender/blender_material_test.cpp).

A ground plane textured with an 8x8 red/white checker (a PNG this script writes) in a Principled
BSDF and what SHOTS puts over it: "materials", a glossy gold metal and a glossy red dielectric
sphere; "glass", a rough glass sphere; "normal_map", nothing, the ground normal-mapped (ridges);
"alpha", a card cut out by its texture's alpha (the Principled BSDF's Alpha); "emission", a card
emitting the checker (the Principled BSDF's Emission), the only light. The others are lit by a sun
(angle 0: a delta light) and a uniform grey world. Every material is built before the export and
exported as it is, through filmback's add-on (importers/blender/export_shot.py: the node trees,
the camera, the sun in Blender's units and the world travel in FILMBACK_blender), so that filmback
renders the node trees Cycles renders; Cycles renders at 160x120 with a 1 px box filter.

    blender -b --factory-startup --python material_shot.py -- OUTDIR SHOT

writes OUTDIR/shot.gltf (+ .bin, checker.png), OUTDIR/cycles.exr and OUTDIR/manifest.txt with
one record: shot name, samples, width_px, height_px, and checker_red/checker_white (the squares'
base colours, linear).
"""

import math
import os
import sys

import bpy
from mathutils import Euler

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "importers",
                                "blender"))
import export_shot  # noqa: E402  (filmback's add-on: Blender's exporter plus FILMBACK_blender)
import make_shot  # noqa: E402  (camera, Cycles settings, manifest records)

SHOT = make_shot.Shot(160, 120, 35.0, (), samples=256)
WORLD_RGB = (0.5, 0.5, 0.5)  # W sr^-1 m^-2
SUN_W_PER_M2 = 3.0
SUN_ROTATION_DEG = (40.0, 0.0, 30.0)
CHECKER_SQUARES = 8
CHECKER_PX = 256
RED_SRGB = (0.8, 0.1, 0.1)
WHITE_SRGB = (0.9, 0.9, 0.9)
# Cycles' bounces after the camera's hit: filmback's path integrator's default max_depth of 8
# counts that hit's light too.
BOUNCES = 7
EMISSION_STRENGTH = 4.0  # W sr^-1 m^-2 per unit of the emissive texture


def srgb_to_linear(v):
    return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4


def checker_image(path):
    """An 8x8 checker, red in the top-left square of the image file (row 0 at the top): glTF's
    texture coordinates put (0, 0) there, so a flipped v turns every square's colour."""
    image = bpy.data.images.new("checker", CHECKER_PX, CHECKER_PX, alpha=False)
    pixels = []
    side = CHECKER_PX // CHECKER_SQUARES
    for row_from_bottom in range(CHECKER_PX):  # Blender stores the bottom row first
        row = CHECKER_PX - 1 - row_from_bottom
        for col in range(CHECKER_PX):
            red = (row // side + col // side) % 2 == 0
            pixels.extend((*(RED_SRGB if red else WHITE_SRGB), 1.0))
    image.pixels = pixels
    image.filepath_raw = path
    image.file_format = "PNG"
    image.save()
    return image


def principled(name, base_colour, metallic, roughness, distribution="GGX", **inputs):
    """A Principled BSDF material with Specular 0.5 (F0 = 0.08 * 0.5 = 0.04) and `inputs` set by
    their names with _ for spaces (Sheen_Tint=0.5); returns it and its node."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.distribution = distribution
    bsdf.inputs["Base Color"].default_value = (*base_colour, 1.0)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Specular"].default_value = 0.5
    for key, value in inputs.items():
        bsdf.inputs[key.replace("_", " ")].default_value = value
    return material, bsdf


def ridges_image(path=None):
    """A tangent-space normal map (OpenGL convention, as glTF and Blender: +X right, +Y up the
    image) of the height field h = A sin(2 pi 4 x) + A sin(2 pi 3 y), x right and y up the image
    in [0, 1]: slopes up to 0.5 along x and 0.38 along y, so that a flipped tangent or bitangent
    lights the other flank of the ridges. Saved as a PNG at `path`, or left a generated image
    (which the add-on saves beside the export)."""
    image = bpy.data.images.new("ridges", CHECKER_PX, CHECKER_PX, alpha=False)
    image.colorspace_settings.name = "Non-Color"
    a = 0.5 / (2 * math.pi * 4)
    pixels = []
    for row_from_bottom in range(CHECKER_PX):
        y = (row_from_bottom + 0.5) / CHECKER_PX
        for col in range(CHECKER_PX):
            x = (col + 0.5) / CHECKER_PX
            n = (-a * 2 * math.pi * 4 * math.cos(2 * math.pi * 4 * x),
                 -a * 2 * math.pi * 3 * math.cos(2 * math.pi * 3 * y), 1.0)
            length = math.sqrt(sum(c * c for c in n))
            pixels.extend((*(0.5 + 0.5 * c / length for c in n), 1.0))
    image.pixels = pixels
    if path:
        image.filepath_raw = path
        image.file_format = "PNG"
        image.save()
    return image


def link_normal_map(material, bsdf, image):
    """The image through a Normal Map node (tangent space, strength 1: glTF's scale 1) into the
    node's Normal."""
    nodes, links = material.node_tree.nodes, material.node_tree.links
    normals = nodes.new("ShaderNodeTexImage")
    normals.image = image
    normals.interpolation = "Linear"
    mapping = nodes.new("ShaderNodeNormalMap")
    links.new(normals.outputs["Color"], mapping.inputs["Color"])
    links.new(mapping.outputs["Normal"], bsdf.inputs["Normal"])


def add_ground(image, normal_map=None):
    bpy.ops.mesh.primitive_plane_add(size=8.0, location=(0.0, 0.0, 0.0))
    ground = bpy.context.active_object
    ground.name = "ground"
    material, bsdf = principled("checker", (1.0, 1.0, 1.0), 0.0, 0.6)
    nodes, links = material.node_tree.nodes, material.node_tree.links
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    texture.interpolation = "Linear"
    links.new(texture.outputs["Color"], bsdf.inputs["Base Color"])
    if normal_map is not None:
        link_normal_map(material, bsdf, normal_map)
    ground.data.materials.append(material)


def cutout_image(path):
    """A green card's colour and coverage: opaque inside a disk centred a third of the way from
    the image's top-left corner and in a bar along its bottom, transparent elsewhere (straight
    alpha, 0 or 1): a flipped or shifted lookup moves the holes."""
    image = bpy.data.images.new("cutout", CHECKER_PX, CHECKER_PX, alpha=True)
    pixels = []
    for row_from_bottom in range(CHECKER_PX):
        v = 1.0 - (row_from_bottom + 0.5) / CHECKER_PX  # from the top
        for col in range(CHECKER_PX):
            u = (col + 0.5) / CHECKER_PX
            inside = (u - 0.33) ** 2 + (v - 0.33) ** 2 < 0.25 ** 2 or v > 0.8
            pixels.extend((0.1, 0.8, 0.1, 1.0 if inside else 0.0))
    image.pixels = pixels
    image.filepath_raw = path
    image.file_format = "PNG"
    image.save()
    return image


def add_cutout(image):
    """A 2 m card standing on the ground in front of the spheres' place, facing the camera, its
    alpha from the image through the Principled BSDF's Alpha, which both renderers render as a
    mix with a Transparent BSDF (blend method CLIP, exported as glTF's alphaMode MASK for other
    viewers, is an Eevee setting Cycles ignores)."""
    bpy.ops.mesh.primitive_plane_add(size=2.0, location=(0.0, -0.5, 1.0), rotation=(math.radians(90.0), 0.0, 0.0))
    card = bpy.context.active_object
    card.name = "card"
    material, bsdf = principled("cutout", (1.0, 1.0, 1.0), 0.0, 1.0)
    material.blend_method = "CLIP"
    material.alpha_threshold = 0.5
    nodes, links = material.node_tree.nodes, material.node_tree.links
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    texture.interpolation = "Linear"
    links.new(texture.outputs["Color"], bsdf.inputs["Base Color"])
    links.new(texture.outputs["Alpha"], bsdf.inputs["Alpha"])
    card.data.materials.append(material)


def add_emissive_card(image):
    """A 2 m card standing behind the spheres' place, facing the camera, emitting the checker
    image through the Principled BSDF's Emission at strength EMISSION_STRENGTH and reflecting
    nothing (base colour black, Specular 0), so that it lights the ground by its texture alone."""
    bpy.ops.mesh.primitive_plane_add(size=2.0, location=(0.0, 1.0, 1.0), rotation=(math.radians(90.0), 0.0, 0.0))
    card = bpy.context.active_object
    card.name = "emitter"
    material, bsdf = principled("emissive", (0.0, 0.0, 0.0), 0.0, 1.0)
    bsdf.inputs["Specular"].default_value = 0.0
    nodes, links = material.node_tree.nodes, material.node_tree.links
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    texture.interpolation = "Linear"
    links.new(texture.outputs["Color"], bsdf.inputs["Emission"])
    bsdf.inputs["Emission Strength"].default_value = EMISSION_STRENGTH
    card.data.materials.append(material)


def add_sphere(name, location, radius, material):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=radius, location=location)
    sphere = bpy.context.active_object
    sphere.name = name
    bpy.ops.object.shade_smooth()
    sphere.data.materials.append(material)


def glass():
    """Principled with Transmission 1: a rough glass tinted by its base colour, its reflection
    and refraction equally rough (Transmission Roughness 0)."""
    return principled("glass", (0.9, 0.95, 1.0), 0.0, 0.15, Transmission=1.0, IOR=1.5)[0]


SHOTS = {
    # A glossy gold metal and a glossy red dielectric.
    "materials": (("metal", (-0.9, 0.2, 0.7), lambda: principled("gold metal", (1.0, 0.77, 0.34), 1.0, 0.3)[0]),
                  ("dielectric", (0.9, 0.4, 0.7), lambda: principled("red dielectric", (0.6, 0.05, 0.05), 0.0, 0.2)[0])),
    # One rough glass sphere over the checker, which it refracts.
    "glass": (("glass", (0.0, 0.3, 0.7), glass),),
    # The ground alone with a normal map (ridges_image).
    "normal_map": (),
    # The ground and a card cut out by its texture's alpha (cutout_image).
    "alpha": (),
    # The ground lit by a card emitting the checker texture (add_emissive_card), no sun, no world.
    "emission": (),
}


def configure_cycles(scene, shot):
    """make_shot.py's settings, with filmback's path depth and nothing that biases Cycles' estimate
    away from the integral filmback estimates."""
    make_shot.configure_cycles(scene, shot)
    cycles = scene.cycles
    cycles.max_bounces = cycles.diffuse_bounces = cycles.glossy_bounces = BOUNCES
    cycles.transmission_bounces = cycles.transparent_max_bounces = BOUNCES
    cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0  # no clamping
    cycles.light_sampling_threshold = 0.0  # every light sample's shadow ray is traced
    cycles.caustics_reflective = cycles.caustics_refractive = True
    cycles.blur_glossy = 0.0  # Filter Glossy off: it widens glossy lobes after a bounce


def main():
    out_dir, name = make_shot.shot_arguments("material_shot.py", SHOTS)

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    make_shot.new_world(scene, WORLD_RGB, 0.0 if name == "emission" else 1.0)

    configure_cycles(scene, SHOT)

    camera = make_shot.build_camera(scene, SHOT)
    camera.location = (0.0, -6.0, 3.2)
    camera.rotation_euler = Euler((math.radians(64.0), 0.0, 0.0), "XYZ")

    normal_map = ridges_image(os.path.join(out_dir, "ridges.png")) if name == "normal_map" else None
    add_ground(checker_image(os.path.join(out_dir, "checker.png")), normal_map)
    for sphere_name, location, make_material in SHOTS[name]:
        add_sphere(sphere_name, location, 0.7, make_material())
    if name == "alpha":
        add_cutout(cutout_image(os.path.join(out_dir, "cutout.png")))
    if name == "emission":
        add_emissive_card(bpy.data.images["checker"])

    sun_data = bpy.data.lights.new("Sun", "SUN")
    sun_data.energy = 0.0 if name == "emission" else SUN_W_PER_M2
    sun_data.angle = 0.0
    sun = bpy.data.objects.new("Sun", sun_data)
    sun.rotation_euler = Euler([math.radians(a) for a in SUN_ROTATION_DEG], "XYZ")
    scene.collection.objects.link(sun)
    bpy.context.view_layer.update()

    linear = lambda c: ",".join(f"{srgb_to_linear(v):.6f}" for v in c)  # noqa: E731
    with open(os.path.join(out_dir, "manifest.txt"), "w") as manifest:
        manifest.write(make_shot.record(
            "shot", name=name, samples=SHOT.samples, width_px=SHOT.width_px,
            height_px=SHOT.height_px, checker_red=linear(RED_SRGB), checker_white=linear(WHITE_SRGB)))

    export_shot.export(os.path.join(out_dir, "shot.gltf"))

    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main()
