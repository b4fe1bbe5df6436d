"""The Blender side of tests/blender/roundtrip_test.py.

    blender -b --factory-startup --python roundtrip_scene.py -- OUTDIR

Builds cameras with unusual physical values (perspective with every lens setting, orthographic,
a focus object that moves, a pinhole, Blender's default), exports the scene through the add-on
(importers/blender/export_shot.py) to OUTDIR/shot.gltf and writes OUTDIR/expected.json: for each
camera, the values bpy reads, under the names `filmback info` prints on its "exact:" line, and
OUTDIR/shot.blend for the command-line entry's test.
"""

import json
import math
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "importers", "blender"))
import export_shot  # noqa: E402

FRAME = 3  # the shot's frame; the focus object is elsewhere on other frames


def add_camera(name, location, rotation, **data):
    cam = bpy.data.cameras.new(name)
    for key, value in data.items():
        target = cam.dof if key.startswith("dof_") else cam
        setattr(target, key.removeprefix("dof_"), value)
    obj = bpy.data.objects.new(name, cam)
    obj.location, obj.rotation_euler = location, rotation
    bpy.context.scene.collection.objects.link(obj)
    return obj


def expected(obj):
    """What filmback must import, read back from bpy (float32 values widened to double)."""
    cam = obj.data
    dof = cam.dof
    out = {
        "projection": "orthographic" if cam.type == "ORTHO" else "perspective",
        "sensor_width_mm": cam.sensor_width, "sensor_height_mm": cam.sensor_height,
        "sensor_fit": cam.sensor_fit.lower(), "shift_x": cam.shift_x, "shift_y": cam.shift_y,
        "clip_near_m": cam.clip_start, "clip_far_m": cam.clip_end,
    }
    if cam.type == "ORTHO":
        out["ortho_scale_m"] = cam.ortho_scale
    else:
        out["focal_length_mm"] = cam.lens
    if dof.use_dof:
        out.update(fstop=dof.aperture_fstop, aperture_blades=dof.aperture_blades,
                   aperture_rotation_rad=dof.aperture_rotation, aperture_ratio=dof.aperture_ratio)
        if dof.focus_object is None:
            out["focus_distance_m"] = dof.focus_distance
        else:
            # Depth of the focus object in camera space (the camera looks down -Z): computed
            # here through the inverse matrix, not as the add-on does it.
            local = obj.matrix_world.inverted() @ dof.focus_object.matrix_world.translation
            out["focus_distance_m"] = -local.z
    else:
        out["fstop"] = math.inf
    return out


def main():
    out_dir = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
    os.makedirs(out_dir, exist_ok=True)
    bpy.ops.wm.read_factory_settings(use_empty=False)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = 1000, 700
    scene.render.resolution_percentage = 37
    scene.frame_start, scene.frame_end = 1, 6
    cameras = [bpy.data.objects["Camera"]]  # Blender's default camera, untouched
    cameras.append(add_camera(
        "Persp", (1.5, -7.25, 2.125), (1.2, 0.05, 0.3), lens=37.3, sensor_width=23.7,
        sensor_height=15.6, sensor_fit="VERTICAL", shift_x=0.137, shift_y=-0.0731,
        clip_start=0.0123, clip_end=4567.8, dof_use_dof=True, dof_aperture_fstop=1.37,
        dof_focus_distance=3.21, dof_aperture_blades=7, dof_aperture_rotation=0.3,
        dof_aperture_ratio=1.7))
    cameras.append(add_camera(
        "Ortho", (0, -20, 3), (1.5, 0, 0), type="ORTHO", ortho_scale=7.77, clip_start=0.5,
        clip_end=50.0, sensor_fit="HORIZONTAL", shift_x=-0.2))
    target = bpy.data.objects.new("FocusTarget", None)
    scene.collection.objects.link(target)
    for frame, x in ((1, -1.0), (6, 4.0)):
        target.location = (x, 2.3, 0.7)
        target.keyframe_insert("location", frame=frame)
    cameras.append(add_camera(
        "Focus", (0.3, -6.1, 1.1), (1.45, 0.0, 0.1), lens=85.0, dof_use_dof=True,
        dof_aperture_fstop=1.4, dof_focus_object=target))
    cameras.append(add_camera("Pinhole", (2, -5, 1), (1.3, 0, 0.4), lens=12.0,
                              sensor_fit="HORIZONTAL", sensor_width=17.3))
    scene.frame_set(FRAME)
    bpy.context.view_layer.update()
    with open(os.path.join(out_dir, "expected.json"), "w") as f:
        json.dump({obj.name: expected(obj) for obj in cameras}, f, indent=1)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out_dir, "shot.blend"))
    export_shot.export(os.path.join(out_dir, "shot.gltf"))


main()
