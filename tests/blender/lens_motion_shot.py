"""The Blender side of the rolling-shutter and animated-lens tests
(tests/blender/blender_lens_motion_test.cpp).

Two shots of emissive spheres ("markers") on a black world, seen by make_shot.py's rotated,
displaced camera, rendered by Cycles and exported through filmback's add-on:
  rolling  Cycles' rolling shutter (rows read top to bottom, each row a share ROLLING_DURATION of
           the shutter) over motion_shot.py's half-frame shutter; markers move fast across and
           down the image (motion_shot.animate: linear keys, constant image speed).
  lens     A zoom, a rack focus, an f-stop and a lens shift, each keyed linearly over frames 0 to
           10; the shot is exported at frame EXPORT_FRAME (so the file's scalar lens values are
           that frame's) and both renderers render frame LENS_FRAME, the file's frame rewritten
           as `--frame` would: its lens values come from the per-frame track. The shutter, a
           frame long, spans a zoom of LENS_MM_PER_FRAME, which Cycles renders as a radial blur.

    blender -b --factory-startup --python lens_motion_shot.py -- OUTDIR rolling|lens

writes OUTDIR/shot.gltf (+ shot.bin), OUTDIR/cycles.exr and OUTDIR/manifest.txt
(tests/blender/blender_shot.h):
  shot    name, samples, width_px, height_px; rolling: shutter_frames, rolling_duration
  marker  name; frame_x_px, frame_y_px: Blender's projection of the sphere's centre at the
          rendered frame (world_to_camera_view); travel_x_px, travel_y_px: its image's travel
          over the shutter (rolling)
Raster convention of docs/conventions.md: origin at the top-left corner, y down.
"""

import json
import os
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_shot  # noqa: E402  (the camera, materials, Cycles settings and shot properties)
import motion_shot  # noqa: E402  (markers moving at constant image speed over its shutter)

Marker = make_shot.Marker
FPS = motion_shot.FPS
ROLLING_DURATION = 0.1  # Cycles' default share of the shutter per row

# Travel over the half-frame shutter, image pixels (x right, y down): a 64-row scan shifts a
# marker by up to 0.9 of it between the top and the bottom rows.
ROLLING_MARKERS = (
    (Marker("top_right", 0.25, 0.20, 6.0, 3.0, (1.0, 0.9, 0.8), 6.0), (30.0, 0.0)),
    (Marker("bottom_left", 0.70, 0.80, 8.0, 3.0, (0.6, 0.8, 1.0), 6.0), (-24.0, 0.0)),
    (Marker("down", 0.20, 0.45, 5.0, 3.0, (0.5, 1.0, 0.5), 6.0), (0.0, 20.0)),
    (Marker("up_right", 0.75, 0.40, 7.0, 3.0, (1.0, 0.5, 0.8), 6.0), (12.0, -16.0)),
    (Marker("still", 0.50, 0.62, 9.0, 3.0, (1.0, 1.0, 0.4), 3.0), (0.0, 0.0)),
)

# The lens keyed at frames 0 and 10 (LINEAR): at LENS_FRAME 80 mm, focus 6 m, f/1.6, shift 0.1;
# at EXPORT_FRAME 56 mm, 3 m, f/1.84, 0.04.
LENS_KEYS = {  # data path: (value at frame 0, value at frame 10)
    "lens": (40.0, 120.0),
    "dof.focus_distance": (1.0, 11.0),
    "dof.aperture_fstop": (2.0, 1.2),
    "shift_x": (0.0, 0.2),
}
LENS_FRAME = 5
EXPORT_FRAME = 2
LENS_SHUTTER_FRAMES = 1.0  # 76 to 84 mm: a marker 40 px off the axis streaks 4 px radially
# Placed at LENS_FRAME; circles of confusion up to 6 px around the 6 m focus.
LENS_MARKERS = (
    Marker("near", 0.22, 0.25, 1.5, 2.5, (1.0, 0.9, 0.8), 20.0),
    Marker("in_focus", 0.80, 0.28, 6.0, 2.5, (0.6, 0.8, 1.0), 8.0),
    Marker("mid", 0.50, 0.52, 3.0, 2.5, (0.5, 1.0, 0.5), 10.0),
    Marker("far", 0.22, 0.76, 30.0, 2.5, (1.0, 0.5, 0.8), 10.0),
    Marker("corner", 0.84, 0.80, 2.0, 2.5, (1.0, 1.0, 0.4), 15.0),
)
SHOTS = {"rolling": make_shot.Shot(96, 64, 35.0, markers=(), samples=128),
         "lens": make_shot.Shot(96, 64, 80.0, markers=(), samples=512)}


def raster(scene, camera, point, shot):
    centre = world_to_camera_view(scene, camera, point)
    return centre.x * shot.width_px, (1.0 - centre.y) * shot.height_px


def key_lens(camera):
    """LENS_KEYS as linear keyframes on the camera's data."""
    data = camera.data
    data.dof.use_dof = True
    for path, values in LENS_KEYS.items():
        owner, prop = (data.dof, path[4:]) if path.startswith("dof.") else (data, path)
        for frame, value in zip(motion_shot.KEY_FRAMES, values):
            setattr(owner, prop, value)
            owner.keyframe_insert(prop, frame=frame)
    for curve in data.animation_data.action.fcurves:
        for point in curve.keyframe_points:
            point.interpolation = "LINEAR"


def set_file_frame(path, frame):
    """The exported file's frame (its scene's FILMBACK_blender `frame`), as `--frame` sets it."""
    with open(path) as f:
        gltf = json.load(f)
    gltf["scenes"][gltf.get("scene", 0)]["extensions"]["FILMBACK_blender"]["frame"] = frame
    with open(path, "w") as f:
        json.dump(gltf, f)


def main():
    out_dir, name = make_shot.shot_arguments("lens_motion_shot.py", SHOTS)
    shot = SHOTS[name]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    make_shot.new_world(scene)
    scene.render.fps, scene.render.fps_base = FPS, 1.0
    scene.frame_start, scene.frame_end = motion_shot.KEY_FRAMES
    frame_number = motion_shot.FRAME if name == "rolling" else LENS_FRAME
    scene.frame_set(frame_number)

    make_shot.configure_cycles(scene, shot)
    scene.render.use_motion_blur = True
    scene.cycles.motion_blur_position = "CENTER"
    camera = make_shot.build_camera(scene, shot)
    if name == "rolling":
        scene.render.motion_blur_shutter = motion_shot.SHUTTER_FRAMES
        scene.cycles.rolling_shutter_type = "TOP"
        scene.cycles.rolling_shutter_duration = ROLLING_DURATION
        markers = ROLLING_MARKERS
    else:
        scene.render.motion_blur_shutter = LENS_SHUTTER_FRAMES
        key_lens(camera)
        markers = tuple((m, (0.0, 0.0)) for m in LENS_MARKERS)
    scene.frame_set(frame_number)
    bpy.context.view_layer.update()
    frame = make_shot.Frame(scene, camera)
    spheres = []
    for marker, travel_px in markers:
        sphere, _ = make_shot.add_sphere(camera, frame, marker, marker.depth_m)
        if travel_px != (0.0, 0.0):
            motion_shot.animate(sphere, camera, frame, travel_px, marker.depth_m)
        spheres.append((sphere, travel_px))
    scene.frame_set(frame_number)

    with open(os.path.join(out_dir, "manifest.txt"), "w") as manifest:
        fields = dict(name=name, samples=shot.samples, width_px=shot.width_px,
                      height_px=shot.height_px)
        if name == "rolling":
            fields.update(shutter_frames=motion_shot.SHUTTER_FRAMES,
                          rolling_duration=ROLLING_DURATION)
        manifest.write(make_shot.record("shot", **fields))
        for sphere, (travel_x, travel_y) in spheres:
            x, y = raster(scene, camera, sphere.matrix_world.translation, shot)
            manifest.write(make_shot.record("marker", name=sphere.name, frame_x_px=x, frame_y_px=y,
                                            travel_x_px=travel_x, travel_y_px=travel_y))

    gltf = os.path.join(out_dir, "shot.gltf")
    if name == "lens":
        scene.frame_set(EXPORT_FRAME)
    make_shot.export(gltf)
    if name == "lens":
        set_file_frame(gltf, frame_number)
        scene.frame_set(frame_number)
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main()
