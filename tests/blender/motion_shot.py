"""The Blender side of the motion-blur test (tests/blender/blender_motion_test.cpp).

Builds one shot of emissive spheres ("markers") on a black world, seen by make_shot.py's rotated,
displaced camera: two move at constant speed (linear keyframes), one along the image's x axis and
one along its y axis, and one stands still. Cycles renders it with motion blur, a box shutter half
a frame long centred on the frame; filmback's add-on exports it with its animation, and the
shutter, frame and fps in the scene's FILMBACK_blender extension.

    blender -b --factory-startup --python motion_shot.py -- OUTDIR motion

writes OUTDIR/shot.gltf (+ shot.bin), OUTDIR/cycles.exr and OUTDIR/manifest.txt, one record a
line (tests/blender/blender_shot.h):
  shot    name, samples, width_px, height_px, shutter_open_s, shutter_close_s,
          cycles_shutter_fraction (the part of the shutter Cycles 3.4 exposes, measured:
          ../shared/notes/blender-camera.md, pitfall 10)
  marker  name; open_x_px, open_y_px and close_x_px, close_y_px: Blender's projection of the
          sphere's centre at shutter open and close (world_to_camera_view at those subframes);
          centroid_x_px, centroid_y_px: the streak's flux-weighted centroid over the shutter;
          cycles_centroid_x_px, cycles_centroid_y_px: the same over Cycles' part of it
Raster convention of docs/conventions.md: origin at the top-left corner, y down.
"""

import math
import os
import sys
from types import SimpleNamespace

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Matrix, Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_shot  # noqa: E402  (the camera, materials, Cycles settings and shot properties)

SHOT = make_shot.Shot(320, 200, 50.0, markers=(), samples=2048)  # streak centroids: noise ~0.03 px
FPS = 24
FRAME = 5
SHUTTER_FRAMES = 0.5  # Cycles' motion_blur_shutter, centred on the frame: frames 4.75 to 5.25
KEY_FRAMES = (0, 10)  # each moving marker's two linear keyframes
CYCLES_SHUTTER_FRACTION = 0.9922

# (marker, travel during the shutter in image pixels: x right, y down). The markers sit where
# they are at the frame's time; spheres 12 px across streak over 45-60 px.
MARKERS = (
    (make_shot.Marker("across", 0.40, 0.30, 8.0, 6.0, (1.0, 0.9, 0.8), 6.0), (60.0, 0.0)),
    (make_shot.Marker("down", 0.75, 0.45, 6.0, 6.0, (0.6, 0.8, 1.0), 6.0), (0.0, 45.0)),
    (make_shot.Marker("still", 0.30, 0.75, 10.0, 6.0, (0.5, 1.0, 0.5), 3.0), (0.0, 0.0)),
)


def animate(sphere, camera, frame, travel_px, depth_m):
    """Moves the sphere at constant speed through where it is now (at FRAME): keyframes at
    KEY_FRAMES, LINEAR, so Blender's motion and the exporter's per-frame samples agree exactly."""
    per_frame_px = Vector(travel_px) / SHUTTER_FRAMES
    metres_per_px = depth_m / frame.px_per_unit
    # Camera space: +x right, +y up (image y points down).
    velocity = camera.matrix_world.to_3x3() @ Vector(
        (per_frame_px.x * metres_per_px, -per_frame_px.y * metres_per_px, 0.0))
    at_frame = sphere.location.copy()
    for key in KEY_FRAMES:
        sphere.location = at_frame + velocity * (key - FRAME)
        sphere.keyframe_insert("location", frame=key)
    for curve in sphere.animation_data.action.fcurves:
        for point in curve.keyframe_points:
            point.interpolation = "LINEAR"
    sphere.location = at_frame


def centre_at(scene, sphere, frame, subframe):
    scene.frame_set(frame, subframe=subframe)
    return sphere.matrix_world.translation.copy()


def raster(scene, camera, point):
    centre = world_to_camera_view(scene, camera, point)
    return centre.x * SHOT.width_px, (1.0 - centre.y) * SHOT.height_px


def streak_centroid(scene, camera, frame, start, end, radius_m, fraction, steps=2000):
    """The flux-weighted centroid of the image of a sphere moving linearly from `start` (shutter
    open) over the first `fraction` of its way to `end`: the time average of its image's centre
    (make_shot.expected_image: an ellipse off the axis) weighted by the image's area (the same
    ellipse, pi times its semi-axes), since the image's radiance is constant."""
    world_to_camera = camera.matrix_world.normalized().inverted()
    total = x_sum = y_sum = 0.0
    for i in range(steps):
        point = start.lerp(end, fraction * (i + 0.5) / steps)
        in_camera = world_to_camera @ point
        sin_a, cos_t = radius_m / in_camera.length, -in_camera.z / in_camera.length
        k = cos_t**2 - sin_a**2
        area = sin_a**2 * math.sqrt(1 - sin_a**2) / k**1.5
        image = make_shot.expected_image(scene, camera, frame, SimpleNamespace(
            matrix_world=Matrix.Translation(point)), radius_m)
        total += area
        x_sum += area * image["image_x_px"]
        y_sum += area * image["image_y_px"]
    return x_sum / total, y_sum / total


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 2 or args[1] != "motion":
        raise SystemExit("usage: blender -b --factory-startup --python motion_shot.py -- OUTDIR motion")
    out_dir = os.path.abspath(args[0])
    os.makedirs(out_dir, exist_ok=True)

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    make_shot.new_world(scene)
    scene.render.fps, scene.render.fps_base = FPS, 1.0
    scene.frame_start, scene.frame_end = KEY_FRAMES
    scene.frame_set(FRAME)

    make_shot.configure_cycles(scene, SHOT)
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = SHUTTER_FRAMES
    scene.cycles.motion_blur_position = "CENTER"
    camera = make_shot.build_camera(scene, SHOT)
    bpy.context.view_layer.update()
    frame = make_shot.Frame(scene, camera)
    spheres = []
    for marker, travel_px in MARKERS:
        sphere, radius_m = make_shot.add_sphere(camera, frame, marker, marker.depth_m)
        if travel_px != (0.0, 0.0):
            animate(sphere, camera, frame, travel_px, marker.depth_m)
        spheres.append((sphere, radius_m))
    scene.frame_set(FRAME)

    half = SHUTTER_FRAMES / 2
    shutter_open_s, shutter_close_s = -half / FPS, half / FPS
    with open(os.path.join(out_dir, "manifest.txt"), "w") as manifest:
        manifest.write(make_shot.record("shot", name="motion", samples=SHOT.samples,
                                        width_px=SHOT.width_px, height_px=SHOT.height_px,
                                        shutter_open_s=shutter_open_s,
                                        shutter_close_s=shutter_close_s,
                                        cycles_shutter_fraction=CYCLES_SHUTTER_FRACTION))
        for sphere, radius_m in spheres:
            start = centre_at(scene, sphere, FRAME - 1, 1.0 - half)
            end = centre_at(scene, sphere, FRAME, half)
            (open_x, open_y), (close_x, close_y) = raster(scene, camera, start), raster(scene, camera, end)
            centroid = streak_centroid(scene, camera, frame, start, end, radius_m, 1.0)
            cycles = streak_centroid(scene, camera, frame, start, end, radius_m,
                                     CYCLES_SHUTTER_FRACTION)
            manifest.write(make_shot.record(
                "marker", name=sphere.name, open_x_px=open_x, open_y_px=open_y, close_x_px=close_x,
                close_y_px=close_y, centroid_x_px=centroid[0], centroid_y_px=centroid[1],
                cycles_centroid_x_px=cycles[0], cycles_centroid_y_px=cycles[1]))

    make_shot.export(os.path.join(out_dir, "shot.gltf"))

    scene.frame_set(FRAME)
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main()
