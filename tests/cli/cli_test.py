"""The command line's promise about bad input (docs/conventions.md, "Errors"): one message,
`filmback: error: file: JSON path: what was found, what was expected`, exit status 1 for bad input
and 2 for bad usage, never a crash and never an output file (not even a hidden temporary one).
What is not supported yet is skipped with one warning each, naming the JSON path.

Run: cli_test.py --filmback BIN --scratch DIR [unittest names...]; --list prints the case names
(CMake registers one CTest test per case from it).
"""

import math
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
import zlib
from pathlib import Path

import case_main
from gltf_files import FLOAT, TRIANGLE, UNSIGNED_BYTE, Gltf, png_1x1_uri, triangle_scene

FILMBACK = None  # set by configure()
SCRATCH = None
TINY = ["--res", "16x16", "--spp", "1", "-q"]
INPUT, USAGE = 1, 2


def animated_scene(times=(0.0, 1.0), values=(0.0, 0.0, -3.0, 1.0, 0.0, -3.0), path="translation",
                   interpolation="LINEAR"):
    """triangle_scene() with one animation channel moving the triangle's node (nodes[0]): key
    times and values as float accessors (SCALAR, then VEC3; VEC4 when there are 4 per key)."""
    g = triangle_scene()
    width = 4 if len(values) == 4 * len(times) and path == "rotation" else 3
    times_view = g.view(struct.pack("<%df" % len(times), *times))
    values_view = g.view(struct.pack("<%df" % len(values), *values))
    g.doc["animations"] = [{
        "channels": [{"sampler": 0, "target": {"node": 0, "path": path}}],
        "samplers": [{"input": g.accessor(times_view, FLOAT, "SCALAR", len(times)),
                      "output": g.accessor(values_view, FLOAT, "VEC%d" % width, len(values) // width),
                      "interpolation": interpolation}]}]
    return g


def png_size(path):
    """Width and height from the IHDR chunk that follows the 8-byte signature (PNG spec §11.2.2)."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "%s is not a PNG" % path
    return struct.unpack(">II", data[16:24])


def png_pixels(path):
    """8-bit RGB pixels, top row first, of a non-interlaced PNG (PNG spec §6.3, §9: the IDAT
    stream is zlib data of scanlines, each led by its filter type)."""
    data = path.read_bytes()
    width, height, depth, colour = struct.unpack(">IIBB", data[16:26])
    assert (depth, colour, data[28]) == (8, 2, 0), "%s: expected 8-bit RGB, not interlaced" % path
    stream, at = b"", 8
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        if kind == b"IDAT":
            stream += data[at + 8:at + 8 + length]
        at += 12 + length
    raw, stride, rows, previous = zlib.decompress(stream), 3 * width, [], bytearray(3 * width)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 3] if i >= 3 else 0
            b, c = previous[i], previous[i - 3] if i >= 3 else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:  # Paeth
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[3 * x:3 * x + 3]) for x in range(width)])
        previous = line
    return rows


def exr_attributes(path):
    """The header attributes of a single-part OpenEXR file, name -> (type, raw value bytes)
    (OpenEXR file layout: magic, version, then name\0 type\0 int32 size value, until an empty
    name)."""
    data = path.read_bytes()
    assert struct.unpack("<I", data[:4])[0] == 20000630, "%s is not an OpenEXR file" % path
    attributes, at = {}, 8
    while data[at] != 0:
        name_end = data.index(b"\0", at)
        type_end = data.index(b"\0", name_end + 1)
        size = struct.unpack("<i", data[type_end + 1:type_end + 5])[0]
        attributes[data[at:name_end].decode()] = (data[name_end + 1:type_end].decode(),
                                                  data[type_end + 5:type_end + 5 + size])
        at = type_end + 5 + size
    return attributes


# A small OpenColorIO config (v2) whose transforms are exact closed forms: the Raw view passes
# scene-linear values through; the Standard view is the sRGB curve; the look doubles.
TINY_OCIO = """ocio_profile_version: 2
roles: {default: linear, scene_linear: linear}
displays:
  sRGB:
    - !<View> {name: Standard, colorspace: srgb}
    - !<View> {name: Raw, colorspace: linear}
looks:
  - !<Look>
    name: Twice
    process_space: linear
    transform: !<MatrixTransform> {matrix: [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1]}
colorspaces:
  - !<ColorSpace> {name: linear, isdata: false}
  - !<ColorSpace>
    name: srgb
    isdata: false
    from_reference: !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055, direction: inverse}
"""


def view_scene(**view):
    """triangle_scene() whose FILMBACK_blender scene extension carries `view` (Blender's view
    settings, under the add-on's names)."""
    g = triangle_scene()
    g.doc["extensionsUsed"] = ["FILMBACK_blender"]
    g.doc["scenes"][0]["extensions"] = {"FILMBACK_blender": view}
    return g


def level(value):
    """An 8-bit level as Blender rounds a display value (its unit_float_to_uchar_clamp)."""
    return int(min(max(value, 0.0), 1.0) * 255 + 0.5)


def srgb(v):
    """IEC 61966-2-1."""
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055


def exr_size(path):
    """Width and height from the dataWindow header attribute (OpenEXR file layout: magic, version,
    then name\\0 type\\0 int32 size value, until an empty name)."""
    data = path.read_bytes()
    assert struct.unpack("<I", data[:4])[0] == 20000630, "%s is not an OpenEXR file" % path
    at = 8
    while data[at] != 0:
        name_end = data.index(b"\0", at)
        type_end = data.index(b"\0", name_end + 1)
        size = struct.unpack("<i", data[type_end + 1:type_end + 5])[0]
        value = data[type_end + 5:type_end + 5 + size]
        if data[at:name_end] == b"dataWindow":
            x0, y0, x1, y1 = struct.unpack("<4i", value)
            return x1 - x0 + 1, y1 - y0 + 1
        at = type_end + 5 + size
    raise AssertionError("%s has no dataWindow" % path)


class CliTest(unittest.TestCase):
    def setUp(self):
        self.dir = Path(tempfile.mkdtemp(prefix=self._testMethodName + "-", dir=SCRATCH))
        self.addCleanup(shutil.rmtree, self.dir, True)
        self.out = self.dir / "out"
        self.out.mkdir()

    def run_cli(self, *args, env_changes=None):
        env = {k: v for k, v in os.environ.items() if k != "FILMBACK_PLUGIN_PATH"}  # only built plugins
        for name, value in (env_changes or {}).items():
            env.pop(name, None) if value is None else env.__setitem__(name, value)
        result = subprocess.run([FILMBACK, *map(str, args)], capture_output=True, text=True, env=env,
                                stdin=subprocess.DEVNULL, timeout=120)
        # Echoed so that CTest's log shows each message as printed (ctest -V, --output-on-failure).
        print("\n$ filmback %s\nexit %d\n%s" % (" ".join(map(str, args)), result.returncode, result.stderr),
              end="", flush=True)
        return result

    def render(self, scene, *options, outputs=("image.exr",), env_changes=None):
        return self.run_cli("render", scene, *[a for o in outputs for a in ("-o", self.out / o)],
                            *options, env_changes=env_changes)

    def scene(self, gltf, name="scene.gltf"):
        return gltf.write(self.dir / name)

    def raw(self, data, name):
        path = self.dir / name
        path.write_bytes(data) if isinstance(data, bytes) else path.write_text(data)
        return path

    def assert_error(self, result, status, prefix, *fragments):
        """Exit `status`, stderr exactly one line starting `filmback: error: ` + prefix and holding
        each fragment, and the output folder still empty."""
        report = "\nexit %d\nstderr:\n%s" % (result.returncode, result.stderr)
        self.assertGreaterEqual(result.returncode, 0, "killed by signal" + report)
        self.assertEqual(result.returncode, status, report)
        lines = result.stderr.splitlines()
        self.assertEqual(len(lines), 1, "expected one message" + report)
        self.assertTrue(lines[0].startswith("filmback: error: " + prefix),
                        "expected the message to start with %r%s" % (prefix, report))
        for fragment in fragments:
            self.assertIn(fragment, lines[0], report)
        self.assertEqual(sorted(os.listdir(self.out)), [], "output folder not empty" + report)

    def assert_input_error(self, scene, json_path, *fragments):
        """A bad scene: exit 1 and `file: JSON path: ...` (no path when json_path is None)."""
        prefix = "%s: %s" % (scene, json_path + ": " if json_path else "")
        self.assert_error(self.render(scene, *TINY), INPUT, prefix, *fragments)

    def assert_usage_error(self, scene, options, prefix, *fragments, outputs=("image.exr",)):
        self.assert_error(self.render(scene, *options, outputs=outputs), USAGE, prefix, *fragments)

    def assert_rendered(self, result, *names):
        report = "\nexit %d\nstderr:\n%s" % (result.returncode, result.stderr)
        self.assertEqual(result.returncode, 0, report)
        self.assertEqual(sorted(os.listdir(self.out)), sorted(names), report)

    # --- files that cannot be read -------------------------------------------------------------

    def test_missing_scene_file(self):
        missing = self.dir / "missing.gltf"
        self.assert_input_error(missing, None, "no such file")

    def test_scene_is_a_folder(self):
        folder = self.dir / "folder.gltf"
        folder.mkdir()
        self.assert_input_error(folder, None, "is a folder, expected a glTF file")

    def test_empty_gltf(self):
        self.assert_input_error(self.raw(b"", "empty.gltf"), None, "the file is empty")

    def test_not_json(self):
        scene = self.raw("solid triangle\n  facet normal 0 0 1\nendsolid\n", "stl.gltf")
        self.assert_input_error(scene, None, "not a valid glTF JSON file")

    def test_malformed_json(self):
        text = triangle_scene().json_text().replace('"nodes": [', '"nodes": [,', 1)
        self.assert_input_error(self.raw(text, "malformed.gltf"), None, "not a valid glTF JSON file")

    def test_truncated_gltf(self):
        text = triangle_scene().json_text()
        self.assert_input_error(self.raw(text[:len(text) // 2], "truncated.gltf"), None,
                                "not a valid glTF JSON file")

    def test_missing_asset_version(self):
        g = triangle_scene()
        del g.doc["asset"]
        self.assert_input_error(self.scene(g), None, "asset")

    def test_truncated_glb(self):
        data = triangle_scene().glb_bytes()
        self.assert_input_error(self.raw(data[:len(data) - 20], "truncated.glb"), None,
                                "not a valid glTF binary file: the header gives a length of %d bytes, "
                                "but the file has %d (truncated?)" % (len(data), len(data) - 20))

    def test_glb_truncated_in_header(self):
        self.assert_input_error(self.raw(triangle_scene().glb_bytes()[:10], "header.glb"), None,
                                "not a valid glTF binary file", "12-byte header")

    def test_glb_bad_magic(self):
        data = b"gLTF" + triangle_scene().glb_bytes()[4:]
        self.assert_input_error(self.raw(data, "magic.glb"), None, "not a valid glTF binary file", "'glTF'")

    def test_glb_version_1(self):
        data = bytearray(triangle_scene().glb_bytes())
        data[4:8] = struct.pack("<I", 1)
        self.assert_input_error(self.raw(bytes(data), "version.glb"), None, "version 1, expected 2")

    def test_gltf_json_named_glb(self):
        self.assert_input_error(self.raw(triangle_scene().json_text(), "json.glb"), None,
                                "not a valid glTF binary file", "'glTF'")

    def test_glb_length_past_end_of_file(self):
        data = bytearray(triangle_scene().glb_bytes())
        data[8:12] = struct.pack("<I", len(data) + 4096)
        self.assert_input_error(self.raw(bytes(data), "length.glb"), None, "not a valid glTF binary file",
                                "length of %d bytes" % (len(data) + 4096))

    def test_glb_json_chunk_past_end(self):
        data = bytearray(triangle_scene().glb_bytes())
        data[12:16] = struct.pack("<I", len(data))
        self.assert_input_error(self.raw(bytes(data), "json_chunk.glb"), None, "not a valid glTF binary file",
                                "chunk 0 at byte 12", "past the end of the file")

    def test_glb_bin_chunk_past_end(self):
        # A BIN chunk length (and buffer byteLength) that counts the chunk's own 8-byte header:
        # the data would end 8 bytes past the end of the file. tinygltf 2.7.0 accepts this and
        # copies those 8 bytes from beyond its input (AddressSanitizer: heap-buffer-overflow).
        g = triangle_scene()
        data = bytearray(g.glb_bytes(buffer_length=len(g.bin) + 8))
        json_length = struct.unpack("<I", data[12:16])[0]
        bin_header = 20 + json_length
        bin_length = struct.unpack("<I", data[bin_header:bin_header + 4])[0]
        data[bin_header:bin_header + 4] = struct.pack("<I", bin_length + 8)
        self.assert_input_error(self.raw(bytes(data), "bin_chunk.glb"), None, "not a valid glTF binary file",
                                "chunk 1 at byte %d" % bin_header, "past the end of the file")

    def test_missing_external_buffer(self):
        text = triangle_scene().json_text(buffer_uri="missing.bin")
        self.assert_input_error(self.raw(text, "external.gltf"), None, "missing.bin")

    def test_external_buffer_beside_the_scene_loads(self):
        g = triangle_scene()
        self.raw(bytes(g.bin), "triangle.bin")
        self.assert_rendered(self.render(self.raw(g.json_text(buffer_uri="triangle.bin"), "external.gltf"),
                                         *TINY), "image.exr")

    def test_buffer_outside_the_scene_folder_is_refused(self):
        g = triangle_scene()
        self.raw(bytes(g.bin), "outside.bin")
        (self.dir / "shots").mkdir()
        # '..' escapes, also percent-encoded (tinygltf decodes URIs before it opens them)
        for uri in ("../outside.bin", "./../outside.bin", "%2e%2e/outside.bin", "sub/%2E%2E/%2e%2e/outside.bin"):
            scene = self.raw(g.json_text(buffer_uri=uri), "shots/escape.gltf")
            self.assert_input_error(scene, "buffers[0].uri", "'%s' refers outside the scene's folder" % uri)
        for uri in (str(self.dir / "outside.bin"), "%2F" + str(self.dir / "outside.bin")[1:]):
            scene = self.raw(g.json_text(buffer_uri=uri), "shots/absolute.gltf")
            self.assert_input_error(scene, "buffers[0].uri", "'%s' is an absolute path" % uri)

    def test_uri_with_a_scheme_is_refused(self):
        g = triangle_scene()
        self.raw(bytes(g.bin), "outside.bin")
        for uri, scheme in (("file://" + str(self.dir / "outside.bin"), "file:"),
                            ("http://127.0.0.1:9/triangle.bin", "http:"),
                            ("https://example.org/triangle.bin", "https:"),
                            ("HTTP%3A//127.0.0.1/triangle.bin", "HTTP:")):
            scene = self.raw(g.json_text(buffer_uri=uri), "scheme.gltf")
            self.assert_input_error(scene, "buffers[0].uri", "'%s' is a '%s' URI" % (uri, scheme),
                                    "never opens a network connection")
        g.doc["images"] = [{"uri": "ftp://127.0.0.1/texture.png"}]
        scene = self.raw(g.json_text(), "image_scheme.gltf")
        self.assert_input_error(scene, "images[0].uri", "is a 'ftp:' URI")

    def test_buffer_symlink_out_of_the_folder_is_refused(self):
        g = triangle_scene()
        self.raw(bytes(g.bin), "outside.bin")
        (self.dir / "shots").mkdir()
        (self.dir / "shots" / "link.bin").symlink_to(self.dir / "outside.bin")
        scene = self.raw(g.json_text(buffer_uri="link.bin"), "shots/link.gltf")
        self.assert_input_error(scene, None, "refers outside the scene's folder")

    def test_buffer_that_is_a_pipe_does_not_block(self):
        os.mkfifo(self.dir / "pipe.bin")
        scene = self.raw(triangle_scene().json_text(buffer_uri="pipe.bin"), "pipe.gltf")
        self.assert_input_error(scene, None, "is not a regular file")

    def test_deeply_nested_json_is_refused_with_line_and_column(self):
        deep = '{"asset": {"version": "2.0"},\n "extras": ' + "[" * 20000 + "]" * 20000 + "}"
        scene = self.raw(deep, "deep.gltf")
        self.assert_error(self.render(scene, *TINY), INPUT, "%s:2:139: " % scene, "nested more than 128")

    def test_deeply_nested_json_in_glb_is_refused(self):
        g = triangle_scene()
        g.doc["asset"]["extras"] = json.loads("[" * 200 + "]" * 200)
        scene = self.raw(g.glb_bytes(), "deep.glb")
        self.assert_error(self.render(scene, *TINY), INPUT, "%s: JSON chunk, byte " % scene,
                          "nested more than 128")

    # --- data that points outside itself ------------------------------------------------------

    def test_accessor_count_past_buffer_view(self):
        g = triangle_scene()
        g.doc["accessors"][0]["count"] = 4  # 4 VEC3 floats: 48 bytes in a 36-byte bufferView
        self.assert_input_error(self.scene(g), "meshes[0].primitives[0].attributes.POSITION (accessors[0])",
                                "bufferViews[0]", "36 bytes")

    def test_accessor_count_overflows(self):
        g = triangle_scene()
        g.doc["accessors"][0]["count"] = 2**62  # count * 12 bytes wraps around in 64 bits
        self.assert_input_error(self.scene(g), "meshes[0].primitives[0].attributes.POSITION (accessors[0])",
                                "bufferViews[0]")

    def test_accessor_count_past_buffer_view_in_glb(self):
        g = triangle_scene()
        g.doc["accessors"][1]["count"] = 4
        self.assert_input_error(self.scene(g, "scene.glb"), "meshes[0].primitives[0].indices (accessors[1])",
                                "bufferViews[1]", "12 bytes")

    def test_buffer_view_past_buffer(self):
        g = triangle_scene()
        g.doc["bufferViews"][1]["byteOffset"] = 40  # 12 bytes from 40 in a 48-byte buffer
        self.assert_input_error(self.scene(g), "bufferViews[1]", "40+12", "buffers[0] (48 bytes)")

    def test_index_past_vertex_count(self):
        g = Gltf()
        position = g.positions(TRIANGLE)
        g.mesh([{"attributes": {"POSITION": position}, "indices": g.indices([0, 1, 3])}])
        g.node(mesh=0, translation=[0.0, 0.0, -3.0])
        self.assert_input_error(self.scene(g), "meshes[0].primitives[0].indices (accessors[1])",
                                "index 2 is 3", "3 vertices")

    def test_accessor_index_out_of_range(self):
        g = triangle_scene()
        g.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7
        self.assert_input_error(self.scene(g), "meshes[0].primitives[0].attributes.POSITION",
                                "accessor index 7", "2 accessors")

    def test_position_accessor_of_wrong_type(self):
        g = triangle_scene()
        g.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 1  # the SCALAR indices
        self.assert_input_error(self.scene(g), "meshes[0].primitives[0].attributes.POSITION (accessors[1])",
                                "type SCALAR, expected VEC3")

    def test_indices_of_float_type(self):
        g = triangle_scene()
        g.doc["accessors"][1]["componentType"] = FLOAT
        self.assert_input_error(self.scene(g), "meshes[0].primitives[0].indices (accessors[1])",
                                "componentType 5126, expected 5121 or 5123 or 5125")

    def test_mesh_index_out_of_range(self):
        g = triangle_scene()
        g.doc["nodes"][0]["mesh"] = 5
        self.assert_input_error(self.scene(g), "nodes[0].mesh", "mesh index 5", "1 meshes")

    def test_material_index_out_of_range(self):
        # The first primitive has no material, so the importer adds its default one; index 0 must
        # still be out of range for a file without materials.
        g = triangle_scene()
        g.doc["meshes"][0]["primitives"].append(dict(g.doc["meshes"][0]["primitives"][0], material=0))
        self.assert_input_error(self.scene(g), "meshes[0].primitives[1].material", "material index 0",
                                "0 materials")

    def test_node_index_out_of_range(self):
        g = triangle_scene()
        g.doc["nodes"][0]["children"] = [9]
        self.assert_input_error(self.scene(g), "nodes[0].children[0]", "node index 9", "2 nodes")

    def test_scene_index_out_of_range(self):
        g = triangle_scene()
        g.doc["scene"] = 3
        self.assert_input_error(self.scene(g), "scene", "scene index 3", "1 scenes")

    def test_node_cycle(self):
        g = triangle_scene()
        a = g.node(name="a", children=[])
        b = g.node(root=False, name="b", children=[a])
        g.doc["nodes"][a]["children"] = [b]
        self.assert_input_error(self.scene(g), "nodes[%d].children[0]" % b,
                                "nodes[%d] is reached a second time" % a)

    def test_node_with_two_parents(self):
        g = triangle_scene()
        child = g.node(root=False, name="child")
        g.node(name="parent1", children=[child])
        second = g.node(name="parent2", children=[child])
        self.assert_input_error(self.scene(g), "nodes[%d].children[0]" % second,
                                "nodes[%d] is reached a second time" % child)

    def test_node_cycle_without_scenes(self):
        g = triangle_scene()
        del g.doc["scenes"], g.doc["scene"]
        g.doc["nodes"][0]["children"] = [1]
        g.doc["nodes"][1]["children"] = [0]
        self.assert_input_error(self.scene(g), "nodes[0]", "cycle")

    def test_nan_position(self):
        g = Gltf()
        g.mesh([{"attributes": {"POSITION": g.positions([TRIANGLE[0], (0.0, math.nan, 0.0), TRIANGLE[2]])}}])
        g.node(mesh=0, translation=[0.0, 0.0, -3.0])
        self.assert_input_error(self.scene(g, "nan.glb"),
                                "meshes[0].primitives[0].attributes.POSITION (accessors[0])",
                                "element 1", "finite")

    def test_unsupported_required_extension(self):
        g = triangle_scene()
        g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_draco_mesh_compression"]
        self.assert_input_error(self.scene(g), "extensionsRequired[0]", "KHR_draco_mesh_compression",
                                "not supported")

    def test_camera_shape_beyond_float_is_refused(self):
        g = triangle_scene()
        g.doc["cameras"][0]["perspective"]["aspectRatio"] = 1e308  # Embree would abort on its rays
        self.assert_input_error(self.scene(g), "cameras[0].perspective.aspectRatio", "1e+308",
                                "expected 1e-4 to 1e4")

    def test_world_transform_overflow_is_refused(self):
        g = triangle_scene()
        g.doc["nodes"][0]["scale"] = [1e200, 1e200, 1e200]
        parent = g.node(scale=[1e200, 1e200, 1e200], children=[0])
        g.doc["scenes"][0]["nodes"] = [parent, 1]
        self.assert_input_error(self.scene(g), "nodes[0]", "overflows")

    def test_light_index_must_be_a_whole_number_in_range(self):
        g = triangle_scene()
        g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
        g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "point"}]}}
        for index in (0.7, 1e20, -1):
            g.doc["nodes"][1]["extensions"] = {"KHR_lights_punctual": {"light": index}}
            self.assert_input_error(self.scene(g), "nodes[1].extensions.KHR_lights_punctual.light",
                                    "expected a whole number below 1")

    def test_base_colour_above_one_is_refused(self):
        g = triangle_scene()
        g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorFactor": [1.5, 0.5, 0.5, 1]}}]
        g.doc["meshes"][0]["primitives"][0]["material"] = 0
        self.assert_input_error(self.scene(g), "materials[0].pbrMetallicRoughness.baseColorFactor",
                                "expected components in [0, 1]")

    def test_info_reports_bad_input_too(self):
        g = triangle_scene()
        g.doc["accessors"][0]["count"] = 4
        scene = self.scene(g)
        self.assert_error(self.run_cli("info", scene), INPUT,
                          "%s: meshes[0].primitives[0].attributes.POSITION (accessors[0]): " % scene)

    # --- what was typed ------------------------------------------------------------------------

    def test_option_value_out_of_range(self):
        scene = self.scene(triangle_scene())
        self.assert_usage_error(scene, ["--res", "16x16", "--spp", "0", "-q"], "--spp: ", "0",
                                "1 to 1000000")

    def test_unknown_option(self):
        scene = self.scene(triangle_scene())
        self.assert_usage_error(scene, TINY + ["--brightness", "2"], "", "--brightness")

    def test_unknown_scene_extension(self):
        scene = self.raw("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "scene.obj")
        self.assert_usage_error(scene, TINY, "'%s': " % scene, "'.obj'", "expected .gltf, .glb or .pov")

    def test_unknown_filter(self):
        scene = self.scene(triangle_scene())
        self.assert_usage_error(scene, TINY + ["--filter", "kaiser"], "", "filter", "'kaiser'")

    def test_unknown_reconstruction(self):
        scene = self.scene(triangle_scene())
        self.assert_usage_error(scene, TINY + ["--reconstruction", "gather"], "--reconstruction: ",
                                "gather", "importance", "splat")

    def test_splat_reconstruction_renders(self):
        result = self.render(self.scene(triangle_scene()), *TINY, "--reconstruction", "splat",
                             "--filter", "lanczos")
        self.assert_rendered(result, "image.exr")

    def test_adaptive_sampling_refuses_splatting(self):
        # Checkpoints of adaptive renders hold the convergence map (tests/unit/interrupt_test.cpp);
        # splatting is still refused: a splatted sample reaches several pixels (docs/sampling.md).
        scene = self.scene(triangle_scene())
        adaptive = TINY + ["--adaptive-threshold", "0.01"]
        self.assert_usage_error(scene, adaptive + ["--reconstruction", "splat"],
                                "--adaptive-threshold with --reconstruction splat: ",
                                "--reconstruction importance")

    def test_unknown_integrator(self):
        scene = self.scene(triangle_scene())
        self.assert_usage_error(scene, TINY + ["--integrator", "bdpt"], "", "integrator", "'bdpt'")

    def test_unknown_plugin_parameter(self):
        scene = self.scene(triangle_scene())
        self.assert_usage_error(scene, TINY + ["--filter", "gaussian:width=2"], "", "'width'",
                                "radius", "sigma")

    def test_parameter_out_of_range(self):
        scene = self.scene(triangle_scene())
        self.assert_usage_error(scene, TINY + ["--filter", "gaussian:sigma=-1"], "", "sigma", "'-1'",
                                "expected")

    def test_parameter_not_a_number(self):
        scene = self.scene(triangle_scene())
        self.assert_usage_error(scene, TINY + ["--integrator", "path:max_depth=deep"], "", "max_depth",
                                "'deep'", "expected a whole number")

    def test_bad_resolution(self):
        scene = self.scene(triangle_scene())
        for res in ["0x10", "10", "10x", "axb", "x10", "16x16x16", "99999x99999", "32768x32768"]:
            with self.subTest(res=res):
                self.assert_usage_error(scene, ["--res", res, "--spp", "1", "-q"], "--res '%s': " % res,
                                        "expected")

    def test_unknown_output_extension(self):
        scene = self.scene(triangle_scene())
        self.assert_usage_error(scene, TINY, "output '%s': " % (self.out / "image.tif"), "'.tif'",
                                "expected .exr, .png, .jpg or .jpeg", outputs=("image.exr", "image.tif"))

    def test_output_folder_missing(self):
        scene = self.scene(triangle_scene())
        self.assert_usage_error(scene, TINY, "output '%s': " % (self.out / "nowhere" / "image.exr"),
                                "does not exist", outputs=("image.exr", "nowhere/image.exr"))

    def test_same_output_twice_keeps_the_existing_file(self):
        scene = self.scene(triangle_scene())
        (self.out / "keep.exr").write_text("the previous render")
        result = self.run_cli("render", scene, *TINY, "-o", self.out / "keep.exr", "-o",
                              self.out / "." / "keep.exr")
        self.assertEqual(result.returncode, USAGE, result.stderr)
        self.assertIn("the same file as output", result.stderr)
        self.assertEqual((self.out / "keep.exr").read_text(), "the previous render")
        self.assertEqual(sorted(os.listdir(self.out)), ["keep.exr"])

    # --- convert --------------------------------------------------------------------------------

    def test_convert_then_render_gives_the_same_image(self):
        """Everything the default scene holds survives the writer: the two renders agree to 1e-6."""
        original = Path(__file__).resolve().parents[2] / "scenes" / "default" / "default.gltf"
        converted = self.dir / "converted.gltf"
        result = self.run_cli("convert", original, converted)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(sorted(os.listdir(self.dir)), ["converted.gltf", "out"])  # no temporary
        options = ["--res", "48x32", "--spp", "4", "-q"]
        for scene, name in ((original, "a.exr"), (converted, "b.exr")):
            result = self.render(scene, *options, outputs=(name,))
            self.assertEqual(result.returncode, 0, result.stderr)
        diff = subprocess.run(["oiiotool", self.out / "a.exr", self.out / "b.exr", "--diff",
                               "--fail", "1e-6"], capture_output=True, text=True)
        self.assertEqual(diff.returncode, 0, diff.stdout + diff.stderr)

    def test_convert_writes_only_gltf(self):
        scene = self.scene(triangle_scene())
        result = self.run_cli("convert", scene, self.out / "scene.obj")
        self.assert_error(result, USAGE, "output '%s': " % (self.out / "scene.obj"),
                          "expected a .gltf file name")

    def test_output_is_a_folder(self):
        scene = self.scene(triangle_scene())
        (self.out / "b.png").mkdir()
        result = self.render(scene, *TINY, outputs=("a.exr", "b.png"))
        self.assertEqual(result.returncode, USAGE, result.stderr)
        self.assertEqual(result.stderr, "filmback: error: output '%s': is a folder, expected an image "
                         "file name\n" % (self.out / "b.png"))
        self.assertEqual(sorted(os.listdir(self.out)), ["b.png"])  # no a.exr, no temporary file

    def test_unknown_camera(self):
        scene = self.scene(triangle_scene())
        self.assert_usage_error(scene, TINY + ["--camera", "Camera.001"], "--camera 'Camera.001': ",
                                "it has: shot")

    # --- animation (glTF 2.0 §3.11) --------------------------------------------------------------

    def test_animation_times_must_increase(self):
        g = animated_scene(times=[0.0, 1.0, 1.0], values=[0.0] * 9)
        self.assert_input_error(self.scene(g), "animations[0].samplers[0].input (accessors[2])",
                                "key 2 at 1 s does not follow key 1 at 1 s", "strictly increasing")

    def test_animation_time_must_be_finite(self):
        g = animated_scene(times=[0.0, math.nan], values=[0.0] * 6)
        self.assert_input_error(self.scene(g), "animations[0].samplers[0].input (accessors[2])",
                                "element 1 is not a finite number")

    def test_animation_values_must_match_the_keys(self):
        g = animated_scene(times=[0.0, 1.0], values=[0.0] * 9)
        self.assert_input_error(self.scene(g), "animations[0].samplers[0].output (accessors[3])",
                                "3 values for 2 keys, expected 2")

    def test_cubic_spline_needs_tangents(self):
        g = animated_scene(times=[0.0, 1.0], values=[0.0] * 6, interpolation="CUBICSPLINE")
        self.assert_input_error(self.scene(g), "animations[0].samplers[0].output (accessors[3])",
                                "2 values for 2 keys, expected 6", "in-tangent, value, out-tangent")

    def test_unknown_interpolation(self):
        g = animated_scene(interpolation="SMOOTH")
        self.assert_input_error(self.scene(g), "animations[0].samplers[0].interpolation",
                                "'SMOOTH', expected LINEAR, STEP or CUBICSPLINE")

    def test_animation_sampler_index_out_of_range(self):
        g = animated_scene()
        g.doc["animations"][0]["channels"][0]["sampler"] = 3
        self.assert_input_error(self.scene(g), "animations[0].channels[0].sampler", "sampler index 3",
                                "1 samplers")

    def test_animation_target_node_out_of_range(self):
        g = animated_scene()
        g.doc["animations"][0]["channels"][0]["target"]["node"] = 9
        self.assert_input_error(self.scene(g), "animations[0].channels[0].target.node", "node index 9",
                                "2 nodes")

    def test_animation_cannot_target_a_matrix_node(self):
        g = animated_scene()
        del g.doc["nodes"][0]["translation"]
        g.doc["nodes"][0]["matrix"] = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1]
        self.assert_input_error(self.scene(g), "animations[0].channels[0].target.node",
                                "nodes[0] has a matrix")

    def test_unknown_animated_property(self):
        g = animated_scene()
        g.doc["animations"][0]["channels"][0]["target"]["path"] = "colour"
        self.assert_input_error(self.scene(g), "animations[0].channels[0].target.path",
                                "'colour' is not an animated property")

    def test_rotation_values_must_be_vec4(self):
        g = animated_scene(path="rotation")
        self.assert_input_error(self.scene(g), "animations[0].samplers[0].output (accessors[3])",
                                "type VEC3, expected VEC4")

    def test_rotation_must_not_be_zero(self):
        g = animated_scene(path="rotation", values=[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0])
        self.assert_input_error(self.scene(g), "animations[0].samplers[0].output (accessors[3])",
                                "key 1 is not a rotation")

    def test_integer_rotations_must_be_normalized(self):
        g = animated_scene(path="rotation", values=[0.0, 0.0, 0.0, 1.0] * 2)
        output = g.doc["animations"][0]["samplers"][0]["output"]
        view = g.view(struct.pack("<8B", 0, 0, 0, 255, 0, 0, 0, 255))
        g.doc["accessors"][output].update(bufferView=view, componentType=UNSIGNED_BYTE)
        self.assert_input_error(self.scene(g), "animations[0].samplers[0].output (accessors[3])",
                                "must be normalized")
        g.doc["accessors"][output]["normalized"] = True
        self.assert_rendered(self.render(self.scene(g, "normalized.gltf"), *TINY), "image.exr")

    def test_weights_and_repeated_channels_warn(self):
        g = animated_scene()
        channels = g.doc["animations"][0]["channels"]
        channels.append({"sampler": 0, "target": {"node": 0, "path": "weights"}})
        channels.append({"sampler": 0, "target": {"node": 0, "path": "translation"}})
        scene = self.scene(g)
        result = self.render(scene, *TINY)
        self.assert_rendered(result, "image.exr")
        warnings = [line for line in result.stderr.splitlines() if line.startswith("warning: ")]
        self.assertEqual(len(warnings), 2, result.stderr)
        self.assertTrue(warnings[0].startswith(
            "warning: %s: animations[0].channels[1].target.node: nodes[0] has no morph targets" % scene),
            result.stderr)
        self.assertTrue(warnings[1].startswith("warning: %s: animations[0].channels[2]: " % scene), result.stderr)
        self.assertIn("already animated by animations[0].channels[0]", warnings[1])

    def test_frame_and_shutter_decide_whether_time_is_sampled(self):
        scene = self.scene(animated_scene())  # the triangle moves from t = 0 to t = 1 s
        cases = [(["--shutter", "0,0.5"], "frame 0 at 24 fps (t = 0 s), shutter open 0.5 s (box): "
                  "time samples for 1 moving instance"),
                 (["--shutter", "0,0.5", "--frame", "36", "--fps", "24"], "frame 36 at 24 fps (t = 1.5 s), "
                  "shutter open 0.5 s (box), nothing moves in it: no time samples"),
                 (["--shutter-curve", "trapezoid:ramp=0.1", "--shutter", "-0.1,0.1", "--frame", "12"],
                  "shutter open 0.2 s (trapezoid ramp 0.1): time samples"),
                 (["--shutter", "0,0.5", "--rolling-shutter", "0.25"], "shutter open 0.5 s (box, rolling "
                  "top to bottom, each row 0.25 of it): time samples for 1 moving instance"),
                 (["--shutter", "0,0.5", "--frame", "36", "--rolling-shutter", "0"], "shutter open 0.5 s "
                  "(box, rolling top to bottom, each row 0 of it), nothing moves in it: no time samples"),
                 ([], "frame 0 at 24 fps (t = 0 s), shutter closed: no time samples")]
        for options, plan in cases:
            with self.subTest(options=options):
                result = self.render(scene, "--res", "16x16", "--spp", "1", *options)
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertIn(plan, result.stdout)

    def test_bad_rolling_shutter(self):
        self.assert_usage_error(self.scene(animated_scene()), TINY + ["--shutter", "0,1", "--rolling-shutter", "1.5"],
                                "--rolling-shutter '1.5': ", "expected a number in [0, 1]")
        self.assert_usage_error(self.scene(animated_scene()), TINY + ["--rolling-shutter", "0.1"],
                                "--rolling-shutter: the shutter is closed", "give --shutter OPEN,CLOSE")

    def test_bad_shutter_curve(self):
        self.assert_usage_error(self.scene(animated_scene()), TINY + ["--shutter-curve", "trapezoid:ramp=0.9"],
                                "--shutter-curve 'trapezoid:ramp=0.9': ", "expected a number in [0, 0.5]")
        self.assert_usage_error(self.scene(animated_scene()), TINY + ["--shutter-curve", "table:values=[0,0]"],
                                "--shutter-curve 'table:values=[0,0]': ", "not all zero")

    # --- where a value came from: the scene (exit 1, naming the file) or an option (exit 2) ------

    def camera_scene(self, ours=None, extras=None, shot=None):
        """triangle_scene() whose camera carries `ours` (FILMBACK_blender) and `extras`, and whose
        scene extension carries `shot`."""
        g = triangle_scene()
        g.doc["extensionsUsed"] = ["FILMBACK_blender"]
        if ours is not None:
            g.doc["cameras"][0]["extensions"] = {"FILMBACK_blender": ours}
        if extras is not None:
            g.doc["cameras"][0]["extras"] = extras
        if shot is not None:
            g.doc["scenes"][0]["extensions"] = {"FILMBACK_blender": shot}
        return self.scene(g)

    def test_scene_filter_error_is_bad_input_naming_the_scene(self):
        # Cycles' filter widths run from 0.01 to 10 px: beyond is the scene's error, exit 1, while
        # a bad --filter is the user's, exit 2, and --filter replaces the scene's filter.
        scene = self.camera_scene(shot={"filter_type": "GAUSSIAN", "filter_width_px": 20})
        self.assert_input_error(scene, "scenes[0].extensions.FILMBACK_blender.filter_width_px",
                                "expected a number in [0.01, 10]")
        scene = self.camera_scene(shot={"filter_type": "GAUSSIAN", "filter_width_px": 0.01})
        self.assert_usage_error(scene, TINY + ["--filter", "gaussian:sigma=0"],
                                "--filter 'gaussian:sigma=0': ", "sigma")
        result = self.render(scene, *TINY[:-1])
        self.assert_rendered(result, "image.exr")
        self.assertIn("filter gaussian:radius=0.015,sigma=0.0025 (importance)", result.stdout)

    def test_bad_fstop_names_where_it_came_from(self):
        scene = self.camera_scene(ours={"fstop": -1})
        self.assert_input_error(scene, "cameras[0].extensions.FILMBACK_blender.fstop",
                                "-1, expected 0 (a pinhole) or an f-number in (0, 1e6]")
        scene = self.camera_scene()
        for fstop in ["-1", "wide", "nan"]:
            with self.subTest(fstop=fstop):
                self.assert_usage_error(scene, TINY + ["--fstop", fstop], "--fstop '%s': " % fstop,
                                        "expected 0 (a pinhole) or an f-number in (0, 1e6]")

    def test_focus_inside_the_focal_length_names_both_origins(self):
        # yfov 0.8 on a square image: f = 18 mm / tan(0.4) = 42.574 mm, from yfov.
        scene = self.camera_scene(ours={"fstop": 2, "focus_distance_m": 0.04})
        self.assert_input_error(scene, "cameras[0].extensions.FILMBACK_blender.focus_distance_m",
                                "not beyond the focal length 42.574 mm (focal length from %s: "
                                "cameras[0].perspective.yfov (under the sensor and its fit))" % scene)
        scene = self.camera_scene(ours={"fstop": 2})
        self.assert_usage_error(scene, TINY + ["--focus-distance", "0.01"], "--focus-distance: ",
                                "not beyond the focal length 42.574 mm")

    def test_info_prints_each_values_origin_and_the_ignored_extras(self):
        # Bug 1 of issue 15: custom properties named like ours gave depth of field Blender had off.
        scene = self.camera_scene(ours={"focal_length_mm": 50, "sensor_fit": "auto"},
                                  extras={"fstop": 2.8})
        result = self.run_cli("info", scene, "--camera", "shot")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("      focal_length_mm: %s: cameras[0].extensions.FILMBACK_blender.focal_length_mm\n"
                      % scene, result.stdout)
        self.assertIn("      fstop: default (FILMBACK_blender names none: depth of field off, a pinhole)",
                      result.stdout)
        self.assertIn("pinhole (no aperture", result.stdout)
        self.assertIn("%s: cameras[0].extras: fstop ignored: FILMBACK_blender describes the camera"
                      % scene, result.stderr)

    def test_info_prints_the_shot_plan_with_each_plugin_values_origin(self):
        # The plan info prints is the one render uses: the lens values reach thinlens by name,
        # each with the JSON path it came from; the shot's filter arrives as typed numbers.
        scene = self.camera_scene(ours={"fstop": 2, "focus_distance_m": 3},
                                  shot={"filter_type": "BOX", "filter_width_px": 1.25})
        result = self.run_cli("info", scene)
        self.assertEqual(result.returncode, 0, result.stderr)
        ours = "%s: cameras[0].extensions.FILMBACK_blender." % scene
        self.assertIn("  camera model thinlens  (%sfstop)\n" % ours, result.stdout)
        self.assertIn("    fstop = 2  from %sfstop\n" % ours, result.stdout)
        self.assertIn("    focus_distance_m = 3  from %sfocus_distance_m\n" % ours, result.stdout)
        self.assertIn("  filter box  (%s: scenes[0].extensions.FILMBACK_blender" % scene,
                      result.stdout)
        self.assertIn("    radius = 0.625  from ", result.stdout)
        self.assertRegex(result.stdout, r"  integrator path  \(default")
        render = self.render(scene, *TINY[:-1])
        self.assertIn("through thinlens (f/2 focused at 3 m", render.stdout)
        self.assertIn("filter box:radius=0.625 (importance)", render.stdout)

    def test_info_with_a_camera_model_prints_what_the_plugin_derives(self):
        # A thick biconvex singlet (R = +-100 mm, 5 mm of glass n = 1.5, stop in front):
        # 1/f = (n-1) (1/R1 - 1/R2 + (n-1) t / (n R1 R2)) gives f = 100.840 mm, and the back focal
        # distance f (1 - (n-1) t / (n R1)) = 99.1597 mm, which the realistic camera reports
        # through fb_camera_api::describe.
        scene = self.camera_scene()
        lens = str(self.dir / "singlet.dat")
        with open(lens, "w") as f:
            f.write("0 1 0 20\n100 5 1.5 20\n-100 0 1 20\n")
        result = self.run_cli("info", scene, "--camera-model", "realistic:lens=" + lens)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("plan (filmback render --camera-model realistic:lens=", result.stdout)
        self.assertIn("  camera model realistic says:\n", result.stdout)
        self.assertIn("    effective focal length: 100.84 mm\n", result.stdout)
        self.assertIn("    back focal distance: 99.1597 mm", result.stdout)
        # The user named the plugin: its refusal is an error, naming the lens file's line.
        with open(lens, "w") as f:
            f.write("0 1 0 20\n100 five 1.5 20\n")
        bad = self.run_cli("info", scene, "--camera-model", "realistic:lens=" + lens)
        self.assertEqual(bad.returncode, 1, bad.stdout + bad.stderr)
        self.assertIn(lens + ":2:", bad.stderr)

    # --- what works ----------------------------------------------------------------------------

    def test_unsupported_features_warn_once_each(self):
        g = triangle_scene()
        position = 0
        g.doc["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": position}]
        g.doc["meshes"][0]["weights"] = [0.5]
        g.doc["meshes"][0]["primitives"] += [{"attributes": {"POSITION": position}, "mode": 1},
                                             {"attributes": {"POSITION": position}, "mode": 0}]
        g.doc["materials"] = [{"pbrMetallicRoughness": {"metallicFactor": 0.0},
                               "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0}}}]
        g.doc["meshes"][0]["primitives"][0]["material"] = 0
        g.doc["extensionsUsed"] = ["KHR_materials_clearcoat"]
        scene = self.scene(g)
        result = self.render(scene, *TINY)
        self.assert_rendered(result, "image.exr")
        expected = ["extensionsUsed[0]",
                    "meshes[0].primitives[1].mode", "meshes[0].primitives[2].mode"]
        warnings = [line for line in result.stderr.splitlines() if line.startswith("warning: ")]
        self.assertEqual(len(warnings), len(expected), result.stderr)
        for path in expected:
            with self.subTest(path=path):
                found = [w for w in warnings if w.startswith("warning: %s: %s: " % (scene, path))]
                self.assertEqual(len(found), 1, "one warning for %s expected:\n%s" % (path, result.stderr))

    def test_texture_without_its_texture_coordinates_is_an_error(self):
        g = triangle_scene()
        g.doc["images"] = [{"uri": png_1x1_uri()}]
        g.doc["textures"] = [{"source": 0}]
        g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        g.doc["meshes"][0]["primitives"][0]["material"] = 0
        self.assert_input_error(self.scene(g), "meshes[0].primitives[0].attributes",
                                "reads TEXCOORD_0, which the primitive does not have")

    def test_writes_exr_and_png(self):
        scene = self.scene(triangle_scene(), "scene.glb")
        result = self.render(scene, "--res", "16x12", "--spp", "1", "-q", outputs=("a.exr", "b.png"))
        self.assert_rendered(result, "a.exr", "b.png")
        self.assertEqual(exr_size(self.out / "a.exr"), (16, 12))
        self.assertEqual(png_size(self.out / "b.png"), (16, 12))
        self.assertEqual(result.stderr, "")

    def test_replaces_existing_output(self):
        scene = self.scene(triangle_scene())
        (self.out / "image.png").write_bytes(b"an older file")
        self.assert_rendered(self.render(scene, *TINY, outputs=("image.png",)), "image.png")
        self.assertEqual(png_size(self.out / "image.png"), (16, 16))
        self.assert_rendered(self.render(scene, "--res", "8x8", "--spp", "1", "-q", outputs=("image.png",)),
                             "image.png")
        self.assertEqual(png_size(self.out / "image.png"), (8, 8))

    # --- 8-bit outputs: the view transform (docs/cli.md, "Colour") -----------------------------
    # The scene is the triangle in a uniform background of 0.18 W/sr/m^2: the top-left pixel sees
    # only the background, so its 8-bit value is the transform of 0.18 exactly.

    def grey_level(self, scene, *options, env_changes=None, name="image.png"):
        result = self.render(scene, "--background", "0.18", *TINY, *options, outputs=(name,),
                             env_changes=env_changes)
        self.assert_rendered(result, name)
        return png_pixels(self.out / name)[0][0][0], result

    def tiny_ocio(self):
        return self.raw(TINY_OCIO, "tiny.ocio")

    def test_view_options_replace_the_files(self):
        scene = self.scene(view_scene(view_transform="Raw", look="Twice", exposure_stops=2.0,
                                      dither_intensity=0))
        config = self.tiny_ocio()
        # The file's: 0.18 x 2^2 x 2 (the look), through the Raw view.
        self.assertEqual(self.grey_level(scene, "--ocio-config", config)[0], level(0.18 * 4 * 2))
        # Each option replaces one of them.
        self.assertEqual(self.grey_level(scene, "--ocio-config", config, "--look", "None")[0],
                         level(0.18 * 4))
        self.assertEqual(self.grey_level(scene, "--ocio-config", config, "--exposure", "-1")[0],
                         level(0.18 / 2 * 2))
        self.assertEqual(self.grey_level(scene, "--ocio-config", config, "--view-transform",
                                         "Standard", "--exposure", "0", "--look", "None")[0],
                         level(srgb(0.18)))
        self.assertEqual(self.grey_level(scene, "--ocio-config", config, "--look", "None",
                                         "--exposure", "0", "--gamma", "2")[0], level(0.18 ** 0.5))
        # An empty view: the plain sRGB curve, with the file's exposure; its look cannot apply.
        value, result = self.grey_level(scene, "--ocio-config", config, "--view-transform", "")
        self.assertEqual(value, level(srgb(0.18 * 4)))
        self.assertIn("look 'Twice' without a view transform: not applied", result.stderr)
        # $OCIO is used when no --ocio-config is given.
        self.assertEqual(self.grey_level(scene, "--look", "None",
                                         env_changes={"OCIO": str(config)})[0], level(0.18 * 4))

    def test_dither_is_blenders_noise_of_about_a_level(self):
        scene = self.scene(view_scene(view_transform="Raw", dither_intensity=1.0))
        result = self.render(scene, "--background", "0.18", "--res", "64x64", "--spp", "1", "-q",
                             "--ocio-config", self.tiny_ocio(), outputs=("image.png",))
        self.assert_rendered(result, "image.png")
        values = {p[0] for row in png_pixels(self.out / "image.png")[:3] for p in row}  # background
        # 0.18 is 45.9 levels; Blender adds 0.0033 x [-0.5, 1.5) (-0.4 to 1.3 levels) before
        # rounding, so 45 to 47.
        self.assertTrue(values <= {45, 46, 47} and len(values) >= 2, values)

    def test_missing_config_renders_the_srgb_curve_with_a_warning(self):
        scene = self.scene(view_scene(view_transform="Filmic", look="Medium High Contrast",
                                      dither_intensity=0))
        value, result = self.grey_level(scene, env_changes={"OCIO": None,
                                                            "BLENDER_SYSTEM_DATAFILES": "/nonexistent"})
        self.assertEqual(value, level(srgb(0.18)))
        self.assertIn("warning: no OpenColorIO config", result.stderr)
        self.assertIn("/nonexistent/colormanagement/config.ocio", result.stderr)
        self.assertIn("without view transform 'Filmic' and look 'Medium High Contrast'", result.stderr)

    def test_config_that_cannot_be_loaded_is_an_error_naming_it(self):
        scene = self.scene(view_scene(view_transform="Filmic"))
        bad = self.raw("ocio_profile_version: 2\ndisplays: [not, a, map\n", "bad.ocio")
        self.assert_error(self.render(scene, *TINY, "--ocio-config", bad, outputs=("image.png",)),
                          INPUT, "%s: the OpenColorIO config (--ocio-config) cannot be loaded" % bad)
        self.assert_error(self.render(scene, *TINY, outputs=("image.png",),
                                      env_changes={"OCIO": str(self.dir / "missing.ocio")}),
                          INPUT, "%s: the OpenColorIO config ($OCIO) cannot be loaded" %
                          (self.dir / "missing.ocio"))

    def test_unknown_names_typed_are_usage_errors_listing_the_configs(self):
        scene = self.scene(view_scene(view_transform="Raw"))
        config = self.tiny_ocio()
        self.assert_usage_error(scene, [*TINY, "--ocio-config", config, "--view-transform", "Filmic"],
                                "--view-transform 'Filmic': expected a view of display 'sRGB': "
                                "'Standard', 'Raw'", outputs=("image.png",))
        self.assert_usage_error(scene, [*TINY, "--ocio-config", config, "--look", "Punchy"],
                                "--look 'Punchy': expected a look: 'None', 'Twice'",
                                outputs=("image.png",))
        self.assert_usage_error(scene, [*TINY, "--exposure", "40"], "--exposure '40': expected a number",
                                outputs=("image.png",))

    def test_unknown_names_in_the_file_fall_back_as_blender_does(self):
        scene = self.scene(view_scene(view_transform="AgX", look="Punchy", dither_intensity=0))
        value, result = self.grey_level(scene, "--ocio-config", self.tiny_ocio())
        self.assertEqual(value, level(srgb(0.18)))  # the display's default view, no look
        self.assertIn("scenes[0].extensions.FILMBACK_blender.view_transform: 'AgX': expected a view",
                      result.stderr)
        self.assertIn("using 'Standard' as Blender does", result.stderr)
        self.assertIn("FILMBACK_blender.look: 'Punchy': expected a look", result.stderr)

    def test_exr_records_the_view_settings(self):
        scene = self.scene(view_scene(view_transform="Filmic", look="Medium High Contrast",
                                      exposure_stops=0.7, gamma=1.2))
        self.assert_rendered(self.render(scene, *TINY, outputs=("image.exr",)), "image.exr")
        attributes = exr_attributes(self.out / "image.exr")
        strings = {name: value.decode() for name, (kind, value) in attributes.items()
                   if kind == "string"}
        floats = {name: struct.unpack("<f", value)[0] for name, (kind, value) in attributes.items()
                  if kind == "float"}
        self.assertEqual(strings.get("filmback/view_transform"), "Filmic")
        self.assertEqual(strings.get("filmback/look"), "Medium High Contrast")
        self.assertEqual(strings.get("filmback/display_device"), "sRGB")
        self.assertAlmostEqual(floats["filmback/exposure_stops"], 0.7, places=6)
        self.assertAlmostEqual(floats["filmback/gamma"], 1.2, places=6)
        self.assertEqual(floats["filmback/dither_intensity"], 1.0)  # Blender's default

    def test_info_prints_the_view_settings(self):
        scene = self.scene(view_scene(view_transform="Filmic", look="High Contrast", exposure_stops=0.5))
        result = self.run_cli("info", scene)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("view (8-bit outputs): display 'sRGB', view 'Filmic', look 'High Contrast', "
                      "exposure 0.5 stops, gamma 1, dither 1", result.stdout)

    def test_writes_jpeg(self):
        scene = self.scene(triangle_scene())
        self.assert_rendered(self.render(scene, *TINY, outputs=("image.jpg",)), "image.jpg")
        self.assertEqual((self.out / "image.jpg").read_bytes()[:3], b"\xff\xd8\xff")


def configure(args):
    global FILMBACK, SCRATCH
    FILMBACK, SCRATCH = args.filmback, args.scratch


if __name__ == "__main__":
    sys.exit(case_main.main(CliTest, __doc__, configure))
