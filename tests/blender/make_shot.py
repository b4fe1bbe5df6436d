"""The Blender side of the tests against Blender (tests/blender/blender_alignment_test.cpp).

Builds one shot of the table SHOTS: small emissive spheres ("markers") on a black world, seen by a
rotated, displaced camera with the shot's lens, sensor, fit, shift and aperture. Exports the scene
through filmback's add-on (importers/blender/export_shot.py: Blender's own glTF exporter plus the
FILMBACK_blender extension) and renders it with Cycles.

    blender -b --factory-startup --python make_shot.py -- OUTDIR SHOT

writes OUTDIR/shot.gltf (+ shot.bin), OUTDIR/cycles.exr (32-bit float, scene-linear) and
OUTDIR/manifest.txt, one record a line, "KIND key=value ...":
  shot    name, samples (per pixel, for both renderers), width_px, height_px, camera_model (the
          filmback camera the shot needs: perspective or thinlens), aperture_blades
  marker  name; blender_x_px, blender_y_px: Blender's projection of the sphere's centre
          (bpy_extras.object_utils.world_to_camera_view); image_x_px, image_y_px: the centre of
          the sphere's image, an ellipse off the axis; diameter_x_px, diameter_y_px: the expected
          disk diameters of the blob along x and y (blobs.h: the sphere's image and the aperture's
          image, moments added); vertex_angle_rad: the raster angle of a bokeh polygon's vertex,
          or nan when the blob has no polygonal shape to measure.
Raster convention of docs/conventions.md: origin at the top-left corner, y down.
"""

import math
import os
import sys
from dataclasses import dataclass

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Euler, Vector

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "importers",
                                "blender"))
import export_shot  # noqa: E402  (filmback's add-on, enabled for this session)


@dataclass(frozen=True)
class Marker:
    name: str
    u: float  # where the centre images, as fractions of the frame's width and height from its
    v: float  # top-left corner
    depth_m: float  # along the view axis
    radius_px: float  # of the sphere's image, near the axis
    colour: tuple
    strength: float  # above 1 the exporter writes KHR_materials_emissive_strength


@dataclass(frozen=True)
class Aperture:
    fstop: float
    focus_m: float  # focus distance along the view axis
    # Focus on an empty at these frame fractions (at depth focus_m) instead of a distance: Blender
    # then focuses on its plane, not at its Euclidean distance. focus_distance is set wrong on purpose.
    focus_object_uv: tuple | None = None
    blades: int = 0
    rotation_deg: float = 0.0
    ratio: float = 1.0


@dataclass(frozen=True)
class Shot:
    width_px: int
    height_px: int
    lens_mm: float
    markers: tuple
    sensor_mm: tuple = (36.0, 24.0)
    sensor_fit: str = "AUTO"
    shift: tuple = (0.0, 0.0)
    clip_m: tuple = (0.1, 200.0)
    depth_scale: float = 1.0  # multiplies every marker's depth
    aperture: Aperture | None = None
    samples: int = 512
    origin_m: tuple = (0.0, 0.0, 0.0)  # added to the camera's location (markers follow it)
    ortho_scale_m: float | None = None  # an orthographic camera of this scale


# Markers at the frame's corners and edges, where the projection is most off-axis, and in the
# middle; fractional positions, depths 3-40 m, colours and strengths that differ.
FRAME_MARKERS = (
    Marker("corner_top_left", 0.0572, 0.0835, 6.0, 5.0, (1.0, 1.0, 1.0), 1.0),
    Marker("corner_top_right", 0.9300, 0.0700, 18.0, 4.0, (0.6, 0.8, 1.0), 3.0),
    Marker("corner_bottom_right", 0.9394, 0.9260, 14.0, 4.5, (1.0, 0.6, 0.3), 5.0),
    Marker("edge_right", 0.9544, 0.3545, 3.0, 6.5, (0.2, 0.5, 1.0), 0.8),
    Marker("edge_top", 0.4713, 0.0620, 25.0, 3.5, (1.0, 1.0, 1.0), 12.0),
    Marker("centre", 0.5006, 0.4980, 4.0, 9.0, (0.9, 0.9, 0.2), 2.5),
    Marker("corner_bottom_left", 0.0709, 0.9065, 9.0, 5.5, (0.4, 1.0, 0.4), 1.5),
    Marker("far", 0.7222, 0.6440, 40.0, 3.0, (1.0, 0.3, 0.8), 20.0),
)

# Around a focus plane at 3 m: two markers on it (one near a corner), two in front, two behind.
# The spheres are large enough (5 px) that about 80 000 lens rays at 1024 spp reach each one:
# flux noise about 0.4 % per renderer.
FOCUS_MARKERS = (
    Marker("in_focus_centre", 0.50, 0.50, 3.0, 4.0, (1.0, 1.0, 1.0), 4.0),
    Marker("in_focus_corner", 0.10, 0.12, 3.0, 4.0, (0.6, 0.8, 1.0), 4.0),
    Marker("front_near", 0.25, 0.32, 1.0, 5.0, (1.0, 0.6, 0.3), 20.0),
    Marker("front", 0.76, 0.26, 1.5, 5.0, (0.2, 0.5, 1.0), 12.0),
    Marker("behind", 0.30, 0.76, 6.0, 5.0, (0.4, 1.0, 0.4), 10.0),
    Marker("behind_far", 0.72, 0.70, 40.0, 5.0, (1.0, 0.3, 0.8), 20.0),
)

# Bokeh around a focus plane at 1.5 m: polygons of circumradius 11-15 px, at least twice the
# sphere's own image, so that their shape and orientation can be measured.
BOKEH_MARKERS = (
    Marker("in_focus_centre", 0.50, 0.50, 1.5, 4.0, (1.0, 1.0, 1.0), 4.0),
    Marker("front_left", 0.20, 0.30, 0.8, 5.0, (1.0, 0.6, 0.3), 20.0),
    Marker("front_right", 0.80, 0.72, 0.8, 5.0, (0.2, 0.5, 1.0), 12.0),
    Marker("behind_left", 0.25, 0.75, 6.0, 5.0, (0.4, 1.0, 0.4), 10.0),
    Marker("behind_right", 0.78, 0.26, 50.0, 5.0, (1.0, 0.3, 0.8), 20.0),
)

SHOTS = {
    # Blender's default camera: 50 mm on 36 x 24 mm, fit AUTO, at 16:9.
    "default_50mm": Shot(320, 180, 50.0, FRAME_MARKERS),
    # The reference frame: landscape 320x200, 35 mm on a 36 mm sensor, fit AUTO (horizontal).
    "landscape_auto": Shot(320, 200, 35.0, FRAME_MARKERS),
    # Landscape, fit VERTICAL: sensor_height (20 mm) spans the image height.
    "vertical_fit": Shot(320, 200, 30.0, FRAME_MARKERS, sensor_mm=(36.0, 20.0), sensor_fit="VERTICAL"),
    # Portrait with AUTO: the fit turns vertical and sensor_width spans the image *height*.
    "portrait_auto": Shot(200, 320, 35.0, FRAME_MARKERS),
    # Shift with a horizontal fit: both shifts are fractions of the image width.
    "lens_shift": Shot(320, 200, 35.0, FRAME_MARKERS, shift=(0.1, -0.07)),
    # Shift in a portrait frame with a vertical fit: fractions of the image height.
    "portrait_vertical_shift": Shot(200, 320, 40.0, FRAME_MARKERS, sensor_mm=(36.0, 30.0),
                                    sensor_fit="VERTICAL", shift=(-0.08, 0.12)),
    # 12 mm on 36 mm: 112 deg across, the corner markers about 60 deg off the axis.
    "wide_12mm": Shot(320, 240, 12.0, FRAME_MARKERS, depth_scale=0.15),
    # 600 mm: 3.4 deg across, markers 0.5-6 km away.
    "tele_600mm": Shot(320, 200, 600.0, FRAME_MARKERS, depth_scale=150.0, clip_m=(1.0, 10000.0)),
    # f/1.4 on 85 mm focused on an empty 3 m deep (off the axis); circles of confusion 8-31 px.
    "dof_f1_4": Shot(320, 240, 85.0, FOCUS_MARKERS, samples=1024,
                     aperture=Aperture(1.4, 3.0, focus_object_uv=(0.9, 0.85))),
    # The frame 1.4e5 m from the origin, where float32 world coordinates are 8-16 mm apart:
    # Cycles keeps its meshes in float32 world space, so the markers are 10x as deep (and as
    # large) for its spheres to keep their shape (at 1x Cycles' own images are 5 % off the math;
    # filmback's, traced in camera-centred space, 0.2 %).
    "far_from_origin": Shot(320, 200, 35.0, FRAME_MARKERS, depth_scale=10.0,
                            clip_m=(1.0, 1000.0), origin_m=(1.2e5, -0.7e5, 0.3e5)),
    # Orthographic, 12 m across, fit AUTO: markers keep their image size at every depth.
    "orthographic": Shot(320, 200, 35.0, FRAME_MARKERS, ortho_scale_m=12.0),
    # Six blades rotated 10 deg: hexagonal bokeh whose orientation is measured.
    "bokeh_hexagon": Shot(320, 240, 85.0, BOKEH_MARKERS, samples=1024,
                          aperture=Aperture(1.4, 1.5, blades=6, rotation_deg=10.0)),
    # Anamorphic ratio 2: the aperture, and so the bokeh, half as wide as high.
    "bokeh_anamorphic": Shot(320, 240, 85.0, BOKEH_MARKERS, samples=1024,
                             aperture=Aperture(1.4, 1.5, ratio=2.0)),
}

CAMERA_LOCATION = (3.2, -6.5, 2.1)
CAMERA_ROTATION_DEG = (74.0, -8.0, 23.0)


def focus_distance_m(camera_object):
    """Cycles' focus distance (intern/cycles/blender/camera.cpp, blender_camera_focal_distance):
    with a focus object, its distance along the camera's Z axis, not its Euclidean distance."""
    dof = camera_object.data.dof
    if dof.focus_object is None:
        return dof.focus_distance
    if dof.focus_subtarget:
        raise ValueError("a focus bone (focus_subtarget) is not carried")
    matrix = camera_object.matrix_world.normalized()
    view_axis = matrix.col[2].xyz.normalized()
    return abs(view_axis.dot(matrix.translation - dof.focus_object.matrix_world.translation))


def new_world(scene, colour=(0.0, 0.0, 0.0), strength=0.0):
    """A node world of uniform radiance colour x strength (black by default); returns its
    Background node."""
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*colour, 1.0)
    background.inputs["Strength"].default_value = strength
    scene.world = world
    return background


def build_camera(scene, shot):
    data = bpy.data.cameras.new("Camera")
    data.type = "ORTHO" if shot.ortho_scale_m else "PERSP"
    if shot.ortho_scale_m:
        data.ortho_scale = shot.ortho_scale_m
    data.lens = shot.lens_mm
    data.sensor_width, data.sensor_height = shot.sensor_mm
    data.sensor_fit = shot.sensor_fit
    data.shift_x, data.shift_y = shot.shift
    data.clip_start, data.clip_end = shot.clip_m
    camera = bpy.data.objects.new("Camera", data)
    camera.location = Vector(CAMERA_LOCATION) + Vector(shot.origin_m)
    camera.rotation_euler = Euler([math.radians(a) for a in CAMERA_ROTATION_DEG], "XYZ")
    scene.collection.objects.link(camera)
    scene.camera = camera
    return camera


class Frame:
    """Blender's own view frame (Camera.view_frame: sensor, fit and shift applied), the only
    source of the projection here: camera-space points for frame positions and pixel scales."""

    def __init__(self, scene, camera):
        corners = camera.data.view_frame(scene=scene)  # top-right, bottom-right, bottom-left, top-left
        self.top_left, self.top_right, self.bottom_left = corners[3], corners[0], corners[2]
        self.depth = -corners[0].z
        self.ortho = camera.data.type == "ORTHO"
        # Pixels per metre at the frame's depth; an orthographic frame has it at every depth.
        self.px_per_unit = scene.render.resolution_x * (1.0 if self.ortho else self.depth) / (
            self.top_right.x - self.top_left.x)

    def point(self, u, v, depth_m):
        across, down = self.top_right - self.top_left, self.bottom_left - self.top_left
        on_frame = self.top_left + u * across + v * down
        if self.ortho:
            return Vector((on_frame.x, on_frame.y, -depth_m))
        return on_frame * (depth_m / self.depth)

    def metres_per_px(self, depth_m):
        return (1.0 if self.ortho else depth_m) / self.px_per_unit


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


def add_sphere(camera, frame, marker, depth_m):
    radius_m = marker.radius_px * frame.metres_per_px(depth_m)
    location = camera.matrix_world @ frame.point(marker.u, marker.v, depth_m)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=radius_m, location=location)
    sphere = bpy.context.active_object
    sphere.name = marker.name
    bpy.ops.object.shade_smooth()
    sphere.data.materials.append(emission_material(marker.name, marker.colour, marker.strength))
    return sphere, radius_m


def add_focus_object(scene, camera, frame, aperture):
    target = bpy.data.objects.new("FocusTarget", None)
    target.location = camera.matrix_world @ frame.point(*aperture.focus_object_uv, aperture.focus_m)
    scene.collection.objects.link(target)
    camera.data.dof.focus_object = target
    camera.data.dof.focus_distance = 2 * aperture.focus_m  # unused: the object takes precedence


def configure_dof(scene, camera, frame, aperture):
    dof = camera.data.dof
    dof.use_dof = True
    dof.aperture_fstop = aperture.fstop
    dof.aperture_blades = aperture.blades
    dof.aperture_rotation = math.radians(aperture.rotation_deg)
    dof.aperture_ratio = aperture.ratio
    if aperture.focus_object_uv:
        add_focus_object(scene, camera, frame, aperture)
    else:
        dof.focus_distance = aperture.focus_m


def aperture_spread(blades):
    """<x^2> = <y^2> of a uniform aperture of circumradius 1: a disk 1/4; a regular n-gon
    (2 + cos(2 pi / n)) / 12, half its <r^2>, which each of its triangles (0, a, b) from the centre
    gives as (|a|^2 + |b|^2 + a.b) / 6."""
    return 0.25 if blades == 0 else (2 + math.cos(2 * math.pi / blades)) / 12


def expected_image(scene, camera, frame, sphere, radius_m):
    """The sphere's image through Blender's camera: where it is, its size, its bokeh's angle."""
    to_camera = camera.matrix_world.normalized().inverted()
    centre = to_camera @ sphere.matrix_world.translation
    w, h = scene.render.resolution_x, scene.render.resolution_y
    if frame.ortho:
        # A parallel projection images a sphere as a disk of its own radius, at its centre's place.
        image = world_to_camera_view(scene, camera, sphere.matrix_world.translation)
        diameter_px = 2 * radius_m * frame.px_per_unit
        return {"image_x_px": image.x * w, "image_y_px": (1 - image.y) * h,
                "diameter_x_px": diameter_px, "diameter_y_px": diameter_px,
                "vertex_angle_rad": math.nan}
    distance, depth = centre.length, -centre.z
    # The pinhole image of a sphere of angular radius a seen at t off the axis is an ellipse:
    # with k = cos^2 t - sin^2 a, semi-axes sin a cos a / k radially and sin a / sqrt(k)
    # tangentially, centred where the centre's direction, moved sideways by cos^2 t / k, meets
    # the frame (the cone x.c = |x| cos a cut by the plane z = -1).
    sin_a, cos_t = radius_m / distance, depth / distance
    cos_a, k = math.sqrt(1 - sin_a**2), cos_t**2 - sin_a**2
    radial_px = frame.px_per_unit * sin_a * cos_a / k
    tangential_px = frame.px_per_unit * sin_a / math.sqrt(k)
    lateral = math.hypot(centre.x, centre.y)
    ux, uy = (centre.x / lateral, -centre.y / lateral) if lateral > 0 else (1.0, 0.0)
    image_centre = Vector((centre.x * cos_t**2 / k, centre.y * cos_t**2 / k, centre.z))
    xx = (radial_px**2 * ux**2 + tangential_px**2 * uy**2) / 4
    yy = (radial_px**2 * uy**2 + tangential_px**2 * ux**2) / 4
    angle = math.nan
    dof = camera.data.dof
    if dof.use_dof:
        # Cycles' thin lens (kernel/camera/camera.h): a lens point l (m) on an aperture of radius
        # f / 2N moves the image of a point at depth D by px_per_unit * l * (1/D_f - 1/D), x and -y.
        radius = camera.data.lens * 1e-3 / (2 * dof.aperture_fstop)
        scale_px = frame.px_per_unit * radius * (1 / focus_distance_m(camera) - 1 / depth)
        blades = dof.aperture_blades if dof.aperture_blades >= 3 else 0
        xx += scale_px**2 * aperture_spread(blades) / dof.aperture_ratio**2
        yy += scale_px**2 * aperture_spread(blades)
        if blades and dof.aperture_ratio == 1 and abs(scale_px) > 2 * radial_px:
            # Cycles' polygon (kernel/sample/mapping.h, regular_polygon_sample) has its vertices
            # at rotation + pi/n + 2 pi j/n on the lens (x right, y up); the image flips y, and in
            # front of the focus plane (scale < 0) turns it by pi too.
            lens_angle = dof.aperture_rotation + math.pi / blades
            raster_angle = -lens_angle + (math.pi if scale_px < 0 else 0.0)
            sector = 2 * math.pi / blades
            angle = math.remainder(raster_angle, sector)
    image = world_to_camera_view(scene, camera, camera.matrix_world.normalized() @ image_centre)
    return {
        "image_x_px": image.x * w,
        "image_y_px": (1 - image.y) * h,
        "diameter_x_px": 4 * math.sqrt(xx),
        "diameter_y_px": 4 * math.sqrt(yy),
        "vertex_angle_rad": angle,
    }


def configure_cycles(scene, shot):
    scene.render.engine = "CYCLES"
    scene.render.resolution_x, scene.render.resolution_y = shot.width_px, shot.height_px
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0
    scene.render.use_motion_blur = False
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = shot.samples
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


def export(path):
    """Through filmback's add-on: Blender's glTF exporter plus the FILMBACK_blender extension."""
    export_shot.export(path, export_lights=False)


def export_and_render_layers(scene, out_dir):
    """OUT_DIR/shot.gltf through the add-on, and Cycles' render of `scene` with its view layer's
    passes to OUT_DIR/cycles.exr, a 32-bit multi-layer EXR."""
    export(os.path.join(out_dir, "shot.gltf"))
    image = scene.render.image_settings
    image.file_format = "OPEN_EXR_MULTILAYER"
    image.color_depth = "32"
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


def record(kind, **fields):
    def text(value):
        return f"{value:.6f}" if isinstance(value, float) else str(value)
    return kind + "".join(f" {key}={text(value)}" for key, value in fields.items()) + "\n"


def shot_arguments(script, shots):
    """OUTDIR (absolute, created) and SHOT from `blender ... --python SCRIPT -- OUTDIR SHOT`; exits
    with the usage and the names in `shots` when they are not that."""
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 2 or args[1] not in shots:
        raise SystemExit(f"usage: blender -b --factory-startup --python {script} -- OUTDIR SHOT\n"
                         "shots: " + " ".join(shots))
    out_dir = os.path.abspath(args[0])
    os.makedirs(out_dir, exist_ok=True)
    return out_dir, args[1]


def main():
    out_dir, name = shot_arguments("make_shot.py", SHOTS)
    shot = SHOTS[name]

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    new_world(scene)

    configure_cycles(scene, shot)
    camera = build_camera(scene, shot)
    bpy.context.view_layer.update()
    frame = Frame(scene, camera)
    if shot.aperture:
        configure_dof(scene, camera, frame, shot.aperture)
    spheres = [(marker, *add_sphere(camera, frame, marker, marker.depth_m * shot.depth_scale))
               for marker in shot.markers]
    bpy.context.view_layer.update()

    w, h = shot.width_px, shot.height_px
    with open(os.path.join(out_dir, "manifest.txt"), "w") as manifest:
        manifest.write(record("shot", name=name, samples=shot.samples, width_px=w, height_px=h,
                              camera_model="orthographic" if shot.ortho_scale_m else
                              "thinlens" if shot.aperture else "perspective",
                              aperture_blades=shot.aperture.blades if shot.aperture else 0))
        for marker, sphere, radius_m in spheres:
            centre = world_to_camera_view(scene, camera, sphere.matrix_world.translation)
            manifest.write(record("marker", name=marker.name, blender_x_px=centre.x * w,
                                  blender_y_px=(1.0 - centre.y) * h,
                                  **expected_image(scene, camera, frame, sphere, radius_m)))

    export(os.path.join(out_dir, "shot.gltf"))

    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


# Blender runs --python scripts as __main__; motion_shot.py imports this file for its helpers.
if __name__ == "__main__":
    main()
