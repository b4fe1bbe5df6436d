"""Blender's own evaluated deformation (armatures, shape keys, deform modifiers, geometry nodes,
baked simulations) as the node's FILMBACK_deformation extension: the depsgraph's vertex positions
and split normals at the times Cycles would sample them, per exported primitive vertex, so that
filmback renders what Blender deformed instead of re-evaluating the glTF skin or morph targets
(docs/scenes.md, "Blender's evaluated deformation").

Times follow Cycles 3.4 (intern/cycles/blender/object.cpp, object_motion_steps): with motion
blur and the object's deformation blur on, 2^motion_steps + 1 positions evenly spaced over the
open shutter, at most 129; otherwise one, at the frame.

Blender's exporter writes each primitive's vertices from the base mesh (the shape keys' reference
key), one per distinct (vertex, split normal, UV...) corner, without saying which Blender vertex
each came from (io_scene_gltf2 gltf2_blender_gather_primitives_extract.py): each exported vertex
is matched back to the Blender vertex at its position and, among that vertex's corners, to the
one whose split normal is nearest the exported normal. A skinned node's positions are in world
space (the exporter bakes matrix_world in and glTF ignores the node's transform), an unskinned
node's in its object space.
"""

import numpy as np

import bpy
from mathutils import kdtree

EXTENSION = "FILMBACK_deformation"
CYCLES_MAX_MOTION_POSITIONS = 129  # Object::MAX_MOTION_STEPS, also Embree's limit
# How far an exported vertex may sit from the base vertex it came from: the exporter rounds to
# float32, and a skinned mesh's positions went through matrix_world in float32.
MATCH_TOLERANCE_RELATIVE = 1e-5
# Base vertices this close to the nearest one count as coinciding with it (a few float32 ulps).
COINCIDENT_RELATIVE = 1e-6


def position_count(scene, obj):
    """How many evaluated positions Cycles 3.4 stores for the object's deformation."""
    cycles = getattr(obj, "cycles", None)
    if not scene.render.use_motion_blur or cycles is None or not cycles.use_motion_blur or \
            not cycles.use_deform_motion:
        return 1
    steps = max(1, cycles.motion_steps)
    return min((2 << (steps - 1)) + 1, CYCLES_MAX_MOTION_POSITIONS)


def step_times(scene, obj):
    """Seconds relative to the frame's time (docs/conventions.md, "Shutter")."""
    count = position_count(scene, obj)
    if count == 1:
        return [0.0]
    from .shot import shutter
    s = shutter(scene)
    open_s, close_s = s["shutter_open_s"], s["shutter_close_s"]
    return [open_s + (close_s - open_s) * k / (count - 1) for k in range(count)]


def set_time(scene, frame, time_s):
    """Seconds on the file's timeline are frames / fps (shot.shutter says why fps_base is out)."""
    offset = frame + time_s * scene.render.fps
    whole = int(np.floor(offset))
    scene.frame_set(whole, subframe=offset - whole)


class Evaluated:
    """The evaluated mesh at the scene's current time: positions, split normals, the corners'
    vertices (its topology), and the object's matrix_world; `with_faces` adds what a mesh of its
    own needs (evaluated_mesh.py): its triangles' corners and material slots, and its UV maps'
    coordinates per corner."""

    def __init__(self, obj, with_faces=False):
        depsgraph = bpy.context.evaluated_depsgraph_get()
        evaluated = obj.evaluated_get(depsgraph)
        me = evaluated.to_mesh()
        try:
            me.calc_normals_split()
            self.positions = read(me.vertices, "co", 3)
            self.normals = read(me.loops, "normal", 3)
            self.corner_vertices = read(me.loops, "vertex_index", 1, np.int64)
            if with_faces:
                me.calc_loop_triangles()
                self.triangles = read(me.loop_triangles, "loops", 3, np.int64)
                self.triangle_materials = read(me.loop_triangles, "material_index", 1, np.int64)
                self.uv_maps = [read(layer.data, "uv", 2) for layer in me.uv_layers]
        finally:
            evaluated.to_mesh_clear()
        self.matrix_world = np.array(evaluated.matrix_world, dtype=np.float64)

    def placed(self, world_space):
        """Positions and unit normals in glTF axes (x, z, -y), in world space or object space."""
        positions, normals = self.positions, self.normals
        if world_space:
            m = self.matrix_world
            positions = positions @ m[:3, :3].T + m[:3, 3]
            normals = normals @ np.linalg.inv(m[:3, :3])
            lengths = np.linalg.norm(normals, axis=1, keepdims=True)
            normals = np.divide(normals, lengths, out=np.zeros_like(normals), where=lengths > 0)
        return yup(positions), yup(normals)

    def same_topology(self, other):
        return np.array_equal(self.corner_vertices, other.corner_vertices) and \
            len(self.positions) == len(other.positions)


def read(collection, name, width, dtype=np.float64):
    """`name` of every item of a bpy collection, as an array of `width` columns (flat for 1)."""
    out = np.empty(len(collection) * width, dtype=dtype)
    collection.foreach_get(name, out)
    return out if width == 1 else out.reshape(-1, width)


def yup(v):
    return np.stack([v[:, 0], v[:, 2], -v[:, 1]], axis=1)


def base_positions(obj):
    """The positions Blender's exporter starts from: the reference shape key's, else the mesh's."""
    me = obj.data
    keys = me.shape_keys.key_blocks if me.shape_keys else None
    source = keys[0].relative_key.data if keys else me.vertices
    return read(source, "co", 3)


def accessor_data(attribute):
    return np.frombuffer(attribute.buffer_view.data, dtype=np.float32).reshape(-1, 3)


def match_corners(gltf_mesh, base_yup, at_frame_yup_normals, corner_vertices):
    """Per primitive, the evaluated corner each exported vertex came from (its vertex is
    corner_vertices[corner]); None when a vertex has no base vertex at its position."""
    tree = kdtree.KDTree(len(base_yup))
    for i, p in enumerate(base_yup):
        tree.insert(p, i)
    tree.balance()
    scale = max(float(np.max(np.abs(base_yup))) if len(base_yup) else 0.0, 1.0)
    tolerance = MATCH_TOLERANCE_RELATIVE * scale
    order = np.argsort(corner_vertices, kind="stable")
    starts = np.searchsorted(corner_vertices[order], np.arange(len(base_yup) + 1))
    out = []
    for primitive in gltf_mesh.primitives:
        positions = accessor_data(primitive.attributes["POSITION"])
        normals = accessor_data(primitive.attributes["NORMAL"]) \
            if "NORMAL" in primitive.attributes else None
        corners = np.empty(len(positions), dtype=np.int64)
        for j, p in enumerate(positions):
            found = tree.find_range(p, tolerance)
            # The nearest base vertices (several only where vertices coincide), not every one
            # within the tolerance: a dense mesh far from the origin has neighbours inside it.
            nearest = min((distance for _, _, distance in found), default=0.0)
            candidates = [index for _, index, distance in found
                          if distance <= nearest + COINCIDENT_RELATIVE * scale]
            loops = [c for v in candidates for c in order[starts[v]:starts[v + 1]]]
            if not loops:
                return None
            if normals is None or len(loops) == 1:
                corners[j] = loops[0]
            else:
                corners[j] = max(loops, key=lambda c: float(at_frame_yup_normals[c] @ normals[j]))
        out.append(corners)
    return out


def float_accessor(array):
    from io_scene_gltf2.blender.exp.gltf2_blender_gather_primitive_attributes import \
        array_to_accessor
    from io_scene_gltf2.io.com import gltf2_io_constants
    return array_to_accessor(np.ascontiguousarray(array, dtype=np.float32),
                             gltf2_io_constants.ComponentType.Float,
                             gltf2_io_constants.DataType.Vec3, include_max_and_min=True)


class Outcome:
    """What the export of a mesh object carries: `extension` (FILMBACK_deformation or None),
    `cage` (export its Subdivision Surface as the cage, subdivision.py) and `path`, what the
    exporter's report says (None: nothing to say)."""

    def __init__(self, extension=None, path=None, cage=False):
        self.extension, self.path, self.cage = extension, path, cage


def evaluate(obj, scene, frame, times):
    """The evaluated meshes at `times` and the frame's own, with its faces, as Cycles' render
    evaluates the modifiers (render_levels.py)."""
    from .render_levels import as_rendered
    with as_rendered(obj):
        try:
            poses = []
            for t in times:
                set_time(scene, frame, t)
                poses.append(Evaluated(obj))
            set_time(scene, frame, 0.0)
            at_frame = Evaluated(obj, with_faces=True)
        finally:
            scene.frame_set(frame)
    return poses, at_frame


def ends_in_subdivision(obj):
    shown = [m for m in obj.modifiers if m.show_render]
    return bool(shown) and shown[-1].type == "SUBSURF"


def deformation_extension(obj, gltf_node, scene, frame):
    """The path a mesh object takes (docs/blender.md, "Deformation"), as an Outcome.

    A trailing Subdivision Surface travels as its cage when nothing before it moves within the
    shutter and the node has no skin (the cage, evaluated at the frame, is then what Cycles
    subdivides); otherwise, as any mesh whose modifiers change the topology, the evaluated mesh
    replaces the gathered one and carries its shapes: what Cycles renders, Blender's mesh at
    render levels and its positions at each motion step."""
    subdivided = ends_in_subdivision(obj)
    if gltf_node.mesh is None or not gltf_node.mesh.primitives:
        return Outcome(cage=subdivided)
    shown = sum(m.show_render for m in obj.modifiers)
    if not obj.data.shape_keys and shown == int(subdivided):
        return Outcome(cage=subdivided)  # nothing evaluates it away from its base mesh or cage
    times = step_times(scene, obj)
    poses, at_frame = evaluate(obj, scene, frame, times)
    world_space = gltf_node.skin is not None
    if not all(at_frame.same_topology(p) for p in poses):
        print(f"filmback: mesh object '{obj.name}': the topology changes within the shutter; "
              "the frame's shape is exported without deformation blur")
        poses, times = [at_frame], [0.0]
    placed = [p.placed(world_space) for p in poses]
    still = all(np.array_equal(positions, placed[0][0]) for positions, _ in placed)
    if subdivided and still and not world_space:
        return Outcome(cage=True, path="subdivision cage evaluated at the frame (nothing before "
                                       "its Subdivision Surface moves within the shutter)")
    if not np.array_equal(at_frame.corner_vertices, read(obj.data.loops, "vertex_index", 1,
                                                         np.int64)):
        return evaluated_mesh_outcome(obj, gltf_node, at_frame, times, placed, still,
                                      world_space)
    base = base_positions(obj)
    if world_space:
        m = np.array(obj.matrix_world, dtype=np.float64)
        base = base @ m[:3, :3].T + m[:3, 3]
    base_yup = yup(base)
    if all(np.array_equal(positions, base_yup) for positions, _ in placed) and \
            obj.data.shape_keys is None and gltf_node.skin is None:
        return Outcome()  # nothing deforms it
    corners = match_corners(gltf_node.mesh, base_yup, at_frame.placed(world_space)[1],
                            at_frame.corner_vertices)
    if corners is None:
        return Outcome(path="glTF skin/morph: its exported vertices do not match its base mesh")
    return Outcome(extension(times, world_space, corners, at_frame, placed),
                   f"Blender's evaluated deformation, {count_of_times(times)}")


def evaluated_mesh_outcome(obj, gltf_node, at_frame, times, placed, still, world_space):
    """The evaluated mesh in place of the gathered one (evaluated_mesh.py), with its shapes
    unless it is still in object space, where the mesh itself is the shape."""
    from .evaluated_mesh import replace_mesh
    if len(at_frame.triangles) == 0:  # a glTF mesh needs a primitive, a primitive triangles
        return Outcome(path="glTF mesh as exported: its evaluated mesh has no faces")
    corners = replace_mesh(gltf_node, obj, at_frame, *at_frame.placed(world_space))
    path = "Blender's evaluated mesh (its modifiers change the topology)"
    if still and not world_space:
        return Outcome(path=path + ", still")
    return Outcome(extension(times, world_space, corners, at_frame, placed),
                   f"{path} and deformation, {count_of_times(times)}")


def count_of_times(times):
    return f"{len(times)} time{'s' if len(times) > 1 else ''}"


def extension(times, world_space, corners, at_frame, placed):
    """FILMBACK_deformation: per primitive, the shapes of the corners its vertices came from."""
    primitives = []
    for corner in corners:
        vertex = at_frame.corner_vertices[corner]
        primitives.append({
            "positions": [float_accessor(positions[vertex]) for positions, _ in placed],
            "normals": [float_accessor(normals[corner]) for _, normals in placed]})
    return {"times_s": times, "world_space": world_space, "primitives": primitives}
