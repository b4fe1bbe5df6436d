"""The Blender side of tests/blender/deformation_export_test.py: which path each mesh takes through
the add-on's FILMBACK_deformation (importers/blender/io_filmback/deformation.py), and the written
shapes against Blender's own evaluated mesh.

    blender -b --factory-startup --python-exit-code 1 --python deformation_export_scene.py -- OUTDIR

Objects, with motion blur on (Object > Motion Blur > Steps 2: 5 positions):
  bent       a cube skinned to a two-bone armature, the lower bone bent: world-space shapes
  keyed      a cube whose shape key is keyed over the shutter: 5 object-space shapes
  plain      a cube nothing deforms: no extension
  remeshed   a cube under a Remesh modifier (other vertices than the base mesh), still: Blender's
             evaluated mesh in place of the base mesh, no extension
  subdivided `bent` under a Subdivision Surface after its Armature modifier, viewport level 0,
             render level 2: the evaluated mesh at render level with 5 world-space shapes
  arrayed    `keyed` repeated twice by an Array modifier: the evaluated mesh with 5 object-space
             shapes
  caged      a cube under a Subdivision Surface alone: its cage, no extension, nothing reported
  posed_cage a cube with a shape key at 0.5 under a Subdivision Surface, still: its cage as
             evaluated at the frame, the path reported
  decimated  a cube whose Decimate ratio is keyed from 1 at the frame down after it (the topology
             changes within the shutter): the frame's shape only, with a warning; the frame's
             shape is the base mesh, so no extension
Exports to OUTDIR/shot.gltf and raises (exit 1) naming what differs: each written position within
1e-5 of a vertex of the evaluated mesh (as Cycles' render evaluates the modifiers) at the
shutter's times, and each evaluated vertex within 1e-5 of a written one; a replaced mesh's
vertices are the frame's evaluated ones.
"""

import json
import math
import os
import struct
import sys

import bpy
import numpy as np
from mathutils import kdtree

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "importers", "blender"))
import export_shot  # noqa: E402  (filmback's add-on, enabled for this session)
from io_filmback import deformation  # noqa: E402
from io_filmback.render_levels import as_rendered  # noqa: E402
sys.path.insert(0, HERE)
from deform_shot import new_rig_in_edit_mode  # noqa: E402

FRAME = 5
STEPS = 2
TOLERANCE = 1e-5


def cube(name, x):
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(x, 0.0, 0.0))
    obj = bpy.context.active_object
    obj.name = obj.data.name = name
    obj.cycles.motion_steps = STEPS
    return obj


def bent_cube(scene, name, x):
    """A cube, subdivided in its data, skinned to a two-bone armature whose lower bone is bent."""
    bent = cube(name, x)
    bpy.ops.object.modifier_add(type="SUBSURF")  # a denser mesh to bend, applied here
    bpy.ops.object.modifier_apply(modifier=bent.modifiers[-1].name)
    data, rig = new_rig_in_edit_mode(scene)
    upper = data.edit_bones.new("upper")
    upper.head, upper.tail = (x, 0, -0.5), (x, 0, 0)
    lower = data.edit_bones.new("lower")
    lower.head, lower.tail, lower.parent = (x, 0, 0), (x, 0, 0.5), upper
    bpy.ops.object.mode_set(mode="OBJECT")
    for bone, keep in (("upper", lambda z: z <= 0), ("lower", lambda z: z > 0)):
        group = bent.vertex_groups.new(name=bone)
        group.add([v.index for v in bent.data.vertices if keep(v.co.z)], 1.0, "REPLACE")
    bent.modifiers.new("Armature", "ARMATURE").object = rig
    bent.parent = rig
    rig.pose.bones["lower"].rotation_mode = "XYZ"
    rig.pose.bones["lower"].rotation_euler = (math.radians(40), 0, 0)
    return bent


def keyed_cube(name, x):
    """A cube whose shape key is keyed from 0 to 1 over the frames around the shutter."""
    keyed = cube(name, x)
    keyed.shape_key_add(name="Basis")
    key = keyed.shape_key_add(name="Up", from_mix=False)
    for point in key.data:
        point.co.z += 0.5 * point.co.x + 0.25
    for frame, value in ((FRAME - 1, 0.0), (FRAME + 1, 1.0)):
        key.value = value
        key.keyframe_insert("value", frame=frame)
    return keyed


def build(scene):
    bent_cube(scene, "bent", 0.0)
    keyed_cube("keyed", 3.0)
    cube("plain", 6.0)
    remeshed = cube("remeshed", 9.0)
    remeshed.modifiers.new("Remesh", "REMESH").octree_depth = 3
    decimated = cube("decimated", 12.0)
    bpy.ops.object.modifier_add(type="SUBSURF")
    bpy.ops.object.modifier_apply(modifier=decimated.modifiers[-1].name)
    decimate = decimated.modifiers.new("Decimate", "DECIMATE")
    # Whole at the frame and before; decimated after it, within the shutter's second half.
    for frame, ratio in ((FRAME, 1.0), (FRAME + 1, 0.2)):
        decimate.ratio = ratio
        decimate.keyframe_insert("ratio", frame=frame)
    subdivision = bent_cube(scene, "subdivided", 15.0).modifiers.new("Subdivision", "SUBSURF")
    subdivision.levels, subdivision.render_levels = 0, 2
    arrayed = keyed_cube("arrayed", 18.0)
    arrayed.modifiers.new("Array", "ARRAY").count = 2
    cube("caged", 21.0).modifiers.new("Subdivision", "SUBSURF")
    posed = cube("posed_cage", 24.0)
    posed.shape_key_add(name="Basis")
    key = posed.shape_key_add(name="Out", from_mix=False)
    for point in key.data:
        point.co *= 1.5
    key.value = 0.5
    posed.modifiers.new("Subdivision", "SUBSURF")


def accessor(gltf, binary, index):
    a = gltf["accessors"][index]
    view = gltf["bufferViews"][a["bufferView"]]
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    values = struct.unpack_from(f"<{3 * a['count']}f", binary, start)
    return np.array(values, dtype=np.float64).reshape(-1, 3)


def evaluated_at(scene, obj, time_s, world_space):
    deformation.set_time(scene, FRAME, time_s)
    with as_rendered(obj):
        pose = deformation.Evaluated(obj)
    return pose.placed(world_space)


def nearest_distances(points, to):
    """For each of `points`, the distance to the nearest of `to`."""
    tree = kdtree.KDTree(len(to))
    for i, p in enumerate(to):
        tree.insert(p, i)
    tree.balance()
    return np.array([tree.find(p)[2] for p in points])


def check_shapes(scene, gltf, binary, node, obj, problems):
    ext = node["extensions"]["FILMBACK_deformation"]
    world = ext["world_space"]
    primitives = gltf["meshes"][node["mesh"]]["primitives"]
    for k, t in enumerate(ext["times_s"]):
        positions, _ = evaluated_at(scene, obj, t, world)
        written = []
        for p, (primitive, shapes) in enumerate(zip(primitives, ext["primitives"])):
            shape = accessor(gltf, binary, shapes["positions"][k])
            normals = accessor(gltf, binary, shapes["normals"][k])
            base = accessor(gltf, binary, primitive["attributes"]["POSITION"])
            if len(base) != len(shape):
                problems.append(f"{obj.name}: primitive {p}: {len(shape)} shapes' vertices for "
                                f"{len(base)} exported")
            if abs(np.linalg.norm(normals, axis=1) - 1).max() > TOLERANCE:
                problems.append(f"{obj.name}: primitive {p} time {k}: normals not unit")
            written.append(shape)
        written = np.concatenate(written)
        # Each written vertex is one of Blender's evaluated ones, and every one is written.
        for what, distances in (("a written position", nearest_distances(written, positions)),
                                ("an evaluated vertex", nearest_distances(positions, written))):
            if distances.max() > TOLERANCE:
                problems.append(f"{obj.name}: time {k}: {what} is {distances.max():.3g} m from "
                                "every one of the other side")
    scene.frame_set(FRAME)


def check_replaced_mesh(scene, gltf, binary, node, obj, problems):
    """A mesh whose modifiers change the topology is Blender's evaluated mesh at the frame."""
    world = node.get("extensions", {}).get("FILMBACK_deformation", {}).get("world_space", False)
    positions, _ = evaluated_at(scene, obj, 0.0, world)
    scene.frame_set(FRAME)
    written = np.concatenate([accessor(gltf, binary, p["attributes"]["POSITION"])
                              for p in gltf["meshes"][node["mesh"]]["primitives"]])
    if len(positions) == len(obj.data.vertices):
        problems.append(f"{obj.name}: its modifiers were expected to change the vertex count")
    for what, distances in (("an exported vertex", nearest_distances(written, positions)),
                            ("an evaluated vertex", nearest_distances(positions, written))):
        if distances.max() > TOLERANCE:
            problems.append(f"{obj.name}: {what} is {distances.max():.3g} m from every one of "
                            "the other side")


def main():
    out_dir = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
    os.makedirs(out_dir, exist_ok=True)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.render.use_motion_blur = True
    scene.render.motion_blur_shutter = 0.5
    scene.frame_start, scene.frame_end = 0, 10
    scene.frame_set(FRAME)
    build(scene)
    scene.frame_set(FRAME)
    path = os.path.join(out_dir, "shot.gltf")
    export_shot.export(path, export_lights=False)

    with open(path) as f:
        gltf = json.load(f)
    with open(os.path.join(out_dir, gltf["buffers"][0]["uri"]), "rb") as f:
        binary = f.read()
    nodes = {n["name"]: n for n in gltf["nodes"]}
    problems = []
    positions = (2 << (STEPS - 1)) + 1
    expected = {"bent": (positions, True), "keyed": (positions, False),
                "subdivided": (positions, True), "arrayed": (positions, False)}
    for name, (count, world) in expected.items():
        ext = nodes[name].get("extensions", {}).get("FILMBACK_deformation")
        if ext is None:
            problems.append(f"{name}: no FILMBACK_deformation")
            continue
        if len(ext["times_s"]) != count or ext["world_space"] != world:
            problems.append(f"{name}: {len(ext['times_s'])} times, world_space "
                            f"{ext['world_space']}; expected {count}, {world}")
        check_shapes(scene, gltf, binary, nodes[name], bpy.data.objects[name], problems)
    for name in ("remeshed", "subdivided", "arrayed"):
        check_replaced_mesh(scene, gltf, binary, nodes[name], bpy.data.objects[name], problems)
        if "skin" in nodes[name]:
            problems.append(f"{name}: a skin on the evaluated mesh, which is posed already")
    for name in ("plain", "remeshed", "decimated", "caged", "posed_cage"):
        if "FILMBACK_deformation" in nodes[name].get("extensions", {}):
            problems.append(f"{name}: has FILMBACK_deformation; expected none")
    for name in ("caged", "posed_cage"):
        if "subdivision" not in nodes[name].get("extensions", {}).get("FILMBACK_blender", {}):
            problems.append(f"{name}: no subdivision cage")
    if problems:
        raise SystemExit("\n".join(problems))
    print("deformation export: every check passed")


main()
