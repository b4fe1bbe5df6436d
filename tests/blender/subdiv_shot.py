"""The Blender side of the subdivision tests (tests/blender/blender_subdiv_test.cpp).

    blender -b --factory-startup --python subdiv_shot.py -- OUTDIR mesh
writes OUTDIR/meshes.txt: for each case, Blender's cage and the vertices of the mesh its
Subdivision Surface modifier evaluates to (object space, Blender's axes), one record a line:
  case NAME level L scheme S boundary B use_creases 0|1 use_limit 0|1 quality Q
  v X Y Z              a cage vertex
  f I J K ...          a cage face, counter-clockwise
  e I J W              an edge crease (Blender's, 0..1)
  c I W                a vertex crease
  r X Y Z              a vertex of Blender's evaluated mesh
  end

    blender -b --factory-startup --python subdiv_shot.py -- OUTDIR uv
writes OUTDIR/uvs.txt: cages with a UV map (a cube with Blender's default unwrap, whose seams
cut it into a cross; a grid whose right half is shifted in u, a seam down its middle) under
uv_smooth NONE, PRESERVE_BOUNDARIES and SMOOTH_ALL, and for each the corners of the mesh
Blender's modifier evaluates, as above plus
  case ... uv_smooth S  (the case line ends with the modifier's uv_smooth)
  t U V                 a cage corner's UV (Blender's, v up), in the order of the f records
  l X Y Z U V           a corner (loop) of Blender's evaluated mesh: its vertex and its UV

    blender -b --factory-startup --python subdiv_shot.py -- OUTDIR textured
builds the textured subdivided shot: a cube with Blender's default unwrap (its faces a cross in
UV space) and a Subdivision Surface modifier (render level 2, uv_smooth as Blender's default),
emitting material_shot.py's 8x8 red and white checker through its UV map on black; exported
with filmback's add-on and rendered with Cycles (shot.gltf, checker.png, cycles.exr,
manifest.txt).

    blender -b --factory-startup --python subdiv_shot.py -- OUTDIR subdiv
builds the subdivided-mesh shot: a cube with a Subdivision Surface modifier (render level 2,
some creases) as an emissive object on a black world, and small emissive marker spheres, seen by
make_shot.py's camera; exports it with filmback's add-on (importers/blender/export_shot.py) and
renders it with Cycles. Writes shot.gltf, cycles.exr and manifest.txt (tests/blender/blender_shot.h) with an
the markers' records; the subdivided object is compared between the two renders.
"""

import math
import os
import sys

import bmesh
import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "importers", "blender"))
import export_shot  # noqa: E402  (filmback's add-on, enabled for the session)
import make_shot  # noqa: E402  (camera, materials, Cycles settings, shot properties, records)
import material_shot  # noqa: E402  (the checker image)


def set_creases(obj, edge_creases, vertex_creases):
    """Blender 3.4 keeps edge creases on MeshEdge.crease and vertex creases in a bmesh layer."""
    me = obj.data
    for (a, b), w in edge_creases.items():
        for e in me.edges:
            if set(e.vertices) == {a, b}:
                e.crease = w
                break
        else:
            raise ValueError(f"no edge {a}-{b}")
    if vertex_creases:
        bm = bmesh.new()
        bm.from_mesh(me)
        layer = bm.verts.layers.crease.verify()
        bm.verts.ensure_lookup_table()
        for v, w in vertex_creases.items():
            bm.verts[v][layer] = w
        bm.to_mesh(me)
        bm.free()


def vertex_crease_values(me):
    bm = bmesh.new()
    bm.from_mesh(me)
    layer = bm.verts.layers.crease.active
    values = {v.index: v[layer] for v in bm.verts} if layer else {}
    bm.free()
    return {i: w for i, w in values.items() if w > 0}


def add_subsurf(obj, level, scheme="CATMULL_CLARK", boundary="ALL", use_creases=True,
                use_limit=True):
    m = obj.modifiers.new("Subdivision", "SUBSURF")
    m.levels = m.render_levels = level  # background evaluation uses the viewport level
    m.subdivision_type = scheme
    m.boundary_smooth = boundary
    m.use_creases = use_creases
    m.use_limit_surface = use_limit
    return m


def write_case(out, name, obj, uvs=False):
    m = obj.modifiers[-1]
    me = obj.data
    out.write(f"case {name} level {m.render_levels} scheme {m.subdivision_type} boundary "
              f"{m.boundary_smooth} use_creases {int(m.use_creases)} "
              f"use_limit {int(m.use_limit_surface)} quality {m.quality}"
              + (f" uv_smooth {m.uv_smooth}" if uvs else "") + "\n")
    for v in me.vertices:
        out.write("v %.9g %.9g %.9g\n" % tuple(v.co))
    for p in me.polygons:
        out.write("f " + " ".join(str(i) for i in p.vertices) + "\n")
    for e in me.edges:
        if e.crease > 0:
            out.write(f"e {e.vertices[0]} {e.vertices[1]} {e.crease:.9g}\n")
    for v, w in vertex_crease_values(me).items():
        out.write(f"c {v} {w:.9g}\n")
    if uvs:
        layer = me.uv_layers.active.data
        for p in me.polygons:
            for i in p.loop_indices:
                out.write("t %.9g %.9g\n" % tuple(layer[i].uv))
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = obj.evaluated_get(depsgraph).to_mesh()
    for v in evaluated.vertices:  # position and the normal Cycles renders with
        out.write("r %.9g %.9g %.9g %.9g %.9g %.9g\n" % (*v.co, *v.normal))
    if uvs:
        layer = evaluated.uv_layers.active.data
        for loop in evaluated.loops:
            out.write("l %.9g %.9g %.9g %.9g %.9g\n"
                      % (*evaluated.vertices[loop.vertex_index].co, *layer[loop.index].uv))
    obj.evaluated_get(depsgraph).to_mesh_clear()
    out.write("end\n")


def new_object(op, **kwargs):
    op(**kwargs)
    return bpy.context.active_object


def mesh_cases(out_dir):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    cases = []
    cube = lambda: new_object(bpy.ops.mesh.primitive_cube_add, size=2)  # noqa: E731
    for level in (1, 2):
        o = cube()
        add_subsurf(o, level)
        cases.append((f"cube_level{level}", o))
    # Creases of 0.5 (sharpness 2.5 if Blender squares, 5 if not), 1 and 0.3, and a vertex crease.
    o = cube()
    set_creases(o, {(0, 1): 0.5, (1, 3): 1.0, (4, 5): 0.3}, {6: 0.7})
    add_subsurf(o, 2)
    cases.append(("cube_creases", o))
    o = cube()
    set_creases(o, {(0, 1): 1.0}, {})
    add_subsurf(o, 2, use_creases=False)
    cases.append(("cube_creases_off", o))
    o = cube()
    add_subsurf(o, 2, use_limit=False)
    cases.append(("cube_no_limit", o))
    o = cube()
    add_subsurf(o, 2, scheme="SIMPLE")
    cases.append(("cube_simple", o))
    # Open meshes for the boundary rules: a 3x3 grid (corners of valence 2).
    # Blender's patches approximate the smooth corners under ALL, less so at higher quality
    # (blender_subdiv_test.cpp): quality 6 there.
    for boundary in ("ALL", "PRESERVE_CORNERS"):
        o = new_object(bpy.ops.mesh.primitive_grid_add, x_subdivisions=3, y_subdivisions=3, size=2)
        add_subsurf(o, 2, boundary=boundary).quality = 6 if boundary == "ALL" else 3
        cases.append((f"grid_{boundary.lower()}", o))
    # N-gons: a cylinder's 8-sided caps, and triangles: a cone's sides.
    o = new_object(bpy.ops.mesh.primitive_cylinder_add, vertices=8)
    add_subsurf(o, 2)
    cases.append(("cylinder_ngons", o))
    o = new_object(bpy.ops.mesh.primitive_cone_add, vertices=6)
    add_subsurf(o, 1)
    cases.append(("cone_triangles", o))
    bpy.context.view_layer.update()
    with open(os.path.join(out_dir, "meshes.txt"), "w") as out:
        for name, o in cases:
            write_case(out, name, o)


def seamed_grid():
    """A 3 x 3 grid (2 m) whose UV map is Blender's planar one with the right half's faces moved
    by 0.5 in u: a seam runs down the middle column of vertices."""
    o = new_object(bpy.ops.mesh.primitive_grid_add, x_subdivisions=4, y_subdivisions=4, size=2)
    me = o.data
    layer = me.uv_layers.active.data
    for p in me.polygons:
        if p.center.x > 0:
            for i in p.loop_indices:
                layer[i].uv = (layer[i].uv[0] + 0.5, layer[i].uv[1])
    return o


def uv_cases(out_dir):
    """Cages with UV seams under three uv_smooth rules; level 1 and 2, limit surface on (and once
    off); n-gons and triangles. The grid's boundary is PRESERVE_CORNERS so that the smooth-corner end caps (see
    mesh_cases) stay out of the comparison of UVs."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    cases = []
    for uv_smooth in ("PRESERVE_BOUNDARIES", "SMOOTH_ALL", "NONE"):
        for level in (1, 2):
            o = new_object(bpy.ops.mesh.primitive_cube_add, size=2)
            add_subsurf(o, level).uv_smooth = uv_smooth
            cases.append((f"cube_{uv_smooth.lower()}_level{level}", o))
        o = seamed_grid()
        add_subsurf(o, 2, boundary="PRESERVE_CORNERS").uv_smooth = uv_smooth
        cases.append((f"grid_{uv_smooth.lower()}", o))
    # Smooth All at quality 6: Blender's end caps at the islands' corners approach the limit.
    o = new_object(bpy.ops.mesh.primitive_cube_add, size=2)
    m = add_subsurf(o, 1)
    m.uv_smooth, m.quality = "SMOOTH_ALL", 6
    cases.append(("cube_smooth_all_quality6", o))
    o = new_object(bpy.ops.mesh.primitive_cube_add, size=2)
    add_subsurf(o, 2, use_limit=False)
    cases.append(("cube_no_limit", o))
    # N-gons and triangles with their default UVs: a cylinder's 8-sided caps, a cone's sides.
    o = new_object(bpy.ops.mesh.primitive_cylinder_add, vertices=8)
    add_subsurf(o, 2)
    cases.append(("cylinder_ngons", o))
    o = new_object(bpy.ops.mesh.primitive_cone_add, vertices=6)
    add_subsurf(o, 1)
    cases.append(("cone_triangles", o))
    bpy.context.view_layer.update()
    with open(os.path.join(out_dir, "uvs.txt"), "w") as out:
        for name, o in cases:
            write_case(out, name, o, uvs=True)


SHOT = make_shot.Shot(320, 200, 35.0, markers=(), samples=512)
# Small glowing spheres around the object, for the geometry of the frame itself.
MARKERS = (
    make_shot.Marker("top_left", 0.12, 0.15, 5.0, 4.0, (1.0, 1.0, 1.0), 4.0),
    make_shot.Marker("top_right", 0.88, 0.18, 7.0, 4.0, (0.6, 0.8, 1.0), 4.0),
    make_shot.Marker("bottom_right", 0.85, 0.85, 4.0, 4.0, (1.0, 0.6, 0.3), 4.0),
    make_shot.Marker("bottom_left", 0.15, 0.82, 6.0, 4.0, (0.4, 1.0, 0.4), 4.0),
)
OBJECT = "SubdividedCube"
OBJECT_DEPTH_M = 6.0
OBJECT_SIZE_M = 1.6
# Blender's creases on the cube's cage (vertex indices of primitive_cube_add): one edge fully
# sharp, one half, and a vertex crease, so the silhouette depends on the crease rule.
EDGE_CREASES = {(0, 1): 1.0, (1, 3): 0.5, (4, 5): 0.8}
VERTEX_CREASES = {6: 0.7}


def build_object(camera, frame):
    obj = new_object(bpy.ops.mesh.primitive_cube_add, size=OBJECT_SIZE_M,
                     location=camera.matrix_world @ frame.point(0.5, 0.5, OBJECT_DEPTH_M),
                     rotation=(0.4, 0.7, 0.2))
    obj.name = OBJECT
    set_creases(obj, EDGE_CREASES, VERTEX_CREASES)
    add_subsurf(obj, 2)
    obj.data.materials.append(make_shot.emission_material(OBJECT, (1.0, 0.9, 0.8), 1.0))
    bpy.ops.object.shade_smooth()
    return obj


def new_shot_scene(shot):
    """An empty scene on a black world, Cycles set up for `shot`, and its camera and frame."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    make_shot.new_world(scene)
    make_shot.configure_cycles(scene, shot)
    camera = make_shot.build_camera(scene, shot)
    bpy.context.view_layer.update()
    return scene, camera, make_shot.Frame(scene, camera)


def build_shot(out_dir):
    scene, camera, frame = new_shot_scene(SHOT)
    build_object(camera, frame)
    spheres = [(marker, *make_shot.add_sphere(camera, frame, marker, marker.depth_m))
               for marker in MARKERS]
    bpy.context.view_layer.update()

    w, h = SHOT.width_px, SHOT.height_px
    with open(os.path.join(out_dir, "manifest.txt"), "w") as manifest:
        manifest.write(make_shot.record("shot", name="subdiv", samples=SHOT.samples, width_px=w,
                                        height_px=h, camera_model="perspective"))
        for marker, sphere, radius_m in spheres:
            centre = make_shot.world_to_camera_view(scene, camera, sphere.matrix_world.translation)
            manifest.write(make_shot.record(
                "marker", name=marker.name, blender_x_px=centre.x * w,
                blender_y_px=(1.0 - centre.y) * h,
                **make_shot.expected_image(scene, camera, frame, sphere, radius_m)))
    # filmback's add-on writes the cage and the modifier (FILMBACK_blender.subdivision).
    export_shot.export(os.path.join(out_dir, "shot.gltf"), export_lights=False)
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


TEXTURED_SHOT = make_shot.Shot(240, 150, 35.0, markers=(), samples=64)
TEXTURED_DEPTH_M = 3.0


def checker_material(name, image, uv_map=None):
    """material_shot.py's checker `image`, emitted at strength 1 (radiance = the texture's linear
    value), through the UV map named `uv_map` (a UV Map node) or the active render one."""
    material = make_shot.emission_material(name, (1.0, 1.0, 1.0), 1.0)
    nodes, links = material.node_tree.nodes, material.node_tree.links
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    texture.interpolation = "Linear"
    links.new(texture.outputs["Color"], nodes["Emission"].inputs["Color"])
    if uv_map is not None:
        source = nodes.new("ShaderNodeUVMap")
        source.uv_map = uv_map
        links.new(source.outputs["UV"], texture.inputs["Vector"])
    return material


def add_shifted_half(cube, image):
    """The cube's first three faces wear a second checker material that reads a second UV map,
    "Shifted": the first moved by one checker square in u, so that a face given the wrong
    material, or the wrong map, shows every square in the other colour."""
    me = cube.data
    first = me.uv_layers.active.data
    shifted = me.uv_layers.new(name="Shifted").data
    for i, loop in enumerate(first):
        shifted[i].uv = (loop.uv[0] + 1.0 / material_shot.CHECKER_SQUARES, loop.uv[1])
    cube.data.materials.append(checker_material("checker shifted", image, "Shifted"))
    for p in me.polygons[:3]:
        p.material_index = 1


def build_textured_shot(out_dir):
    """Two subdivided objects wearing the checker, at TEXTURED_DEPTH_M on black: a cube with
    Blender's default unwrap (its faces a cross in UV space, every vertex on the island's
    boundary, so seams and boundary rules matter), half of it in a second material through a
    second UV map (add_shifted_half), and a torus with Blender's default UVs (a grid with
    interior vertices, whose smoothing the rule decides). What each pixel shows is where the
    refined UVs put the checker, with nothing else in the image."""
    scene, camera, frame = new_shot_scene(TEXTURED_SHOT)
    image = material_shot.checker_image(os.path.join(out_dir, "checker.png"))
    material = checker_material("checker", image)
    cube = new_object(bpy.ops.mesh.primitive_cube_add, size=OBJECT_SIZE_M,
                      location=camera.matrix_world @ frame.point(0.3, 0.5, TEXTURED_DEPTH_M),
                      rotation=(0.5, 0.6, 0.3))
    torus = new_object(bpy.ops.mesh.primitive_torus_add, major_segments=12, minor_segments=6,
                       major_radius=0.6, minor_radius=0.25,
                       location=camera.matrix_world @ frame.point(0.75, 0.5, TEXTURED_DEPTH_M),
                       rotation=(1.0, 0.3, 0.2))
    # Its grid of UVs waved across v: refinement reproduces linear UVs under every rule, and it is
    # where they are not linear that the rules differ.
    layer = torus.data.uv_layers.active.data
    for loop in layer:
        u, v = loop.uv
        loop.uv = (u, v + 0.06 * math.sin(2 * math.pi * 4 * u))
    for obj in (cube, torus):
        add_subsurf(obj, 2)
        obj.data.materials.append(material)
        bpy.context.view_layer.objects.active = obj
        bpy.ops.object.shade_smooth()
    add_shifted_half(cube, image)
    bpy.context.view_layer.update()
    with open(os.path.join(out_dir, "manifest.txt"), "w") as manifest:
        manifest.write(make_shot.record(
            "shot", name="textured", samples=TEXTURED_SHOT.samples,
            width_px=TEXTURED_SHOT.width_px, height_px=TEXTURED_SHOT.height_px,
            camera_model="perspective"))
    export_shot.export(os.path.join(out_dir, "shot.gltf"), export_lights=False)
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 2 or args[1] not in ("mesh", "uv", "textured", "subdiv"):
        raise SystemExit("usage: blender -b --factory-startup --python subdiv_shot.py -- OUTDIR "
                         "mesh|uv|textured|subdiv")
    out_dir = os.path.abspath(args[0])
    os.makedirs(out_dir, exist_ok=True)
    if args[1] == "mesh":
        mesh_cases(out_dir)
    elif args[1] == "uv":
        uv_cases(out_dir)
    elif args[1] == "textured":
        build_textured_shot(out_dir)
    else:
        build_shot(out_dir)


if __name__ == "__main__":
    main()
