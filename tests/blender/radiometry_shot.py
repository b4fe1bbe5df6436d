"""The Blender side of the radiometry tests (tests/blender/blender_radiometry_test.cpp).

Builds one shot of SHOTS (a ground plane with a box and a sphere, lit by Blender lights and a
uniform world; diffuse everywhere, or with a glossy metal ground in which the lights' shapes are
seen), exports it with Blender's own glTF exporter and renders it with Cycles:

    blender -b --factory-startup --python radiometry_shot.py -- OUTDIR SHOT

writes OUTDIR/shot.gltf (+ shot.bin), OUTDIR/cycles.exr and OUTDIR/manifest.txt (one "shot"
record: name, samples, width_px, height_px), as make_shot.py does, whose Cycles settings and
export it borrows.

The materials are Diffuse BSDFs (roughness 0: Lambertian), and a glossy ground a Principled metal
(metallic 1, GGX); the export goes through filmback's add-on (importers/blender/export_shot.py),
which writes their node trees, the lights (area lights included) and the world, image and all, in
the FILMBACK_blender extension, so that filmback renders the same closures as Cycles.

Cycles renders with max_bounces = diffuse_bounces = glossy_bounces = 7, which is filmback's default
path depth of 8 (max_depth counts the direct-light bounce, Cycles' bounces do not), no clamping,
no light threshold and no Filter Glossy, so both estimate the same integral.
"""

import math
import os
import sys
from dataclasses import dataclass

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_shot  # noqa: E402  (Blender runs this file as __main__, so import by path)


@dataclass(frozen=True)
class LightSpec:
    name: str
    type: str  # POINT, SPOT, SUN, AREA
    location: tuple
    target: tuple  # where its -Z axis points
    energy: float  # W, or W/m^2 for a sun
    colour: tuple = (1.0, 1.0, 1.0)
    radius: float = 0.0  # point and spot shadow_soft_size
    spot_size_deg: float = 45.0
    spot_blend: float = 0.15
    angle_deg: float = 0.0  # sun
    shape: str = "SQUARE"
    size: float = 1.0
    size_y: float = 1.0
    spread_deg: float = 180.0


@dataclass(frozen=True)
class Shot:
    lights: tuple
    world_colour: tuple = (0.0, 0.0, 0.0)
    world_strength: float = 0.0
    sky: bool = False  # an equirectangular image (make_sky) through an Environment Texture
    glossy_ground: float = 0.0  # > 0: the ground is a grey metal of this roughness
    objects: bool = True  # the box and the sphere on the ground
    # A second Cycles render with another seed (cycles_seed2.exr), whose difference from the first
    # is the shot's noise floor: for shots whose noise at an affordable sample count is above the
    # test's bar (blender_radiometry_test.cpp).
    noise_floor: bool = False
    width_px: int = 128
    height_px: int = 96
    samples: int = 1024


SHOTS = {
    # A 10-degree sun from the front left and a blue-grey sky.
    "sun_world": Shot((LightSpec("Sun", "SUN", (0, 0, 5), (1.2, 2.0, 0.0), 3.0,
                                 colour=(1.0, 0.95, 0.85), angle_deg=10.0),),
                      world_colour=(0.25, 0.32, 0.45), world_strength=0.8),
    # A soft point light and a soft, blended spot, both above the frame. (It needed 4096 spp while
    # filmback reached these lights by light sampling alone; with MIS 1024 are enough.)
    "point_spot": Shot((LightSpec("Point", "POINT", (-2.0, -1.0, 4.0), (0, 0, 0), 600.0,
                                  colour=(1.0, 0.9, 0.8), radius=0.3),
                        LightSpec("Spot", "SPOT", (1.8, -1.5, 4.2), (0.6, 0.4, 0.0), 1500.0,
                                  colour=(0.8, 0.9, 1.0), radius=0.1, spot_size_deg=50.0,
                                  spot_blend=0.4))),
    # A rectangle and a disk area light; the disk is in the frame, its lit face towards the
    # camera, which (in Cycles as in filmback) does not see it.
    "area": Shot((LightSpec("Square", "AREA", (-1.4, -0.6, 3.5), (-0.3, 0.2, 0.0), 500.0,
                            colour=(1.0, 0.9, 0.75), shape="RECTANGLE", size=1.5, size_y=0.8),
                  LightSpec("Disk", "AREA", (1.7, 1.2, 2.2), (0.3, 0.0, 0.0), 250.0,
                            colour=(0.75, 0.85, 1.0), shape="DISK", size=0.8))),
    # No lights: an environment image with a bright patch (a low sun) and a sky gradient, which
    # tests its orientation (the shadows' direction) and importance sampling.
    "hdr_world": Shot((), world_strength=1.5, sky=True, samples=2048),
    # Cycles 3.4's lights with a size seen in a glossy metal ground (roughness 0.15), each placed
    # where the ground mirrors it towards the camera (about 1.5 m in front of the origin), so that
    # BSDF-sampled rays find most of its highlight. The point light's shot has no objects: in a
    # metal ground they would be lit by caustics, whose noise (in both renderers) would hide the
    # highlight's radiometry at this sample count.
    "point_glossy": Shot((LightSpec("Point", "POINT", (-0.19, 1.31, 2.0), (0, 0, 0), 300.0,
                                    colour=(1.0, 0.92, 0.8), radius=0.3),),
                         glossy_ground=0.15, objects=False),
    "sun_glossy": Shot((LightSpec("Sun", "SUN", (0, 0, 5), (0.3, -4.5, 1.8), 3.0,
                                  colour=(1.0, 0.95, 0.85), angle_deg=10.0),),
                       world_colour=(0.25, 0.32, 0.45), world_strength=0.3, glossy_ground=0.15),
    # The lights below light much of the frame only indirectly, whose noise a dim grey world
    # (irradiance 0.47 W/m^2, a tenth of the lights') keeps from dominating the comparison.
    # A spot of radius 0.4 m, its soft edge (blend 0.3) across the sphere.
    "spot_radius": Shot((LightSpec("Spot", "SPOT", (1.5, -1.5, 3.5), (0.2, 0.3, 0.0), 1200.0,
                                   colour=(0.9, 0.95, 1.0), radius=0.4, spot_size_deg=50.0,
                                   spot_blend=0.3),),
                        world_colour=(1.0, 1.0, 1.0), world_strength=0.15),
    # A disk and an ellipse area light, each sampled uniformly over its area as Cycles does.
    "disk_ellipse": Shot((LightSpec("Disk", "AREA", (-1.6, -0.8, 2.8), (-0.4, 0.3, 0.0), 300.0,
                                    colour=(1.0, 0.9, 0.75), shape="DISK", size=0.9),
                          LightSpec("Ellipse", "AREA", (1.6, 0.8, 2.5), (0.5, 0.2, 0.0), 300.0,
                                    colour=(0.75, 0.85, 1.0), shape="ELLIPSE", size=1.6,
                                    size_y=0.5)),
                         world_colour=(1.0, 1.0, 1.0), world_strength=0.15),
    # A 2.5 x 1.5 m rectangle of spread 30 degrees 2.5 m over the objects: a lit patch of about
    # 3.8 x 2.8 m with a soft rim, the light sampled over the part of it the spread lets reach
    # each point.
    # Cycles samples its radiance, peaked towards the normal (44 times P / (4 A) there), uniformly
    # over that part, so each pixel's noise is about 5 % at 1024 spp in Cycles as in filmback:
    # the shot measures its noise floor.
    "spread": Shot((LightSpec("Softbox", "AREA", (0.0, 0.3, 2.5), (0.0, 0.3, 0.0), 600.0,
                              shape="RECTANGLE", size=2.5, size_y=1.5, spread_deg=30.0),),
                   world_colour=(1.0, 1.0, 1.0), world_strength=0.15, noise_floor=True),
}

CAMERA_LOCATION = (0.3, -6.0, 3.2)
CAMERA_TARGET = (0.0, 0.2, 0.45)


SKY_SIZE = (64, 32)


def make_sky(path):
    """A 64x32 equirectangular sky written as a Radiance .hdr (flat RGBE scanlines, top row
    first; Blender would colour-manage an image it saves itself): blue above the horizon, brown
    below, and a 4x3-texel patch about 100 times brighter some 25 degrees up, lighting the scene
    from the back left. Returns it loaded into Blender, which reads the same file as filmback."""
    width, height = SKY_SIZE
    data = bytearray()
    for row in range(height):  # from the top
        elevation = math.pi / 2 - (row + 0.5) / height * math.pi
        for column in range(width):
            if elevation > 0:
                colour = (0.3 + 0.3 * (1 - math.sin(elevation)), 0.45, 0.9)
            else:
                colour = (0.25, 0.2, 0.15)
            if 38 <= column < 42 and 10 <= row < 13:
                colour = (60.0, 50.0, 40.0)
            mantissa, exponent = math.frexp(max(colour))
            scale = mantissa * 256.0 / max(colour)
            data += bytes([int(c * scale) for c in colour] + [exponent + 128])
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(f"-Y {height} +X {width}\n".encode())
        f.write(bytes(data))
    return bpy.data.images.load(path)


def look_at(obj, location, target):
    obj.location = location
    direction = Vector(target) - Vector(location)
    obj.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()


def diffuse(name, colour):
    """A material of one Diffuse BSDF (roughness 0: Lambertian)."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.0
    output = nodes.new("ShaderNodeOutputMaterial")
    links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])
    return material


def glossy_metal(name, colour, roughness):
    """A Principled metal with GGX (Blender 3.4's other choice, Multiscatter GGX, is not glTF's)."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.distribution = "GGX"
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Metallic"].default_value = 1.0
    bsdf.inputs["Roughness"].default_value = roughness
    return material


def build_geometry(scene, shot):
    bpy.ops.mesh.primitive_plane_add(size=12.0, location=(0, 0, 0))
    ground = bpy.context.object
    if shot.glossy_ground > 0:
        ground.data.materials.append(glossy_metal("Ground", (0.8, 0.8, 0.8), shot.glossy_ground))
    else:
        ground.data.materials.append(diffuse("Ground", (0.55, 0.55, 0.5)))
    if not shot.objects:
        return
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.9, 0.5, 0.5), rotation=(0, 0, 0.5))
    cube = bpy.context.object
    cube.data.materials.append(diffuse("Box", (0.8, 0.35, 0.2)))
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=0.6,
                                         location=(-0.9, 0.1, 0.6))
    sphere = bpy.context.object
    bpy.ops.object.shade_smooth()
    sphere.data.materials.append(diffuse("Sphere", (0.25, 0.6, 0.35)))


def add_light(scene, spec):
    data = bpy.data.lights.new(spec.name, spec.type)
    data.energy = spec.energy
    data.color = spec.colour
    if spec.type in {"POINT", "SPOT"}:
        data.shadow_soft_size = spec.radius
    if spec.type == "SPOT":
        data.spot_size = math.radians(spec.spot_size_deg)
        data.spot_blend = spec.spot_blend
    if spec.type == "SUN":
        data.angle = math.radians(spec.angle_deg)
    if spec.type == "AREA":
        data.shape = spec.shape
        data.size, data.size_y = spec.size, spec.size_y
        data.spread = math.radians(spec.spread_deg)
    obj = bpy.data.objects.new(spec.name, data)
    scene.collection.objects.link(obj)
    look_at(obj, spec.location, spec.target)
    return obj


def build(out_dir, name, shot, before_export=None):
    """Builds `shot` in a new scene and exports it to OUT_DIR/shot.gltf with the manifest; returns
    the scene, ready to render. `before_export`, when given, is called with the scene just before
    the export (look_shot.py sets Blender's Color Management there)."""
    os.makedirs(out_dir, exist_ok=True)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    background = make_shot.new_world(scene, shot.world_colour, shot.world_strength)
    if shot.sky:
        tree = background.id_data
        texture = tree.nodes.new("ShaderNodeTexEnvironment")
        texture.image = make_sky(os.path.join(out_dir, "sky.hdr"))
        tree.links.new(texture.outputs["Color"], background.inputs["Color"])

    make_shot.configure_cycles(scene, shot)
    cycles = scene.cycles
    cycles.max_bounces = cycles.diffuse_bounces = cycles.glossy_bounces = 7
    cycles.caustics_reflective = True
    cycles.blur_glossy = 0.0  # Filter Glossy widens glossy lobes after a bounce; filmback does not
    cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0
    cycles.light_sampling_threshold = 0.0
    camera_data = bpy.data.cameras.new("Camera")
    camera_data.lens, camera_data.sensor_width, camera_data.sensor_fit = 35.0, 36.0, "AUTO"
    camera = bpy.data.objects.new("Camera", camera_data)
    scene.collection.objects.link(camera)
    look_at(camera, CAMERA_LOCATION, CAMERA_TARGET)
    scene.camera = camera
    build_geometry(scene, shot)
    for spec in shot.lights:
        add_light(scene, spec)
    bpy.context.view_layer.update()
    if before_export:
        before_export(scene)

    with open(os.path.join(out_dir, "manifest.txt"), "w") as manifest:
        fields = {"second_cycles": "cycles_seed2.exr"} if shot.noise_floor else {}
        manifest.write(make_shot.record("shot", name=name, samples=shot.samples,
                                        width_px=shot.width_px, height_px=shot.height_px,
                                        **fields))
    gltf_path = os.path.join(out_dir, "shot.gltf")
    make_shot.export_shot.export(gltf_path)  # filmback's add-on: materials, lights and world
    return scene


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 2 or args[1] not in SHOTS:
        raise SystemExit("usage: blender -b --factory-startup --python radiometry_shot.py -- "
                         "OUTDIR SHOT\nshots: " + " ".join(SHOTS))
    out_dir, name = os.path.abspath(args[0]), args[1]
    shot = SHOTS[name]
    scene = build(out_dir, name, shot)
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)
    if shot.noise_floor:
        scene.cycles.seed = 2
        scene.render.filepath = os.path.join(out_dir, "cycles_seed2.exr")
        bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main()
