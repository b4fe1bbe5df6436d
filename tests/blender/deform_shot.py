"""The Blender side of the deformation tests (tests/blender/blender_deform_test.cpp).

Emissive spheres ("markers") on a black world, seen by make_shot.py's camera, joined into one mesh
that Blender deforms; the add-on exports Blender's evaluated positions (FILMBACK_deformation,
importers/blender/io_filmback/deformation.py) and Cycles renders the shot:
  armature   a two-bone armature bent 50 degrees at its joint; a marker on each bone and one at
             the joint weighted half to each
  shapekey   a shape key at 0.6 moving two of three markers
  blur1, blur3, blur7
             a shape key animated linearly (keys at frames 4 and 6, values -2 and 2) slides one
             marker 40 px across the image during a half-frame shutter centred on frame 5,
             with the object's Cycles motion steps 1, 3 or 7 (3, 9 or 129 evaluated
             positions); a second marker is still
  swing1, swing3
             a marker on a bone turning 90 degrees about the view axis during the shutter, 40 px
             from its pivot, with Cycles' motion steps 1 and 3: an arc both renderers cut into
             the same 2 or 8 chords
  subdivided the armature shot under a Subdivision Surface after the Armature modifier, viewport
             level 0 and render level 1: the add-on writes Blender's evaluated mesh at render
             level (the topology changes) with its bent positions
  array      a marker moved by a shape key at 0.6, repeated three times by an Array modifier
             after it: three markers where the base mesh has one

    blender -b --factory-startup --python deform_shot.py -- OUTDIR SHOT

writes OUTDIR/shot.gltf (+ shot.bin), OUTDIR/cycles.exr and OUTDIR/manifest.txt
(tests/blender/blender_shot.h):
  shot    name, samples, width_px, height_px, positions (evaluated positions per frame Cycles
          stores), cycles_shutter_fraction (motion_shot.py's, blur shots only)
  marker  name; x_px, y_px: Blender's projection of the marker's evaluated centre at the frame;
          for blur shots open_x_px, open_y_px, close_x_px, close_y_px at shutter open and close
Raster convention of docs/conventions.md: origin at the top-left corner, y down.
"""

import math
import os
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_shot  # noqa: E402  (the camera, materials, Cycles settings, export)
import motion_shot  # noqa: E402  (the blur shots' timing and Cycles' shutter fraction)

STILL_SHOT = make_shot.Shot(200, 120, 50.0, markers=(), samples=256)
BLUR_SHOT = make_shot.Shot(200, 120, 50.0, markers=(), samples=1024)
DEPTH_M = 6.0
BEND_DEG = 50.0
SHAPE_KEY_VALUE = 0.6
BLUR_TRAVEL_PX = (40.0, 0.0)
BLUR_KEY_FRAMES = (4, 6)  # the shape key's two linear keys, around the shutter
SWING_DEG = 90.0  # the swing shots' turn during the shutter
SWING_RADIUS_PX = 40.0
ARRAY_COPIES = 3
ARRAY_SPACING_PX = 50.0
SHOTS = ("armature", "shapekey", "blur1", "blur3", "blur7", "swing1", "swing3", "subdivided",
         "array")


def marker(name, u, v, radius_px=5.0, colour=(1.0, 0.9, 0.8), strength=4.0):
    return make_shot.Marker(name, u, v, DEPTH_M, radius_px, colour, strength)


def joined(spheres, name):
    """One mesh object of the marker spheres, each keeping its material (a primitive each)."""
    bpy.ops.object.select_all(action="DESELECT")
    for s in spheres:
        s.select_set(True)
    bpy.context.view_layer.objects.active = spheres[0]
    bpy.ops.object.join()
    obj = bpy.context.active_object
    obj.name = name
    return obj


def evaluated_centres(obj, parts):
    """The centres of the evaluated mesh's `parts` runs of consecutive vertices: the joined
    spheres (disjoint, in the order they were joined, make_shot's spheres all of one vertex
    count) or an Array's copies (each the whole base mesh, in order)."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = obj.evaluated_get(depsgraph)
    me = evaluated.to_mesh()
    try:
        per_part = len(me.vertices) // parts
        out = []
        for k in range(parts):
            centre = sum((me.vertices[i].co for i in range(k * per_part, (k + 1) * per_part)),
                         Vector()) / per_part
            out.append(evaluated.matrix_world @ centre)
        return out
    finally:
        evaluated.to_mesh_clear()


def sphere_vertices(obj):
    """The vertex indices of each joined sphere (evaluated_centres says why they are runs)."""
    per_sphere = len(obj.data.vertices) // len(obj.data.materials)
    return [range(k * per_sphere, (k + 1) * per_sphere) for k in range(len(obj.data.materials))]


def array_copies(obj):
    return next((m.count for m in obj.modifiers if m.type == "ARRAY"), None)


def marker_centres(obj):
    """Blender's evaluated centre of each marker, with a Subdivision Surface hidden (the refined
    mesh's vertices are not runs per sphere; the cage's are, and its centre is the marker's)."""
    copies = array_copies(obj)
    if copies:
        return evaluated_centres(obj, copies)
    subdivisions = [m for m in obj.modifiers if m.type == "SUBSURF" and m.show_viewport]
    for m in subdivisions:
        m.show_viewport = False
    try:
        return evaluated_centres(obj, len(obj.data.materials))
    finally:
        for m in subdivisions:
            m.show_viewport = True


def raster(scene, camera, point, shot):
    c = world_to_camera_view(scene, camera, point)
    return c.x * shot.width_px, (1.0 - c.y) * shot.height_px


def new_rig_in_edit_mode(scene):
    """An empty armature "rig" in `scene`, active and in Edit Mode for its bones; returns its
    data and object."""
    data = bpy.data.armatures.new("rig")
    rig = bpy.data.objects.new("rig", data)
    scene.collection.objects.link(rig)
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.mode_set(mode="EDIT")
    return data, rig


def build_armature(scene, camera, frame):
    markers = (marker("root", 0.25, 0.55), marker("joint", 0.5, 0.55, colour=(0.6, 0.8, 1.0)),
               marker("tip", 0.72, 0.55, colour=(0.4, 1.0, 0.4), strength=6.0))
    spheres = [make_shot.add_sphere(camera, frame, m, DEPTH_M)[0] for m in markers]
    bones = ("upper", "upper", "lower")  # the joint marker is half on each (below)
    for s, bone in zip(spheres, bones):
        group = s.vertex_groups.new(name=bone)
        group.add(range(len(s.data.vertices)), 1.0, "REPLACE")
    spheres[1].vertex_groups.new(name="lower").add(range(len(spheres[1].data.vertices)), 0.5,
                                                   "REPLACE")
    spheres[1].vertex_groups["upper"].add(range(len(spheres[1].data.vertices)), 0.5, "REPLACE")
    limb = joined(spheres, "limb")

    start = camera.matrix_world @ frame.point(0.15, 0.55, DEPTH_M)
    middle = camera.matrix_world @ frame.point(0.5, 0.55, DEPTH_M)
    end = camera.matrix_world @ frame.point(0.85, 0.55, DEPTH_M)
    data, rig = new_rig_in_edit_mode(scene)
    upper = data.edit_bones.new("upper")
    upper.head, upper.tail = start, middle
    lower = data.edit_bones.new("lower")
    lower.head, lower.tail = middle, end
    lower.parent = upper
    bpy.ops.object.mode_set(mode="OBJECT")
    # Bend in the image plane: about the camera's view axis, in the bone's own frame.
    pose = rig.pose.bones["lower"]
    view_axis = camera.matrix_world.to_3x3() @ Vector((0.0, 0.0, 1.0))
    axis_in_bone = (rig.data.bones["lower"].matrix_local.to_3x3().inverted() @ view_axis)
    pose.rotation_mode = "AXIS_ANGLE"
    pose.rotation_axis_angle = (math.radians(BEND_DEG), *axis_in_bone.normalized())
    modifier = limb.modifiers.new("Armature", "ARMATURE")
    modifier.object = rig
    limb.parent = rig
    return limb


def build_shapekey(camera, frame):
    markers = (marker("still", 0.25, 0.4), marker("moves", 0.5, 0.4, colour=(0.6, 0.8, 1.0)),
               marker("far", 0.7, 0.6, colour=(0.4, 1.0, 0.4), strength=6.0))
    obj = joined([make_shot.add_sphere(camera, frame, m, DEPTH_M)[0] for m in markers], "blend")
    obj.shape_key_add(name="Basis")
    key = obj.shape_key_add(name="Moved", from_mix=False)
    offsets = (Vector(), camera.matrix_world.to_3x3() @ Vector((0.4, -0.3, 0.0)),
               camera.matrix_world.to_3x3() @ Vector((-0.2, 0.5, 0.3)))
    inverse = obj.matrix_world.to_3x3().inverted()
    for indices, offset in zip(sphere_vertices(obj), offsets):
        for i in indices:
            key.data[i].co += inverse @ offset
    key.value = SHAPE_KEY_VALUE
    return obj


def build_subdivided(scene, camera, frame):
    limb = build_armature(scene, camera, frame)
    subdivision = limb.modifiers.new("Subdivision", "SUBSURF")
    subdivision.levels, subdivision.render_levels = 0, 1  # the viewport's would not change it
    return limb


def build_array(camera, frame):
    obj = build_shapekey_marker(camera, frame)
    array = obj.modifiers.new("Array", "ARRAY")
    array.count = ARRAY_COPIES
    array.use_relative_offset, array.use_constant_offset = False, True
    step = camera.matrix_world.to_3x3() @ Vector((ARRAY_SPACING_PX, 0.0, 0.0))
    array.constant_offset_displace = obj.matrix_world.to_3x3().inverted() @ (
        step * frame.metres_per_px(DEPTH_M))
    return obj


def build_shapekey_marker(camera, frame):
    """One marker that a shape key at SHAPE_KEY_VALUE moves up and to the right."""
    obj = joined([make_shot.add_sphere(camera, frame, marker("moved", 0.3, 0.5), DEPTH_M)[0]],
                 "moved")
    obj.shape_key_add(name="Basis")
    key = obj.shape_key_add(name="Moved", from_mix=False)
    offset = obj.matrix_world.to_3x3().inverted() @ (
        camera.matrix_world.to_3x3() @ Vector((0.3, 0.2, 0.0)))
    for point in key.data:
        point.co += offset
    key.value = SHAPE_KEY_VALUE
    return obj


def build_blur(scene, camera, frame, steps):
    markers = (marker("slides", 0.35, 0.4), marker("still", 0.6, 0.7, colour=(0.4, 1.0, 0.4)))
    obj = joined([make_shot.add_sphere(camera, frame, m, DEPTH_M)[0] for m in markers], "slider")
    obj.shape_key_add(name="Basis")
    key = obj.shape_key_add(name="Slid", from_mix=False)
    # The key at 1 moves the marker by the shutter's travel; its value is keyed linearly as
    # (frame - FRAME) / SHUTTER_FRAMES, so the marker is where make_shot put it at the frame and
    # slides BLUR_TRAVEL_PX over the shutter centred on it.
    travel = camera.matrix_world.to_3x3() @ Vector(
        (BLUR_TRAVEL_PX[0], -BLUR_TRAVEL_PX[1], 0.0)) * frame.metres_per_px(DEPTH_M)
    inverse = obj.matrix_world.to_3x3().inverted()
    for i in sphere_vertices(obj)[0]:
        key.data[i].co += inverse @ travel
    reach = (BLUR_KEY_FRAMES[1] - motion_shot.FRAME) / motion_shot.SHUTTER_FRAMES
    key.slider_min, key.slider_max = -reach, reach  # Blender allows -10 to 10
    for key_frame in BLUR_KEY_FRAMES:
        key.value = (key_frame - motion_shot.FRAME) / motion_shot.SHUTTER_FRAMES
        key.keyframe_insert("value", frame=key_frame)
    for curve in obj.data.shape_keys.animation_data.action.fcurves:
        for point in curve.keyframe_points:
            point.interpolation = "LINEAR"
    obj.cycles.motion_steps = steps
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = motion_shot.SHUTTER_FRAMES
    scene.cycles.motion_blur_position = "CENTER"
    return obj


def build_swing(scene, camera, frame, steps):
    """A marker on a bone that turns SWING_DEG about the view axis during the shutter, at
    SWING_RADIUS_PX from its pivot: an arc that the motion positions cut into chords."""
    pivot = camera.matrix_world @ frame.point(0.3, 0.5, DEPTH_M)
    at = marker("swings", 0.3 + SWING_RADIUS_PX / STILL_SHOT.width_px, 0.5)
    obj = joined([make_shot.add_sphere(camera, frame, at, DEPTH_M)[0]], "swinger")
    obj.vertex_groups.new(name="arm").add(range(len(obj.data.vertices)), 1.0, "REPLACE")
    data, rig = new_rig_in_edit_mode(scene)
    arm = data.edit_bones.new("arm")
    arm.head = pivot
    arm.tail = pivot + camera.matrix_world.to_3x3() @ Vector((0.0, 0.3, 0.0))
    bpy.ops.object.mode_set(mode="OBJECT")
    pose = rig.pose.bones["arm"]
    view_axis = camera.matrix_world.to_3x3() @ Vector((0.0, 0.0, 1.0))
    axis = (rig.data.bones["arm"].matrix_local.to_3x3().inverted() @ view_axis).normalized()
    pose.rotation_mode = "AXIS_ANGLE"
    per_frame = math.radians(SWING_DEG) / motion_shot.SHUTTER_FRAMES
    for key_frame in BLUR_KEY_FRAMES:
        pose.rotation_axis_angle = ((key_frame - motion_shot.FRAME) * per_frame, *axis)
        pose.keyframe_insert("rotation_axis_angle", frame=key_frame)
    for curve in rig.animation_data.action.fcurves:
        for point in curve.keyframe_points:
            point.interpolation = "LINEAR"
    obj.modifiers.new("Armature", "ARMATURE").object = rig
    obj.parent = rig
    obj.cycles.motion_steps = steps
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = motion_shot.SHUTTER_FRAMES
    scene.cycles.motion_blur_position = "CENTER"
    return obj


def main():
    out_dir, name = make_shot.shot_arguments("deform_shot.py", SHOTS)
    blur = name.startswith(("blur", "swing"))
    shot = BLUR_SHOT if blur else STILL_SHOT
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    make_shot.new_world(scene)
    make_shot.configure_cycles(scene, shot)
    scene.render.fps, scene.render.fps_base = motion_shot.FPS, 1.0
    scene.frame_start, scene.frame_end = motion_shot.KEY_FRAMES
    scene.frame_set(motion_shot.FRAME)
    camera = make_shot.build_camera(scene, shot)
    bpy.context.view_layer.update()
    frame = make_shot.Frame(scene, camera)
    if name == "armature":
        obj = build_armature(scene, camera, frame)
    elif name == "shapekey":
        obj = build_shapekey(camera, frame)
    elif name == "subdivided":
        obj = build_subdivided(scene, camera, frame)
    elif name == "array":
        obj = build_array(camera, frame)
    elif name.startswith("swing"):
        obj = build_swing(scene, camera, frame, int(name[len("swing"):]))
    else:
        obj = build_blur(scene, camera, frame, int(name[len("blur"):]))
    scene.frame_set(motion_shot.FRAME)
    bpy.context.view_layer.update()

    from io_filmback import deformation
    copies = array_copies(obj)
    names = [f"copy{k}" for k in range(copies)] if copies else \
        [m.name for m in obj.data.materials]
    with open(os.path.join(out_dir, "manifest.txt"), "w") as manifest:
        manifest.write(make_shot.record(
            "shot", name=name, samples=shot.samples, width_px=shot.width_px,
            height_px=shot.height_px, positions=deformation.position_count(scene, obj),
            cycles_shutter_fraction=motion_shot.CYCLES_SHUTTER_FRACTION))
        at_frame = marker_centres(obj)
        ends = []
        if blur:
            half = motion_shot.SHUTTER_FRAMES / 2
            for f, sub in ((motion_shot.FRAME - 1, 1.0 - half), (motion_shot.FRAME, half)):
                scene.frame_set(f, subframe=sub)
                ends.append(marker_centres(obj))
            scene.frame_set(motion_shot.FRAME)
        for k, (marker_name, centre) in enumerate(zip(names, at_frame)):
            x, y = raster(scene, camera, centre, shot)
            fields = {"x_px": x, "y_px": y}
            if ends:
                (ox, oy), (cx, cy) = (raster(scene, camera, e[k], shot) for e in ends)
                fields.update(open_x_px=ox, open_y_px=oy, close_x_px=cx, close_y_px=cy)
            manifest.write(make_shot.record("marker", name=marker_name, **fields))

    make_shot.export(os.path.join(out_dir, "shot.gltf"))
    scene.frame_set(motion_shot.FRAME)
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main()
