"""A mesh whose modifiers change its topology (Subdivision Surface after an armature, Array, Mirror
with merge, Remesh, Solidify, geometry nodes that make geometry), written as Blender evaluated it:
the glTF mesh Blender's exporter gathered from the base mesh is replaced by the depsgraph's mesh
at the frame (its triangles, split normals, UV maps and materials), so that its vertices are the
ones whose positions FILMBACK_deformation carries per time (docs/blender.md, "Deformation").

Each exported vertex is one distinct (Blender vertex, split normal, UV coordinates) corner of a
material's triangles, as Blender's exporter makes them; the corner it came from is kept so the
shapes at other times are read from the same vertex and corner.
"""

import numpy as np

from .deformation import float_accessor
from .subdivision import slot_primitives


def corner_keys(pose, uv_maps):
    """Per corner: its vertex, its split normal and its coordinates in each UV map, the values
    that make two corners one exported vertex."""
    columns = [pose.corner_vertices[:, None].astype(np.float64),
               pose.normals.astype(np.float32).astype(np.float64)]
    columns += [uvs.astype(np.float32).astype(np.float64) for uvs in uv_maps]
    return np.concatenate(columns, axis=1)


def index_accessor(indices):
    from io_scene_gltf2.blender.exp.gltf2_blender_gather_primitive_attributes import \
        array_to_accessor
    from io_scene_gltf2.io.com import gltf2_io_constants
    # 65535 and 4294967295 are primitive restart values (glTF 2.0 §3.7.2.1), as the exporter's.
    small = indices.max(initial=0) < 65535
    return array_to_accessor(indices.astype(np.uint16 if small else np.uint32),
                             gltf2_io_constants.ComponentType.UnsignedShort if small else
                             gltf2_io_constants.ComponentType.UnsignedInt,
                             gltf2_io_constants.DataType.Scalar)


def uv_accessor(uvs):
    from io_scene_gltf2.blender.exp.gltf2_blender_gather_primitive_attributes import \
        array_to_accessor
    from io_scene_gltf2.io.com import gltf2_io_constants
    flipped = np.stack([uvs[:, 0], 1.0 - uvs[:, 1]], axis=1)  # glTF's v = 1 - Blender's
    return array_to_accessor(np.ascontiguousarray(flipped, dtype=np.float32),
                             gltf2_io_constants.ComponentType.Float,
                             gltf2_io_constants.DataType.Vec2)


def replace_mesh(gltf_node, obj, pose, positions, normals):
    """Puts the evaluated mesh `pose` (deformation.Evaluated with its faces; `positions` and unit
    `normals` placed in the extension's space) on the node in place of the gathered one; returns,
    per primitive, the corner each exported vertex came from."""
    from io_scene_gltf2.io.com import gltf2_io
    gathered = gltf_node.mesh
    primitives_of_slots = slot_primitives(obj, gathered)
    slots = len(primitives_of_slots) if primitives_of_slots else 0
    triangle_slots = np.minimum(pose.triangle_materials, max(slots - 1, 0))
    triangle_primitives = np.asarray(primitives_of_slots)[triangle_slots] \
        if primitives_of_slots else np.zeros(len(pose.triangles), dtype=np.int64)
    keys = corner_keys(pose, pose.uv_maps)
    primitives, corners = [], []
    for index, template in enumerate(gathered.primitives):
        triangles = pose.triangles[triangle_primitives == index]
        if len(triangles) == 0:
            continue
        used = triangles.reshape(-1)
        _, first, inverse = np.unique(keys[used], axis=0, return_index=True,
                                      return_inverse=True)
        corner = used[first]
        vertex = pose.corner_vertices[corner]
        attributes = {"POSITION": float_accessor(positions[vertex]),
                      "NORMAL": float_accessor(normals[corner])}
        for n, uvs in enumerate(pose.uv_maps):
            attributes[f"TEXCOORD_{n}"] = uv_accessor(uvs[corner])
        primitives.append(gltf2_io.MeshPrimitive(
            attributes=attributes, extensions=None, extras=None,
            indices=index_accessor(inverse.reshape(-1)), material=template.material,
            mode=template.mode, targets=None))
        corners.append(corner)
    gltf_node.mesh = gltf2_io.Mesh(extensions=gathered.extensions, extras=gathered.extras,
                                   name=gathered.name, primitives=primitives, weights=None)
    # The evaluated mesh is already posed: a skin would pose it again in other viewers.
    gltf_node.skin = None
    return corners
