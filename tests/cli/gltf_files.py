"""Small glTF 2.0 files for the command-line tests, written with the standard library only.

A Gltf holds the JSON document and one binary buffer; it is written either as .gltf (the buffer as
a base64 data: URI) or as .glb (the buffer as the BIN chunk). Cases break a valid file by editing
`doc` or `bin` before writing it, so each file has exactly one thing wrong.
Layout references are to the glTF 2.0 specification (registry.khronos.org/glTF/specs/2.0).
"""

import base64
import json
import struct
import zlib

FLOAT = 5126  # accessor componentType (spec §5.1.3)
UNSIGNED_BYTE = 5121
UNSIGNED_INT = 5125

GLB_MAGIC = 0x46546C67  # "glTF" (spec §4.4.3)
GLB_JSON = 0x4E4F534A  # "JSON"
GLB_BIN = 0x004E4942  # "BIN\0"


def _pad4(data, fill):
    return data + fill * (-len(data) % 4)


class Gltf:
    def __init__(self):
        self.doc = {
            "asset": {"version": "2.0", "generator": "filmback tests/cli"},
            "scene": 0,
            "scenes": [{"nodes": []}],
            "nodes": [],
            "meshes": [],
            "accessors": [],
            "bufferViews": [],
            "buffers": [],
        }
        self.bin = bytearray()

    def view(self, data):
        """Appends `data` to the buffer, 4-byte aligned, as a new bufferView; returns its index."""
        self.bin += b"\0" * (-len(self.bin) % 4)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, view, component_type, element_type, count):
        self.doc["accessors"].append(
            {"bufferView": view, "componentType": component_type, "type": element_type, "count": count})
        return len(self.doc["accessors"]) - 1

    def positions(self, points):
        """A VEC3 float accessor; min/max are required for POSITION (spec §3.7.2.1)."""
        data = b"".join(struct.pack("<3f", *p) for p in points)
        index = self.accessor(self.view(data), FLOAT, "VEC3", len(points))
        finite = [p for p in points if all(c == c for c in p)]  # NaN != NaN
        if finite:
            self.doc["accessors"][index]["min"] = [min(p[i] for p in finite) for i in range(3)]
            self.doc["accessors"][index]["max"] = [max(p[i] for p in finite) for i in range(3)]
        return index

    def indices(self, values, component_type=UNSIGNED_INT):
        code = {UNSIGNED_BYTE: "B", UNSIGNED_INT: "I"}[component_type]
        data = struct.pack("<%d%s" % (len(values), code), *values)
        return self.accessor(self.view(data), component_type, "SCALAR", len(values))

    def mesh(self, primitives):
        self.doc["meshes"].append({"primitives": primitives})
        return len(self.doc["meshes"]) - 1

    def node(self, root=True, **fields):
        self.doc["nodes"].append(fields)
        index = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def camera(self, name):
        cameras = self.doc.setdefault("cameras", [])
        cameras.append({"name": name, "type": "perspective",
                        "perspective": {"yfov": 0.8, "aspectRatio": 1.0, "znear": 0.1, "zfar": 100.0}})
        return len(cameras) - 1

    def json_text(self, buffer_uri=None):
        """The document with the buffer as a data: URI, or as `buffer_uri` (a file next to it)."""
        doc = dict(self.doc)
        if self.bin:
            data = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()
            doc["buffers"] = [{"byteLength": len(self.bin), "uri": buffer_uri or data}]
        return json.dumps(doc, indent=1)

    def glb_bytes(self, buffer_length=None):
        """The binary container (spec §4.4): 12-byte header, JSON chunk, BIN chunk. The buffer's
        byteLength is the BIN data's unless `buffer_length` says otherwise."""
        doc = dict(self.doc)
        if self.bin:
            doc["buffers"] = [{"byteLength": buffer_length or len(self.bin)}]
        json_chunk = _pad4(json.dumps(doc).encode(), b" ")
        bin_chunk = _pad4(bytes(self.bin), b"\0")
        body = struct.pack("<II", len(json_chunk), GLB_JSON) + json_chunk
        if bin_chunk:
            body += struct.pack("<II", len(bin_chunk), GLB_BIN) + bin_chunk
        return struct.pack("<III", GLB_MAGIC, 2, 12 + len(body)) + body

    def write(self, path):
        """Writes .gltf or .glb by the path's extension; returns the path."""
        if str(path).endswith(".glb"):
            path.write_bytes(self.glb_bytes())
        else:
            path.write_text(self.json_text())
        return path


TRIANGLE = [(-1.0, -1.0, 0.0), (1.0, -1.0, 0.0), (0.0, 1.0, 0.0)]


def triangle_scene():
    """One indexed triangle 3 m in front of a camera named 'shot' that looks at it down -Z."""
    g = Gltf()
    position = g.positions(TRIANGLE)
    index = g.indices([0, 1, 2])
    g.mesh([{"attributes": {"POSITION": position}, "indices": index}])
    g.node(name="triangle", mesh=0, translation=[0.0, 0.0, -3.0])
    g.node(name="shot", camera=g.camera("shot"))
    return g


def png_1x1_uri():
    """A valid 1x1 grey PNG (PNG spec §5: signature, IHDR, IDAT, IEND) as a data: URI."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    ihdr = struct.pack(">IIBBBBB", 1, 1, 8, 0, 0, 0, 0)  # 8-bit greyscale
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(b"\x00\x80"))
           + chunk(b"IEND", b""))
    return "data:image/png;base64," + base64.b64encode(png).decode()
