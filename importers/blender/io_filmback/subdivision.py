"""A mesh whose last modifier is a Subdivision Surface, as its unrefined quad cage and the
modifier's settings (the FILMBACK_blender subdivision object): filmback refines it itself, with
the cage's UV maps (a coordinate per face corner, glTF's v = 1 - Blender's as in TEXCOORD_n) and
which of the glTF mesh's primitives (materials) each face wears."""

import bmesh
import bpy


def subdivision_extension(obj, gltf_mesh):
    modifiers = [m for m in obj.modifiers if m.show_render]
    if not modifiers or modifiers[-1].type != "SUBSURF":
        return None
    m = modifiers[-1]
    out = {"levels_render": m.render_levels, "quality": m.quality,
           "scheme": m.subdivision_type, "boundary_smooth": m.boundary_smooth,
           "use_creases": m.use_creases, "use_limit_surface": m.use_limit_surface,
           "uv_smooth": m.uv_smooth}
    out.update(cage(obj, m, gltf_mesh))
    return out


def cage(obj, modifier, gltf_mesh):
    """The mesh the modifiers before the subdivision make as Cycles' render evaluates them
    (render_levels.py), in glTF axes (x, z, -y)."""
    from .render_levels import as_rendered
    with as_rendered(obj):
        modifier.show_viewport = False  # as_rendered puts it back
        depsgraph = bpy.context.evaluated_depsgraph_get()
        evaluated = obj.evaluated_get(depsgraph)
        me = evaluated.to_mesh()
        try:
            return cage_arrays(me, face_primitives(me, obj, gltf_mesh))
        finally:
            evaluated.to_mesh_clear()


def cage_arrays(me, faces_primitives=None):
    positions = []
    for v in me.vertices:
        positions += [v.co.x, v.co.z, -v.co.y]
    edge_creases = []
    for e in me.edges:
        if e.crease > 0:
            edge_creases += [e.vertices[0], e.vertices[1], e.crease]
    vertex_creases = []
    for i, w in vertex_crease_values(me):
        vertex_creases += [i, w]
    out = {"cage_positions": positions,
           "cage_face_sizes": [len(p.vertices) for p in me.polygons],
           "cage_face_vertices": [i for p in me.polygons for i in p.vertices]}
    if edge_creases:
        out["edge_creases"] = edge_creases
    if vertex_creases:
        out["vertex_creases"] = vertex_creases
    if len(me.uv_layers) > 0:
        out["uv_maps"] = [{"name": layer.name, "uvs": corner_uvs(me, layer)}
                          for layer in me.uv_layers]
    if faces_primitives is not None:
        out["face_primitives"] = faces_primitives
    return out


def corner_uvs(me, layer):
    """The layer's coordinates at each polygon's corners, in cage_face_vertices' order, v flipped
    as Blender's exporter flips TEXCOORD_n."""
    out = []
    data = layer.data
    for p in me.polygons:
        for i in p.loop_indices:
            u, v = data[i].uv
            out += [u, 1.0 - v]
    return out


def face_primitives(me, obj, gltf_mesh):
    """Which primitive of the exported mesh each polygon's material went to, or None when the mesh
    has one primitive."""
    primitives = slot_primitives(obj, gltf_mesh)
    if primitives is None:
        return None
    # Blender clamps a polygon's material index to the slots there are.
    return [primitives[min(p.material_index, len(primitives) - 1)] for p in me.polygons]


def slot_primitives(obj, gltf_mesh):
    """Per material slot (at least one), the primitive of the exported mesh its material went to,
    or None when the mesh has one primitive. Blender's exporter makes a primitive per material
    slot used, with the slot's material (io_scene_gltf2 gltf2_blender_gather_primitives_extract.py):
    a slot's primitive is the one whose material is its material, found by name (the first
    primitive for a material it has none of)."""
    primitives = list(getattr(gltf_mesh, "primitives", None) or [])
    if len(primitives) < 2:
        return None
    names = [getattr(p.material, "name", None) if p.material is not None else None
             for p in primitives]
    materials = [slot.material for slot in obj.material_slots] or [None]
    out = []
    for material in materials:
        name = material.name if material is not None else None
        out.append(names.index(name) if name in names else 0)
    return out


def vertex_crease_values(me):
    """Blender 3.4 keeps vertex creases in a bmesh layer, not on MeshVertex."""
    bm = bmesh.new()
    try:
        bm.from_mesh(me)
        layer = bm.verts.layers.crease.active
        return [(v.index, v[layer]) for v in bm.verts if layer and v[layer] > 0]
    finally:
        bm.free()
