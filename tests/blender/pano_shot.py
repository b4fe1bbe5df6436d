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
from dataclasses import dataclass

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
    sensor_fit: str = "AUTO"
    shift: tuple = (0.0, 0.0)  # fractions of the frame (Cycles adds them to u and v)
    samples: int = 64
    world: float = 0.02  # the world's radiance, each channel
    distances_m: tuple = ()  # of the markers, in order; default 3 m + 1.5 m per marker
    dof: tuple = ()  # (lens mm, f-number, focus distance m): Cycles' depth of field

    def imaged_sensor_mm(self):
        """Cycles' sensorwidth, sensorheight (blender/camera.cpp): the fitted side, the other in
        the frame's aspect."""
        w, h = self.width_px, self.height_px
        fit = self.sensor_fit if self.sensor_fit != "AUTO" else "HORIZONTAL" if w > h else "AUTO"
        if fit == "HORIZONTAL":
            return (self.sensor_mm[0], self.sensor_mm[0] * h / w)
        side = self.sensor_mm[1] if fit == "VERTICAL" else self.sensor_mm[0]
        return (side * w / h, side)

    def look(self, x, y):
        """The direction raster fraction (x, y) (from the top-left corner) looks in."""
        return self.direction(x + self.shift[0], 1 - y + self.shift[1], self.settings,
                              self.imaged_sensor_mm()).normalized()


# Fractions of the frame on a circle of radius r (in units of the half-frame) at angle a (deg,
# counter-clockwise from +x), for markers along a fisheye's rim.
def on_circle(name, r, a_deg, rx=0.5, ry=0.5, centre=(0.5, 0.5)):
    a = math.radians(a_deg)
    return (name, centre[0] + rx * r * math.cos(a), centre[1] - ry * r * math.sin(a))


# The equisolid shot's circle: 11.8 mm on 36 x 24 mm, its centre where the shift puts it (u = x +
# shift_x, v = 1 - y + shift_y at the film's centre).
def on_equisolid_circle(name, r, a_deg):
    return on_circle(name, r, a_deg, 11.8 / 36, 11.8 / 24, (0.5 - 0.06, 0.5 - 0.04))


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
    # Shifted by (0.06, -0.04) of the frame: the circle's centre moves left and up.
    "fisheye_equisolid": PanoShot(
        96, 64, "FISHEYE_EQUISOLID", "fisheye_equisolid",
        {"fisheye_lens": 8.0, "fisheye_fov": math.radians(190)},
        lambda u, v, s, mm: equisolid(u, v, s, mm),
        (on_equisolid_circle("centre", 0.0, 0), on_equisolid_circle("rim_right", 0.92, 5),
         on_equisolid_circle("rim_top", 0.85, 80), on_equisolid_circle("rim_left", 0.9, 200),
         on_equisolid_circle("middle", 0.55, 300)),
        shift=(0.06, -0.04)),
    # The whole sphere in a disc: the rim is behind the camera.
    "mirrorball": PanoShot(
        64, 64, "MIRRORBALL", "mirrorball", {}, lambda u, v, s, _: mirrorball(u, v, s),
        (("centre", 0.5, 0.5), on_circle("side_right", 0.7, 20), on_circle("side_top", 0.7, 110),
         on_circle("rim_left", 0.85, 185), on_circle("rim_bottom", 0.85, 280))),
    # A calibrated-looking lens: theta = 0.075 r - 4e-5 r^3 (mm), cut at 126 degrees; the sensor's
    # 20 mm height spans the frame (fit VERTICAL), so 30 mm its width.
    "fisheye_polynomial": PanoShot(
        96, 64, "FISHEYE_LENS_POLYNOMIAL", "fisheye_polynomial", POLYNOMIAL,
        lambda u, v, s, mm: polynomial(u, v, s, mm),
        (("centre", 0.5, 0.5), ("right", 0.95, 0.45), ("top_left", 0.12, 0.12),
         ("bottom", 0.4, 0.94), ("middle", 0.7, 0.7)),
        sensor_mm=(36.0, 20.0), sensor_fit="VERTICAL"),
    # Depth of field: Blender's aperture f / 2N = 0.2 m (f = 200 mm, f/0.5), focused 3 m away
    # along each ray; markers from 0.6 m (blurred over about 5 px) to 20 m.
    "equirectangular_dof": PanoShot(
        128, 64, "EQUIRECTANGULAR", "equirectangular",
        {"latitude_min": -1.5, "latitude_max": 1.5, "longitude_min": -3.1, "longitude_max": 3.1},
        lambda u, v, s, _: equirectangular(u, v, s),
        (("near", 0.3, 0.4), ("in_focus", 0.5, 0.5), ("nearer", 0.72, 0.62),
         ("far", 0.12, 0.7), ("farther", 0.88, 0.3)),
        samples=256, distances_m=(1.0, 3.0, 0.6, 8.0, 20.0), dof=(200.0, 0.5, 3.0)),
}


def pixel_pitch_rad(shot, x, y):
    """The angle a pixel spans around raster fraction (x, y), the mean of its two sides."""
    d = shot.look(x, y)
    return (d.angle(shot.look(x + 1 / shot.width_px, y)) +
            d.angle(shot.look(x, y + 1 / shot.height_px))) / 2


def build_camera(scene, shot):
    data = bpy.data.cameras.new("Camera")
    data.type = "PANO"
    data.sensor_width, data.sensor_height = shot.sensor_mm
    data.sensor_fit = shot.sensor_fit
    data.shift_x, data.shift_y = shot.shift
    data.clip_start, data.clip_end = 0.1, 200.0
    if shot.dof:
        data.lens, data.dof.aperture_fstop, data.dof.focus_distance = shot.dof
        data.dof.use_dof = True
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
    """A sphere 2.5 pixels in angular radius where raster fraction (x, y) looks."""
    direction = shot.look(x, y)
    distance_m = shot.distances_m[index] if shot.distances_m else 3.0 + 1.5 * index
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
