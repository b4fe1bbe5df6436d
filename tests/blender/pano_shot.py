"""The Blender side of the panoramic camera tests (tests/blender/blender_panorama_test.cpp).

Builds one shot of the table SHOTS: a panoramic camera of one of Cycles 3.4's types, a dim uniform
world (so that a fisheye's circle shows) and small emissive spheres ("markers") placed where the
shot's projection images them: at the centre, near a fisheye's rim, near the poles and on both
sides of an equirectangular seam. Exports it through filmback's add-on (which writes the panorama
Blender's own glTF exporter drops) and renders it with Cycles, as make_shot.py does.

    blender -b --factory-startup --python pano_shot.py -- OUTDIR SHOT

writes OUTDIR/shot.gltf, OUTDIR/cycles.exr and OUTDIR/manifest.txt:
  shot    name, samples, width_px, height_px, camera_model (the filmback camera plugin),
          world (R+G+B of the world's radiance: a blob is brighter than it)
  marker  name; image_x_px, image_y_px: where the projection images the sphere's centre.
The projections here are the test's own reading of Cycles' definitions (docs/camera-model.md,
"Panoramic cameras"), in Blender's camera space (-Z forward, +Y up); Cycles' render checks them.
"""

import math
import os
import sys
from dataclasses import dataclass, field

import bpy
from mathutils import Euler, Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_shot  # noqa: E402  (its Cycles settings, materials, export and manifest records)


def fisheye(theta, x, y):
    r = math.hypot(x, y)
    ex, ey = (x / r, y / r) if r > 0 else (0.0, 1.0)
    return Vector((ex * math.sin(theta), ey * math.sin(theta), -math.cos(theta)))


def equirectangular(u, v, s):
    lon = s["longitude_min"] + (s["longitude_max"] - s["longitude_min"]) * u
    lat = s["latitude_min"] + (s["latitude_max"] - s["latitude_min"]) * v
    return Vector((math.cos(lat) * math.sin(lon), math.sin(lat), -math.cos(lat) * math.cos(lon)))


def equidistant(u, v, s):
    x, y = 2 * (u - 0.5), 2 * (v - 0.5)
    return fisheye(math.hypot(x, y) * s["fisheye_fov"] / 2, x, y)


def equisolid(u, v, s, sensor_mm):
    x, y = (u - 0.5) * sensor_mm[0], (v - 0.5) * sensor_mm[1]
    return fisheye(2 * math.asin(math.hypot(x, y) / (2 * s["fisheye_lens"])), x, y)


def polynomial(u, v, s, sensor_mm):
    x, y = (u - 0.5) * sensor_mm[0], (v - 0.5) * sensor_mm[1]
    r = math.hypot(x, y)
    theta = -sum(s[f"fisheye_polynomial_k{i}"] * r**i for i in range(5))
    return fisheye(theta, x, y)


def mirrorball(u, v, s):
    x, y = 2 * u - 1, 2 * v - 1
    w = math.sqrt(1 - x * x - y * y)
    return Vector((2 * w * x, 2 * w * y, 1 - 2 * w * w))


@dataclass(frozen=True)
class PanoShot:
    width_px: int
    height_px: int
    panorama_type: str  # Blender's (cam.cycles.panorama_type)
    kind: str  # filmback's camera plugin
    settings: dict  # cam.cycles values
    direction: object  # (u, v, settings, sensor_mm) -> camera-space direction
    markers: tuple  # (name, x, y): raster fractions from the top-left corner
    sensor_mm: tuple = (36.0, 24.0)
    samples: int = 64
    world: float = 0.02  # the world's radiance, each channel
    options: dict = field(default_factory=dict)


# Fractions of the frame on a circle of radius r (in units of the half-frame) at angle a (deg,
# counter-clockwise from +x), for markers along a fisheye's rim.
def on_circle(name, r, a_deg, rx=0.5, ry=0.5):
    a = math.radians(a_deg)
    return (name, 0.5 + rx * r * math.cos(a), 0.5 - ry * r * math.sin(a))


POLYNOMIAL = {"fisheye_fov": 2.2, "fisheye_polynomial_k0": 0.0, "fisheye_polynomial_k1": -0.075,
              "fisheye_polynomial_k2": 0.0, "fisheye_polynomial_k3": 4e-5,
              "fisheye_polynomial_k4": 0.0}

SHOTS = {
    # Asymmetric ranges: the markers' places test which way longitude and latitude run.
    "equirectangular": PanoShot(
        128, 64, "EQUIRECTANGULAR", "equirectangular",
        {"latitude_min": -1.45, "latitude_max": 1.5, "longitude_min": -3.0, "longitude_max": 3.1},
        lambda u, v, s, _: equirectangular(u, v, s),
        (("centre", 0.5, 0.5), ("seam_left", 0.035, 0.45), ("seam_right", 0.962, 0.56),
         ("north", 0.3, 0.07), ("south", 0.72, 0.93), ("behind_left", 0.12, 0.3),
         ("right", 0.8, 0.22), ("low", 0.6, 0.74))),
    # 200 degrees on a 3:2 frame: an ellipse, the rim markers behind the camera's plane.
    "fisheye_equidistant": PanoShot(
        96, 64, "FISHEYE_EQUIDISTANT", "fisheye_equidistant", {"fisheye_fov": math.radians(200)},
        lambda u, v, s, _: equidistant(u, v, s),
        (("centre", 0.5, 0.5), on_circle("rim_right", 0.9, 8), on_circle("rim_top", 0.9, 95),
         on_circle("rim_left", 0.88, 190), on_circle("rim_bottom_right", 0.9, 300),
         on_circle("middle", 0.5, 140), on_circle("inner", 0.35, 250))),
    # 8 mm, 190 degrees on 36 x 24 mm: a circle of radius 11.8 mm inside the frame's height.
    "fisheye_equisolid": PanoShot(
        96, 64, "FISHEYE_EQUISOLID", "fisheye_equisolid",
        {"fisheye_lens": 8.0, "fisheye_fov": math.radians(190)},
        lambda u, v, s, mm: equisolid(u, v, s, mm),
        (("centre", 0.5, 0.5), on_circle("rim_right", 0.92, 5, 11.8 / 36, 11.8 / 24),
         on_circle("rim_top", 0.9, 80, 11.8 / 36, 11.8 / 24),
         on_circle("rim_left", 0.9, 200, 11.8 / 36, 11.8 / 24),
         on_circle("middle", 0.55, 300, 11.8 / 36, 11.8 / 24))),
    # The whole sphere in a disc: the rim is behind the camera.
    "mirrorball": PanoShot(
        64, 64, "MIRRORBALL", "mirrorball", {}, lambda u, v, s, _: mirrorball(u, v, s),
        (("centre", 0.5, 0.5), on_circle("side_right", 0.7, 20), on_circle("side_top", 0.7, 110),
         on_circle("rim_left", 0.85, 185), on_circle("rim_bottom", 0.85, 280))),
    # A calibrated-looking lens: theta = 0.075 r - 4e-5 r^3 (mm), cut at 126 degrees.
    "fisheye_polynomial": PanoShot(
        96, 64, "FISHEYE_LENS_POLYNOMIAL", "fisheye_polynomial", POLYNOMIAL,
        lambda u, v, s, mm: polynomial(u, v, s, mm),
        (("centre", 0.5, 0.5), ("right", 0.95, 0.45), ("top_left", 0.12, 0.12),
         ("bottom", 0.4, 0.94), ("middle", 0.7, 0.7))),
}


def pixel_pitch_rad(shot, x, y):
    """The angle a pixel spans around raster fraction (x, y), the mean of its two sides."""
    def direction(fx, fy):
        return shot.direction(fx, 1 - fy, shot.settings, shot.sensor_mm).normalized()
    d = direction(x, y)
    return (d.angle(direction(x + 1 / shot.width_px, y)) +
            d.angle(direction(x, y + 1 / shot.height_px))) / 2


def build_camera(scene, shot):
    data = bpy.data.cameras.new("Camera")
    data.type = "PANO"
    data.sensor_width, data.sensor_height = shot.sensor_mm
    data.clip_start, data.clip_end = 0.1, 200.0
    settings = data if hasattr(data, "panorama_type") else data.cycles  # Blender 4 / 3
    settings.panorama_type = shot.panorama_type
    for key, value in shot.settings.items():
        setattr(settings, key, value)
    camera = bpy.data.objects.new("Camera", data)
    camera.location = Vector(make_shot.CAMERA_LOCATION)
    camera.rotation_euler = Euler([math.radians(a) for a in make_shot.CAMERA_ROTATION_DEG], "XYZ")
    scene.collection.objects.link(camera)
    scene.camera = camera
    return camera


def add_marker(camera, shot, index, name, x, y):
    """A sphere 2.5 pixels in angular radius where raster fraction (x, y) looks, 3-12 m away."""
    direction = shot.direction(x, 1 - y, shot.settings, shot.sensor_mm).normalized()
    distance_m = 3.0 + 1.5 * index
    radius_m = distance_m * math.tan(2.5 * pixel_pitch_rad(shot, x, y))
    location = camera.matrix_world @ (direction * distance_m)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=48, ring_count=24, radius=radius_m,
                                         location=location)
    sphere = bpy.context.active_object
    sphere.name = name
    bpy.ops.object.shade_smooth()
    colours = ((1.0, 1.0, 1.0), (0.6, 0.8, 1.0), (1.0, 0.6, 0.3), (0.4, 1.0, 0.4))
    sphere.data.materials.append(
        make_shot.emission_material(name, colours[index % len(colours)], 3.0 + index))


def main():
    out_dir, name = make_shot.shot_arguments("pano_shot.py", SHOTS)
    shot = SHOTS[name]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    make_shot.new_world(scene, (shot.world,) * 3, 1.0)
    make_shot.configure_cycles(scene, make_shot.Shot(shot.width_px, shot.height_px, 50.0, (),
                                                     samples=shot.samples))
    camera = build_camera(scene, shot)
    bpy.context.view_layer.update()
    for index, (marker, x, y) in enumerate(shot.markers):
        add_marker(camera, shot, index, marker, x, y)
    bpy.context.view_layer.update()

    w, h = shot.width_px, shot.height_px
    with open(os.path.join(out_dir, "manifest.txt"), "w") as manifest:
        manifest.write(make_shot.record("shot", name=name, samples=shot.samples, width_px=w,
                                        height_px=h, camera_model=shot.kind,
                                        world=3 * shot.world))
        for marker, x, y in shot.markers:
            manifest.write(make_shot.record("marker", name=marker, image_x_px=x * w,
                                            image_y_px=y * h))
    make_shot.export(os.path.join(out_dir, "shot.gltf"))
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main()
