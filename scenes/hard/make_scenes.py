"""Writes the hard-case scenes of scenes/hard/ (README.md there: what each case expects and how
tests/hard/ checks it). Standard library only; the glTF writer is tests/cli/gltf_files.py's.

Run from anywhere: python3 scenes/hard/make_scenes.py [FOLDER] (default: this script's folder).
The files are committed; running the script again rewrites them byte for byte.

Units: metres, W/sr for point lights (written as candela, x 683, as KHR_lights_punctual wants),
W/m^2 for the sun (lux, x 683), radiance W sr^-1 m^-2 for emission. Cameras carry Blender's
physical values in FILMBACK_blender (docs/blender.md, "What is carried"), and yfov to match.
"""

import math
import struct
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests" / "cli"))
from gltf_files import FLOAT, Gltf  # noqa: E402

LUMENS_PER_WATT = 683.0


# --- geometry ----------------------------------------------------------------------------------

def uv_sphere(radius, segments, rings):
    """Positions, exact unit normals and counter-clockwise (outward) triangles of a UV sphere."""
    points, normals, triangles = [], [], []
    for j in range(rings + 1):
        theta = math.pi * j / rings
        for i in range(segments + 1):
            phi = 2 * math.pi * i / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            normals.append(n)
            points.append(tuple(radius * c for c in n))
    for j in range(rings):
        for i in range(segments):
            a, b = j * (segments + 1) + i, (j + 1) * (segments + 1) + i
            if j > 0:
                triangles += [a, b, a + 1]
            if j < rings - 1:
                triangles += [a + 1, b, b + 1]
    return points, normals, triangles


def icosphere(radius, subdivisions):
    """A convex icosphere: its vertices on the sphere, flat triangles, no normals."""
    t = (1 + math.sqrt(5)) / 2
    points = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
              (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    points = [normalize(p) for p in points]
    for _ in range(subdivisions):
        middle, refined = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                points.append(normalize([(x + y) / 2 for x, y in zip(points[a], points[b])]))
                middle[key] = len(points) - 1
            return middle[key]
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            refined += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = refined
    return [tuple(radius * c for c in p) for p in points], [i for f in faces for i in f]


def grid(half, cells, height):
    """A square of side 2 half in the plane y = 0 facing +y, cells x cells quads; height(i, j)
    lifts vertex (i, j)."""
    points, triangles = [], []
    for j in range(cells + 1):
        for i in range(cells + 1):
            points.append((-half + 2 * half * i / cells, height(i, j), -half + 2 * half * j / cells))
    for j in range(cells):
        for i in range(cells):
            a = j * (cells + 1) + i
            b = a + cells + 1
            triangles += [a, b, a + 1, a + 1, b, b + 1]
    return points, triangles


def octahedron(radius):
    p = [(radius, 0, 0), (-radius, 0, 0), (0, radius, 0), (0, -radius, 0), (0, 0, radius),
         (0, 0, -radius)]
    return p, [0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5]


def normalize(v):
    length = math.sqrt(sum(c * c for c in v))
    return tuple(c / length for c in v)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def look_at(eye, target, up=(0.0, 1.0, 0.0)):
    """The glTF rotation (x, y, z, w) of a camera at `eye` looking at `target` (cameras look down
    their -Z with +Y up)."""
    z = normalize([e - t for e, t in zip(eye, target)])
    x = normalize(cross(up, z))
    y = cross(z, x)
    m = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]  # columns x, y, z
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 2 * math.sqrt(1 + trace)
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4]
    k = max(range(3), key=lambda i: m[i][i])
    i, j = (k + 1) % 3, (k + 2) % 3
    s = 2 * math.sqrt(1 + m[k][k] - m[i][i] - m[j][j])
    q = [0.0, 0.0, 0.0, (m[j][i] - m[i][j]) / s]
    q[k], q[i], q[j] = s / 4, (m[i][k] + m[k][i]) / s, (m[j][k] + m[k][j]) / s
    return q


# --- a scene -----------------------------------------------------------------------------------

class Scene(Gltf):
    def __init__(self, generator):
        super().__init__()
        self.doc["asset"]["generator"] = "scenes/hard/make_scenes.py: " + generator
        self.doc["materials"] = []
        self.used = []

    def use(self, extension):
        if extension not in self.used:
            self.used.append(extension)
            self.doc["extensionsUsed"] = self.used

    def lambertian(self, name, albedo):
        """glTF's default dielectric less its specular layer: a Lambertian reflector."""
        self.use("KHR_materials_specular")
        self.doc["materials"].append({
            "name": name, "pbrMetallicRoughness": {"baseColorFactor": list(albedo) + [1.0],
                                                   "metallicFactor": 0.0},
            "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}})
        return len(self.doc["materials"]) - 1

    def metal(self, name, colour, roughness):
        self.doc["materials"].append({
            "name": name, "pbrMetallicRoughness": {"baseColorFactor": list(colour) + [1.0],
                                                   "metallicFactor": 1.0,
                                                   "roughnessFactor": roughness}})
        return len(self.doc["materials"]) - 1

    def emitter(self, name, radiance):
        """Black, emitting `radiance` (W sr^-1 m^-2) from both faces."""
        scale = max(radiance)
        material = {"name": name, "doubleSided": True,
                    "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0],
                                             "metallicFactor": 0.0},
                    "emissiveFactor": [c / scale for c in radiance]}
        if scale != 1:
            self.use("KHR_materials_emissive_strength")
            material["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": scale}}
        self.doc["materials"].append(material)
        return len(self.doc["materials"]) - 1

    def vec3(self, values):
        data = b"".join(struct.pack("<3f", *v) for v in values)
        index = self.accessor(self.view(data), FLOAT, "VEC3", len(values))
        return index

    def triangles(self, name, points, indices, material, normals=None):
        attributes = {"POSITION": self.positions(points)}
        if normals:
            attributes["NORMAL"] = self.vec3(normals)
        primitive = {"attributes": attributes, "indices": self.indices(indices),
                     "material": material}
        self.doc["meshes"].append({"name": name, "primitives": [primitive]})
        return len(self.doc["meshes"]) - 1

    def point_light(self, name, watts_per_sr, position):
        return self.light({"name": name, "type": "point", "color": [1.0, 1.0, 1.0],
                           "intensity": watts_per_sr * LUMENS_PER_WATT}, translation=position)

    def sun(self, name, watts_per_m2, towards_light):
        """A directional light shining from `towards_light` (glTF lights shine down -Z)."""
        return self.light({"name": name, "type": "directional", "color": [1.0, 1.0, 1.0],
                           "intensity": watts_per_m2 * LUMENS_PER_WATT},
                          rotation=look_at((0, 0, 0), [-c for c in towards_light],
                                           up=(0.0, 0.0, 1.0) if abs(towards_light[1]) > 0.99
                                           else (0.0, 1.0, 0.0)))

    def light(self, light, **node):
        self.use("KHR_lights_punctual")
        lights = self.doc.setdefault("extensions", {}).setdefault(
            "KHR_lights_punctual", {"lights": []})["lights"]
        lights.append(light)
        return self.node(name=light["name"],
                         extensions={"KHR_lights_punctual": {"light": len(lights) - 1}}, **node)

    def camera(self, name, width_px, height_px, focal_mm, sensor_mm=(36.0, 24.0), fstop=None,
               focus_m=None, clip=(0.1, 1000.0), **node):
        """A perspective camera with fit AUTO (the larger image side spans the sensor width) and the
        shot's resolution, in FILMBACK_blender and as yfov/aspectRatio."""
        self.use("FILMBACK_blender")
        aspect = width_px / height_px
        extent_x = sensor_mm[0] / focal_mm if aspect >= 1 else sensor_mm[0] / focal_mm * aspect
        physical = {"focal_length_mm": focal_mm, "sensor_width_mm": sensor_mm[0],
                    "sensor_height_mm": sensor_mm[1], "sensor_fit": "auto",
                    "clip_near_m": clip[0], "clip_far_m": clip[1]}
        if fstop is not None:
            physical["fstop"] = fstop
        if focus_m is not None and math.isfinite(focus_m):  # absent: focused at infinity
            physical["focus_distance_m"] = focus_m
        cameras = self.doc.setdefault("cameras", [])
        cameras.append({"name": name, "type": "perspective",
                        "perspective": {"yfov": 2 * math.atan(extent_x / aspect / 2),
                                        "aspectRatio": aspect, "znear": clip[0], "zfar": clip[1]},
                        "extensions": {"FILMBACK_blender": physical}})
        self.doc["scenes"][0]["extensions"] = {
            "FILMBACK_blender": {"resolution_x_px": width_px, "resolution_y_px": height_px}}
        return self.node(name=name, camera=len(cameras) - 1, **node)


def offset(point, by):
    return [p + b for p, b in zip(point, by)]


# --- the cases (README.md) ---------------------------------------------------------------------

def far_from_origin(distance_m):
    """A floor, a smooth sphere and a box 2 m in front of a camera, lit by a point light, with the
    whole shot (camera included) moved `distance_m` along a direction whose components (like a real
    shot's coordinates) are not round numbers, so that render space's subtraction rounds."""
    s = Scene("far_from_origin(%g)" % distance_m)
    by = [distance_m * c for c in (1.0, 0.7071067811865476, -0.3183098861837907)]
    floor = s.triangles("floor", *grid(4.0, 1, lambda i, j: 0.0), s.lambertian("grey", (0.5,) * 3))
    points, normals, triangles = uv_sphere(0.5, 24, 12)
    sphere = s.triangles("sphere", points, triangles, s.lambertian("orange", (0.8, 0.4, 0.1)),
                         normals)
    cube_points = [(x, y, z) for x in (-0.2, 0.2) for y in (0.0, 0.4) for z in (-0.2, 0.2)]
    cube_faces = [0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1, 2, 3, 7, 2, 7, 6, 0, 2, 6,
                  0, 6, 4, 1, 5, 7, 1, 7, 3]
    cube = s.triangles("box", cube_points, cube_faces, s.lambertian("blue", (0.2, 0.3, 0.7)))
    s.node(name="floor", mesh=floor, translation=by)
    s.node(name="sphere", mesh=sphere, translation=offset([0.0, 0.5, -2.0], by))
    s.node(name="box", mesh=cube, translation=offset([-0.75, 0.0, -2.3], by),
           rotation=[0.0, math.sin(0.3), 0.0, math.cos(0.3)])
    s.point_light("lamp", 20.0, offset([1.2, 2.5, -1.0], by))
    eye = [0.0, 0.8, 0.0]
    s.camera("shot", 96, 64, 40.0, rotation=look_at(eye, [0.0, 0.45, -2.0]),
             translation=offset(eye, by))
    return s


def markers_in_view(focal_mm, sensor_mm, width_px, height_px, depth_m, side_px, fractions):
    """Emissive squares facing a camera at the origin (looking down -Z), on the plane z = -depth,
    each centred at the given fractions of the half image (x right, y up), `side_px` across."""
    s = Scene("markers_in_view(%g mm)" % focal_mm)
    tan_half_x = sensor_mm[0] / (2 * focal_mm)  # alpha = 2 atan(w / 2f)
    tan_half_y = tan_half_x * height_px / width_px
    half = side_px / 2 * 2 * tan_half_x / width_px * depth_m
    square = s.triangles("square", [(-half, -half, 0.0), (half, -half, 0.0), (half, half, 0.0),
                                    (-half, half, 0.0)], [0, 1, 2, 0, 2, 3],
                         s.emitter("white", (1.0, 1.0, 1.0)))
    for k, (fx, fy) in enumerate(fractions):
        s.node(name="marker_%d" % k, mesh=square,
               translation=[fx * tan_half_x * depth_m, fy * tan_half_y * depth_m, -depth_m])
    s.camera("shot", width_px, height_px, focal_mm, sensor_mm, clip=(0.01, 10 * depth_m))
    return s


MARKER_FRACTIONS = [(0.0, 0.0), (0.5, 0.0), (-0.9, 0.0), (0.0, 0.8), (0.85, -0.8), (-0.7, 0.6)]


def defocus_markers(focal_mm, fstop, focus_m, depths_m, sensor_mm, width_px, image_radius_px=1.5):
    """Emissive octahedra at the given depths along a row across the view, each imaging (in focus)
    to a diamond of half-diagonal `image_radius_px`; a thin lens of f/fstop focused at focus_m."""
    s = Scene("defocus_markers(f/%g)" % fstop)
    white = s.emitter("white", (1.0, 1.0, 1.0))
    pixel_m = sensor_mm / width_px * 1e-3
    focal_m = focal_mm * 1e-3
    for k, depth in enumerate(depths_m):
        radius = image_radius_px * pixel_m * depth / focal_m
        mesh = s.triangles("octahedron_%d" % k, *octahedron(radius), white)
        across = (k + 0.5) / len(depths_m) - 0.5  # of the image width, at the marker's depth
        s.node(name="marker_%d" % k, mesh=mesh,
               translation=[across * sensor_mm / focal_mm * depth, 0.0, -depth])
    s.camera("shot", width_px, 40, focal_mm, (sensor_mm, sensor_mm),
             fstop=fstop, focus_m=focus_m, clip=(1e-3, 1e4))
    return s


def self_intersection():
    """A nearly coplanar floor (a 16 x 16 grid whose vertices are lifted by up to 1 um) and a
    convex icosphere off its edge, lit by a point light 5 cm above the floor, so that light reaches
    most of the floor at grazing angles; nothing shadows anything."""
    s = Scene("self_intersection")

    def lift(i, j):  # a fixed pseudo-random pattern in [-1, 1] um
        return 1e-6 * math.sin(12.9898 * i + 78.233 * j) * math.cos(4.1414 * i * j + 1.0)
    floor = s.triangles("floor", *grid(2.0, 16, lift), s.lambertian("floor", (0.5,) * 3))
    points, triangles = icosphere(0.5, 2)
    ball = s.triangles("ball", points, triangles, s.lambertian("ball", (0.5,) * 3))
    s.node(name="floor", mesh=floor)
    s.node(name="ball", mesh=ball, translation=[3.0, 0.5, 0.0])
    s.point_light("lamp", 2.0, [0.0, 0.05, 0.0])
    eye = [0.0, 3.0, 3.0]
    s.camera("shot", 64, 64, 30.0, rotation=look_at(eye, [0.0, 0.0, 0.0]), translation=eye)
    return s


def terminator():
    """A low-poly sphere (12 x 6 segments, 1 m radius) with the exact sphere's normals, lit by a
    sun from the side, seen from 4 m."""
    s = Scene("terminator")
    points, normals, triangles = uv_sphere(1.0, 12, 6)
    ball = s.triangles("ball", points, triangles, s.lambertian("white", (0.8,) * 3), normals)
    s.node(name="ball", mesh=ball)
    s.sun("sun", 3.0, normalize((1.0, 0.25, 0.35)))
    s.camera("shot", 96, 96, 50.0, (36.0, 36.0), translation=[0.0, 0.0, 4.0])
    return s


def degenerate_triangles():
    """A 2 x 2 m Lambertian square 3 m in front of the camera, two triangles, with zero-area
    triangles among them (a repeated vertex, three collinear vertices on its diagonal, three
    equal vertices, a zero normal), lit by a point light; and a small emissive triangle whose mesh
    also holds zero-area triangles, which light sampling must not choose."""
    s = Scene("degenerate_triangles")
    square = [(-1.0, -1.0, 0.0), (1.0, -1.0, 0.0), (1.0, 1.0, 0.0), (-1.0, 1.0, 0.0),
              (0.0, 0.0, 0.0), (0.5, 0.5, 0.0)]
    normals = [(0.0, 0.0, 1.0)] * 5 + [(0.0, 0.0, 0.0)]
    indices = [0, 1, 2, 0, 0, 1, 0, 4, 2, 4, 4, 4, 2, 3, 0, 4, 5, 4, 5, 2, 4]
    wall = s.triangles("wall", square, indices, s.lambertian("wall", (0.5,) * 3), normals)
    s.node(name="wall", mesh=wall, translation=[0.0, 0.0, -3.0])
    lamp = [(0.0, 0.0, 0.0), (0.2, 0.0, 0.0), (0.0, 0.2, 0.0), (0.1, 0.0, 0.0)]
    emitter = s.triangles("lamp", lamp, [0, 1, 3, 0, 1, 2, 2, 2, 2], s.emitter("lamp", (50.0,) * 3))
    s.node(name="lamp", mesh=emitter, translation=[0.1, 1.2, -1.5],
           rotation=[0.0, 1.0, 0.0, 0.0])  # above the view, turned to face the wall (-Z)
    s.point_light("bulb", 1.0, [0.4, 0.6, -1.0])
    s.camera("shot", 64, 64, 30.0, (36.0, 36.0))
    return s


def coincident_surfaces():
    """Two 2 x 2 m squares in the same plane 3 m in front of the camera, triangulated along
    different diagonals, one reddish and one greenish, lit by a point light."""
    s = Scene("coincident_surfaces")
    corners = [(-1.0, -1.0, 0.0), (1.0, -1.0, 0.0), (1.0, 1.0, 0.0), (-1.0, 1.0, 0.0)]
    a = s.triangles("a", corners, [0, 1, 2, 0, 2, 3], s.lambertian("reddish", (0.6, 0.3, 0.3)))
    b = s.triangles("b", corners, [0, 1, 3, 1, 2, 3], s.lambertian("greenish", (0.3, 0.6, 0.3)))
    s.node(name="a", mesh=a, translation=[0.0, 0.0, -3.0])
    s.node(name="b", mesh=b, translation=[0.0, 0.0, -3.0])
    s.point_light("bulb", 1.0, [0.4, 0.6, -1.0])
    s.camera("shot", 64, 64, 30.0, (36.0, 36.0))
    return s


def emissive_wall(width_px, height_px, covered_to_px=None):
    """A wall of radiance (0.25, 1.5, 3) 5 m in front of a 50 mm camera, filling the view, or
    (covered_to_px) covering the image left of that raster column exactly. It reaches 2 m beyond
    the widest filter's reach (16 px around the image), no further: float vertices resolve a
    triangle's edge to about 1e-7 of their size, so a kilometre-wide wall would blur its edge by a
    quarter pixel in the 16384 px frame."""
    s = Scene("emissive_wall(%dx%d)" % (width_px, height_px))
    tan_half_x = 36.0 / (2 * 50.0)
    half_x = tan_half_x * 5.0 * (1 + 32 / width_px) + 2.0
    half_y = tan_half_x * 5.0 * height_px / width_px * (1 + 32 / height_px) + 2.0
    right = half_x if covered_to_px is None else (
        (covered_to_px / width_px * 2 - 1) * tan_half_x * 5.0)
    wall = s.triangles("wall", [(-half_x, -half_y, 0.0), (right, -half_y, 0.0),
                                (right, half_y, 0.0), (-half_x, half_y, 0.0)], [0, 1, 2, 0, 2, 3],
                       s.emitter("glow", (0.25, 1.5, 3.0)))
    s.node(name="wall", mesh=wall, translation=[0.0, 0.0, -5.0])
    s.camera("shot", width_px, height_px, 50.0)
    return s


def emissive_wall_of(radiance):
    """A wall of the given radiance in front of the camera: 1e39 is a finite JSON number
    (emissiveFactor 1 x emissiveStrength 1e39) beyond float's range."""
    s = Scene("emissive_wall_of(%g)" % max(radiance))
    wall = s.triangles("wall", [(-1.0, -1.0, 0.0), (1.0, -1.0, 0.0), (1.0, 1.0, 0.0),
                                (-1.0, 1.0, 0.0)], [0, 1, 2, 0, 2, 3], s.emitter("glow", radiance))
    s.node(name="wall", mesh=wall, translation=[0.0, 0.0, -5.0])
    s.camera("shot", 32, 32, 50.0)
    return s


def moving_emitter():
    """An emissive square crossing the view along +x at 1 m/s (x = t - 1 at t s), 5 m away."""
    s = Scene("moving_emitter")
    square = s.triangles("square", [(-0.2, -0.2, 0.0), (0.2, -0.2, 0.0), (0.2, 0.2, 0.0),
                                    (-0.2, 0.2, 0.0)], [0, 1, 2, 0, 2, 3],
                         s.emitter("glow", (1.0, 1.0, 1.0)))
    node = s.node(name="square", mesh=square, translation=[-1.0, 0.0, -5.0])
    times = s.accessor(s.view(struct.pack("<2f", 0.0, 2.0)), FLOAT, "SCALAR", 2)
    values = s.accessor(s.view(struct.pack("<6f", -1.0, 0.0, -5.0, 1.0, 0.0, -5.0)), FLOAT,
                        "VEC3", 2)
    s.doc["animations"] = [{"name": "cross", "channels": [
        {"sampler": 0, "target": {"node": node, "path": "translation"}}],
        "samplers": [{"input": times, "output": values, "interpolation": "LINEAR"}]}]
    s.camera("shot", 96, 32, 50.0)
    return s


def bright_emitter():
    """A Lambertian floor under a 1 x 1 m panel of radiance 1 and, beside it, a 2 x 2 cm tile of
    radiance 1e6, both facing down from 1 m up; the camera looks down at the floor. A small
    upright mirror-like metal plate at x = 2 m reflects the tile onto the floor around x = 1 m:
    a caustic, which light sampling cannot find and BSDF sampling rarely does (fireflies)."""
    s = Scene("bright_emitter")
    floor = s.triangles("floor", *grid(3.0, 1, lambda i, j: 0.0), s.lambertian("floor", (0.5,) * 3))
    s.node(name="floor", mesh=floor)

    def panel(name, half, radiance, at):
        mesh = s.triangles(name, [(-half, 0.0, -half), (half, 0.0, -half), (half, 0.0, half),
                                  (-half, 0.0, half)], [0, 1, 2, 0, 2, 3],
                           s.emitter(name, (radiance,) * 3))
        s.node(name=name, mesh=mesh, translation=at)
    panel("panel", 0.5, 1.0, [-0.6, 1.0, 0.0])
    panel("tile", 0.01, 1e6, [0.6, 1.0, 0.0])
    plate = s.triangles("plate", [(0.0, -0.2, -0.3), (0.0, -0.2, 0.3), (0.0, 0.2, 0.3),
                                  (0.0, 0.2, -0.3)], [0, 1, 2, 0, 2, 3],
                        s.metal("mirror", (0.9, 0.9, 0.9), 0.05))
    s.node(name="plate", mesh=plate, translation=[2.0, 0.3, 0.0])
    eye = [0.0, 0.5, 2.5]
    s.camera("shot", 64, 48, 35.0, rotation=look_at(eye, [0.0, 0.25, 0.0]), translation=eye)
    return s


def bad_vertex_data(attribute, element, value):
    """One triangle 3 m in front of the camera, with smooth normals, whose `attribute` (POSITION
    or NORMAL) has `value` in component 1 of element `element`."""
    s = Scene("bad_vertex_data(%s)" % attribute)
    data = {"POSITION": [(-1.0, -1.0, 0.0), (1.0, -1.0, 0.0), (0.0, 1.0, 0.0)],
            "NORMAL": [(0.0, 0.0, 1.0)] * 3}
    point = list(data[attribute][element])
    point[1] = value
    data[attribute][element] = tuple(point)
    mesh = s.triangles("triangle", data["POSITION"], [0, 1, 2], s.lambertian("grey", (0.5,) * 3),
                       data["NORMAL"])
    s.node(name="triangle", mesh=mesh, translation=[0.0, 0.0, -3.0])
    s.point_light("bulb", 1.0, [0.0, 0.0, -1.0])
    s.camera("shot", 32, 32, 50.0)
    return s


CASES = {
    "far_origin.gltf": lambda: far_from_origin(0.0),
    "far_1e5.gltf": lambda: far_from_origin(1e5),
    "far_1e7.gltf": lambda: far_from_origin(1e7),
    "fov_2000mm.gltf": lambda: markers_in_view(2000.0, (17.45, 13.0), 128, 96, 1000.0, 3.0,
                                               MARKER_FRACTIONS),
    "fov_8mm.gltf": lambda: markers_in_view(8.0, (90.73, 45.0), 256, 128, 1.0, 4.0,
                                            MARKER_FRACTIONS),
    "aperture_f0_95.gltf": lambda: defocus_markers(50.0, 0.95, 2.0, [1.2, 2.0, 4.0], 14.4, 150),
    "aperture_f182.gltf": lambda: defocus_markers(50.0, 182.0, math.inf, [0.08, 0.12, 100.0], 3.6,
                                                  150),
    "focus_near_focal_length.gltf": lambda: defocus_markers(50.0, 8.0, 0.0505, [0.055, 0.0505],
                                                            9.6, 100),
    "focus_inside_focal_length.gltf": lambda: defocus_markers(50.0, 2.8, 0.04, [1.0], 14.4, 32),
    "self_intersection.gltf": self_intersection,
    "terminator.gltf": terminator,
    "degenerate_triangles.gltf": degenerate_triangles,
    "coincident_surfaces.gltf": coincident_surfaces,
    "one_pixel.gltf": lambda: emissive_wall(1, 1),
    "wide_image.gltf": lambda: emissive_wall(16384, 64, covered_to_px=8192),
    "filter_edge.gltf": lambda: emissive_wall(80, 48, covered_to_px=40.3),
    "moving_emitter.gltf": moving_emitter,
    "bright_emitter.gltf": bright_emitter,
    "nan_position.gltf": lambda: bad_vertex_data("POSITION", 2, math.nan),
    "inf_normal.gltf": lambda: bad_vertex_data("NORMAL", 1, math.inf),
    "huge_normal.gltf": lambda: bad_vertex_data("NORMAL", 1, 3e38),
    "inf_emission.gltf": lambda: emissive_wall_of((1e39,) * 3),
}


def main():
    folder = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent
    for name, make in CASES.items():
        make().write(folder / name)


if __name__ == "__main__":
    main()
