"""The Blender side of the Principled shots (tests/blender/blender_principled_test.cpp).

One stage seen by a low camera: a ground 120 m wide reaching the horizon, so that the lower half of
the frame sees it at grazing angles (cos of the view angle 0.44 at the bottom row, 0 at the
horizon), and three spheres standing on it 5 m away. SHOTS says their materials and the lights:
Principled BSDFs at roughness 0.2, 0.5 and 0.9 (ground included), metal, sheen, clearcoat,
specular tint, glass, Multiscatter GGX, a Mix Shader of a Glossy and a Diffuse BSDF by a
texture, a normal map on a sphere, an Emission added to a Glossy BSDF mixed with a Transparent
one and Principled's Alpha, under a sun and a dim world; Blender's default material under a sun, a point light and
the default world's grey; and the same stage lit by a point light with a radius (a sphere light)
or by a disk area light alone. Every material is a node tree built before the export and exported
as it is by filmback's add-on (importers/blender/export_shot.py), so that both renderers render
the same trees; Cycles renders with material_shot.py's settings (filmback's path depth, no
clamping, no light threshold, Filter Glossy off) and a 1 px box filter.

    blender -b --factory-startup --python principled_shot.py -- OUTDIR SHOT

writes OUTDIR/shot.gltf (+ .bin, the stripes' image), OUTDIR/cycles.exr and OUTDIR/manifest.txt
with one "shot" record: name, samples, width_px, height_px.
"""

import os
import sys
from dataclasses import dataclass

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_shot  # noqa: E402  (camera, Cycles settings, manifest records)
import material_shot  # noqa: E402  (Principled materials, spheres, Cycles settings, the add-on)
from radiometry_shot import look_at  # noqa: E402

# 160x120 at 256 spp, 35 mm on a 36 mm wide sensor.
CAMERA = make_shot.Shot(160, 120, 35.0, (), samples=256)
CAMERA_LOCATION = (0.0, -5.0, 0.9)
CAMERA_TARGET = (0.0, 0.0, 0.45)
GROUND_SIZE_M = 120.0
SPHERE_RADIUS_M = 0.5
SPHERE_X_M = (-1.4, 0.0, 1.4)
GROUND_COLOUR = (0.5, 0.45, 0.35)
STRIPES_PX = 64


@dataclass(frozen=True)
class Light:
    """A Blender light; a sun keeps Blender's default angle for a new sun, 0.526 degrees."""
    type: str  # SUN, POINT, AREA (a disk)
    energy: float  # W/m^2 for a sun, W otherwise
    location: tuple = (0.0, 0.0, 10.0)
    target: tuple = (0.0, 0.0, 0.0)  # where its -Z axis points
    radius_m: float = 0.0  # a point light's
    size_m: float = 1.0  # a disk's diameter


# A sun from the front left, 35 degrees high: the spheres' shadows fall towards the camera and the
# ground's glossy lobe brightens towards the bottom of the frame.
SUN = Light("SUN", 3.0, location=(-6.0, 6.0, 5.9), target=(0.0, 0.0, 0.0))
# A sun from behind the camera on the right, 35 degrees high: the ground scatters it back towards
# the camera at grazing angles (Principled diffuse's retro-reflection), and shadows and the glass
# sphere's caustic fall behind the spheres.
SUN_BEHIND = Light("SUN", 3.0, location=(4.0, -7.0, 5.7), target=(0.0, 0.0, 0.0))
# A sun 60 degrees high from behind the right: the glass sphere's caustic falls close behind it,
# and the sphere is 58 degrees from the antisolar point, between its rainbows (28 and 78 degrees at
# IOR 1.45). Under SUN_BEHIND (34 degrees) the primary bow's glint left a noise floor of 10 % in
# its block at 256 spp, 6.6 % at 1024.
SUN_HIGH = Light("SUN", 3.0, location=(3.0, -4.0, 8.7), target=(0.0, 0.0, 0.0))
DIM_WORLD = ((0.05, 0.06, 0.08), 1.0)
# Blender 3.4's default scene: its light (point, 1000 W, radius 0.1 m, at (4.08, 1.0, 5.9)) and
# its world (grey 0.050876).
DEFAULT_POINT = Light("POINT", 1000.0, location=(4.08, 1.0, 5.9), radius_m=0.1)
DEFAULT_WORLD = ((0.050876, 0.050876, 0.050876), 1.0)


def principled(name, base_colour, metallic, roughness, **inputs):
    """What makes a Principled BSDF material (material_shot.principled) when the shot is built."""
    return lambda: material_shot.principled(name, base_colour, metallic, roughness, **inputs)[0]


def ground_at(roughness):
    return principled("ground", GROUND_COLOUR, 0.0, roughness)


def spheres_at(roughness):
    """A blue dielectric, a white one and a gold metal."""
    return (principled("blue", (0.1, 0.25, 0.6), 0.0, roughness),
            principled("white", (0.8, 0.8, 0.8), 0.0, roughness),
            principled("gold", (1.0, 0.77, 0.34), 1.0, roughness))


def default_material():
    """What Blender gives a new material: a Principled BSDF with base colour 0.8, Roughness 0.5,
    Specular 0.5."""
    material = bpy.data.materials.new("Material")
    material.use_nodes = True
    return material


SHEEN = principled("sheen", (0.3, 0.05, 0.1), 0.0, 0.8, Sheen=1.0, Sheen_Tint=0.5)
CLEARCOAT = principled("clearcoat", (0.6, 0.1, 0.05), 0.0, 0.6, Clearcoat=1.0,
                       Clearcoat_Roughness=0.05)
SPECULAR_TINT = principled("specular tint", (0.1, 0.3, 0.8), 0.0, 0.3, Specular=1.0,
                           Specular_Tint=1.0)
# Rough enough that its caustics and internal glints stay within a few % of noise at 256 spp.
GLASS = principled("glass", (0.95, 0.95, 1.0), 0.0, 0.4, Transmission=1.0, IOR=1.45)
MULTISCATTER = principled("multiscatter", (0.9, 0.6, 0.2), 0.5, 0.6, distribution="MULTI_GGX")


# Anisotropic lobes along Cycles' default tangent (radial about each object's Z axis).
ANISOTROPIC = (principled("brushed gold", (1.0, 0.77, 0.34), 1.0, 0.3, Anisotropic=0.9),
               principled("turned", (0.2, 0.4, 0.3), 0.0, 0.25, Anisotropic=0.7,
                          Anisotropic_Rotation=0.25),
               principled("brushed steel", (0.6, 0.6, 0.62), 1.0, 0.5, Anisotropic=-0.6))


def normal_mapped():
    """A Principled BSDF normal-mapped by material_shot.py's ridges, on a sphere: the tangent frame
    follows the sphere's UV map."""
    material, bsdf = material_shot.principled("normal mapped", (0.6, 0.5, 0.3), 0.0, 0.35)
    material_shot.link_normal_map(material, bsdf, material_shot.ridges_image())
    return material


def emission_add_transparent():
    """Mix(0.7, Transparent, Add(Emission, Glossy)): an orange Emission of strength 0.3 added to a
    GGX Glossy BSDF of roughness 0.3, 30 % transparent."""
    material = bpy.data.materials.new("emission add transparent")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (1.0, 0.4, 0.1, 1.0)
    emission.inputs["Strength"].default_value = 0.3
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = "GGX"
    glossy.inputs["Roughness"].default_value = 0.3
    add = nodes.new("ShaderNodeAddShader")
    links.new(emission.outputs["Emission"], add.inputs[0])
    links.new(glossy.outputs["BSDF"], add.inputs[1])
    transparent = nodes.new("ShaderNodeBsdfTransparent")
    mix = nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.7
    links.new(transparent.outputs["BSDF"], mix.inputs[1])
    links.new(add.outputs["Shader"], mix.inputs[2])
    links.new(mix.outputs["Shader"], nodes["Material Output"].inputs["Surface"])
    return material


# Principled's Alpha 0.5 over a half clearcoat.
HALF_ALPHA = principled("half alpha", (0.2, 0.7, 0.3), 0.0, 0.3, Alpha=0.5, Clearcoat=0.5)


def stripes_image():
    """Eight vertical bands, alternately 0 and 1 (Non-Color: the values as they are), along the
    sphere's longitude (its U); a generated image, which the add-on saves beside the export."""
    image = bpy.data.images.new("stripes", STRIPES_PX, STRIPES_PX, alpha=False)
    image.colorspace_settings.name = "Non-Color"
    pixels = []
    for _ in range(STRIPES_PX):
        for col in range(STRIPES_PX):
            v = float((col * 8 // STRIPES_PX) % 2)
            pixels.extend((v, v, v, 1.0))
    image.pixels = pixels
    return image


def glossy_diffuse_mix():
    """A Mix Shader of a Diffuse BSDF (factor 0) and a GGX Glossy BSDF (factor 1) by the stripes'
    colour (a grey, whose luminance Cycles takes for the float factor)."""
    material = bpy.data.materials.new("glossy diffuse mix")
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.remove(nodes["Principled BSDF"])
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.7, 0.25, 0.1, 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = "GGX"
    glossy.inputs["Color"].default_value = (0.9, 0.9, 0.9, 1.0)
    glossy.inputs["Roughness"].default_value = 0.25
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = stripes_image()
    texture.interpolation = "Linear"
    mix = nodes.new("ShaderNodeMixShader")
    links.new(texture.outputs["Color"], mix.inputs["Fac"])
    links.new(diffuse.outputs["BSDF"], mix.inputs[1])
    links.new(glossy.outputs["BSDF"], mix.inputs[2])
    links.new(mix.outputs["Shader"], nodes["Material Output"].inputs["Surface"])
    return material


@dataclass(frozen=True)
class Shot:
    ground: object  # () -> material
    spheres: tuple  # three () -> material, left to right
    lights: tuple
    world: tuple = DIM_WORLD  # (colour, strength)


SHOTS = {
    "roughness_0.2": Shot(ground_at(0.2), spheres_at(0.2), (SUN,)),
    "roughness_0.5": Shot(ground_at(0.5), spheres_at(0.5), (SUN,)),
    "roughness_0.9": Shot(ground_at(0.9), spheres_at(0.9), (SUN,)),
    "layers": Shot(ground_at(0.5), (SHEEN, CLEARCOAT, SPECULAR_TINT), (SUN_BEHIND,)),
    "anisotropic": Shot(ground_at(0.5), ANISOTROPIC, (SUN, SUN_BEHIND)),
    "glass_mix": Shot(ground_at(0.5), (GLASS, glossy_diffuse_mix, MULTISCATTER),
                      (SUN_HIGH,)),
    "nodes": Shot(ground_at(0.5), (normal_mapped, emission_add_transparent, HALF_ALPHA),
                  (SUN_BEHIND,)),
    # The ordinary shot: every object in Blender's default material, the default scene's
    # point light and world, and a sun.
    "default": Shot(default_material, (default_material,) * 3, (SUN, DEFAULT_POINT),
                    world=DEFAULT_WORLD),
    # A point light of radius 0.4 m above the front right, alone with the dim world.
    "sphere_light": Shot(ground_at(0.5), spheres_at(0.3),
                         (Light("POINT", 600.0, location=(1.8, -1.2, 2.4), radius_m=0.4),)),
    # A disk area light 1.2 m across above the front left, facing the spheres.
    "disk_light": Shot(ground_at(0.5), spheres_at(0.3),
                       (Light("AREA", 400.0, location=(-1.6, -1.0, 2.6), target=(0.0, 0.0, 0.3),
                              size_m=1.2),)),
}


def add_light(scene, index, spec):
    data = bpy.data.lights.new(f"{spec.type.title()} {index}", spec.type)
    data.energy = spec.energy
    if spec.type == "POINT":
        data.shadow_soft_size = spec.radius_m
    if spec.type == "AREA":
        data.shape = "DISK"
        data.size = spec.size_m
    light = bpy.data.objects.new(data.name, data)
    scene.collection.objects.link(light)
    look_at(light, spec.location, spec.target)


def build(shot):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    make_shot.new_world(scene, *shot.world)
    material_shot.configure_cycles(scene, CAMERA)
    camera = make_shot.build_camera(scene, CAMERA)
    look_at(camera, CAMERA_LOCATION, CAMERA_TARGET)

    bpy.ops.mesh.primitive_plane_add(size=GROUND_SIZE_M, location=(0.0, 0.0, 0.0))
    ground = bpy.context.active_object
    ground.name = "ground"
    ground.data.materials.append(shot.ground())
    for i, (x, make_material) in enumerate(zip(SPHERE_X_M, shot.spheres)):
        material_shot.add_sphere(f"sphere {i}", (x, 0.0, SPHERE_RADIUS_M), SPHERE_RADIUS_M,
                                 make_material())
    for i, spec in enumerate(shot.lights):
        add_light(scene, i, spec)
    bpy.context.view_layer.update()
    return scene


def main():
    out_dir, name = make_shot.shot_arguments("principled_shot.py", SHOTS)
    shot = SHOTS[name]
    scene = build(shot)
    with open(os.path.join(out_dir, "manifest.txt"), "w") as manifest:
        manifest.write(make_shot.record("shot", name=name, samples=CAMERA.samples,
                                        width_px=CAMERA.width_px, height_px=CAMERA.height_px))
    material_shot.export_shot.export(os.path.join(out_dir, "shot.gltf"))
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main()
