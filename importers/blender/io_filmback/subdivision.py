"""A mesh whose last modifier is a Subdivision Surface, as its unrefined quad cage and the
modifier's settings (the FILMBACK_blender subdivision object): filmback refines it itself."""

import bmesh
import bpy


def subdivision_extension(obj):
    modifiers = [m for m in obj.modifiers if m.show_render]
    if not modifiers or modifiers[-1].type != "SUBSURF":
        return None
    m = modifiers[-1]
    out = {"levels_render": m.render_levels, "quality": m.quality,
           "scheme": m.subdivision_type, "boundary_smooth": m.boundary_smooth,
           "use_creases": m.use_creases, "use_limit_surface": m.use_limit_surface,
           "uv_smooth": m.uv_smooth}
    out.update(cage(obj, m))
    return out


def cage(obj, modifier):
    """The mesh the modifiers before the subdivision make, in glTF axes (x, z, -y)."""
    shown = modifier.show_viewport
    modifier.show_viewport = False
    try:
        depsgraph = bpy.context.evaluated_depsgraph_get()
        evaluated = obj.evaluated_get(depsgraph)
        me = evaluated.to_mesh()
        try:
            return cage_arrays(me)
        finally:
            evaluated.to_mesh_clear()
    finally:
        modifier.show_viewport = shown
        bpy.context.evaluated_depsgraph_get()


def cage_arrays(me):
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
