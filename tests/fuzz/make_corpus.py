"""Writes the fuzz harnesses' seed corpora (tests/fuzz/corpus/<harness>/), committed as written:
valid scenes of each kind, the hostile files of tests/hostile/, files reaching for the harness
folders' real files (tests/fuzz/fuzz_gltf.cpp, fuzz_pov.cpp), the default scene as a .glb, and the
heads of a few POV-Ray sample scenes (when povray-examples is installed). Files named found_* are
inputs the fuzzers found, kept as they were (each fix has its regression test); this script leaves
them alone.

Run: python3 tests/fuzz/make_corpus.py
"""

import json
import os
import random
import struct
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(HERE.parent / "cli"))
from gltf_files import GLB_BIN, GLB_JSON, GLB_MAGIC, _pad4, png_1x1_uri, triangle_scene  # noqa: E402

SAMPLES = Path("/usr/share/doc/povray/examples")
SAMPLE_HEADS = ["objects/primitiv.pov", "language/fileio/fileio.pov",
                "textures/interior_texture.pov", "advanced/benchmark/benchmark.pov"]
HEAD_BYTES = 3000


def gltf_corpus():
    files = {}
    g = triangle_scene()
    files["triangle.gltf"] = g.json_text()
    files["triangle.glb"] = g.glb_bytes()
    files["external.gltf"] = g.json_text(buffer_uri="triangle.bin")
    files["escape.gltf"] = g.json_text(buffer_uri="../outside.bin")
    files["encoded_escape.gltf"] = g.json_text(buffer_uri="%2e%2e/outside.bin")
    files["symlink.gltf"] = g.json_text(buffer_uri="link.bin")
    files["absolute.gltf"] = g.json_text(buffer_uri="/etc/passwd")
    files["http.gltf"] = g.json_text(buffer_uri="http://127.0.0.1:9/triangle.bin")
    textured = triangle_scene()
    textured.doc["images"] = [{"uri": png_1x1_uri()}, {"uri": "texture.png"}]
    textured.doc["textures"] = [{"source": 0}, {"source": 1}]
    textured.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}},
                                  "emissiveTexture": {"index": 1}}]
    files["textured.gltf"] = textured.json_text()
    blender = triangle_scene()
    texture = {"uri": "texture.png", "uv_map": "UVMap", "uv_transform": [2, 0, 0.5, 0, 2, 0],
               "extension": "CLIP", "interpolation": "Cubic", "colorspace": "Non-Color"}
    blender.doc["materials"] = [{"extensions": {"FILMBACK_blender": {
        "blender_version": [3, 4, 1], "surface": 4, "warnings": ["a node not carried"],
        "nodes": [
            {"type": "PRINCIPLED", "distribution": "MULTI_GGX", "inputs": {
                "base_color": {"texture": texture}, "roughness": {"texture": texture, "channel": "G"},
                "anisotropic": 0.5, "sheen": 1, "clearcoat": 0.5, "subsurface": 0.2, "alpha": 0.8,
                "emission": [1, 0.5, 0], "emission_strength": 2,
                "normal": {"normal_map": {"texture": texture, "strength": 0.7}}}},
            {"type": "GLASS", "distribution": "BECKMANN", "inputs": {"ior": 1.33, "roughness": 0.1}},
            {"type": "MIX_SHADER", "inputs": {"fac": {"texture": texture, "output": "Alpha"}},
             "shaders": [0, 1]},
            {"type": "TRANSPARENT", "inputs": {"color": [0.5, 0.5, 0.5]}},
            {"type": "ADD_SHADER", "shaders": [2, 3]}]}}}]
    blender.doc["meshes"][0]["primitives"][0]["material"] = 0
    blender.doc["meshes"][0]["extensions"] = {"FILMBACK_blender": {
        "uv_maps": ["UVMap"], "texspace_location": [0, 0, 0], "texspace_size": [1, 1, 1]}}
    blender.doc["extensionsUsed"] = ["FILMBACK_blender"]
    files["blender_material.gltf"] = blender.json_text()
    lit = triangle_scene()
    lit.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    lit.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "intensity": 100, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}}]}}
    lit.node(name="lamp", extensions={"KHR_lights_punctual": {"light": 0}}, translation=[0, 2, 0])
    files["light.gltf"] = lit.json_text()
    animated = triangle_scene()
    times = animated.view(struct.pack("<2f", 0.0, 1.0))
    values = animated.view(struct.pack("<6f", 0, 0, -3, 1, 0, -3))
    t = animated.accessor(times, 5126, "SCALAR", 2)
    animated.doc["accessors"][t].update({"min": [0.0], "max": [1.0]})
    v = animated.accessor(values, 5126, "VEC3", 2)
    animated.doc["animations"] = [{"samplers": [{"input": t, "output": v, "interpolation": "LINEAR"}],
                                   "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]}]
    files["animated.gltf"] = animated.json_text()
    # tests/hostile/: a BIN chunk longer than the file, an accessor past its view, 2^31 elements,
    # a node cycle
    data = bytearray(g.glb_bytes())
    bin_at = 20 + struct.unpack("<I", data[12:16])[0]
    data[bin_at:bin_at + 4] = struct.pack("<I", 0x7FFFFFF0)
    files["chunk_past_end.glb"] = bytes(data)
    past = triangle_scene()
    past.doc["accessors"][0]["byteOffset"] = 24
    files["accessor_past_view.gltf"] = past.json_text()
    huge = triangle_scene()
    huge.doc["accessors"][0]["count"] = 2 ** 31
    files["huge_accessor.gltf"] = huge.json_text()
    cycle = triangle_scene()
    a = cycle.node(name="a", children=[])
    b = cycle.node(root=False, name="b", children=[a])
    cycle.doc["nodes"][a]["children"] = [b]
    files["cycle.gltf"] = cycle.json_text()
    # the default scene, its buffer as the BIN chunk
    doc = json.loads((ROOT / "scenes/default/default.gltf").read_text())
    binary = (ROOT / "scenes/default/default.bin").read_bytes()
    doc["buffers"] = [{"byteLength": len(binary)}]
    json_chunk = _pad4(json.dumps(doc, separators=(",", ":")).encode(), b" ")
    bin_chunk = _pad4(binary, b"\0")
    body = (struct.pack("<II", len(json_chunk), GLB_JSON) + json_chunk
            + struct.pack("<II", len(bin_chunk), GLB_BIN) + bin_chunk)
    files["default_scene.glb"] = struct.pack("<III", GLB_MAGIC, 2, 12 + len(body)) + body
    return files


POV_SCENES = {
    "sphere.pov": """camera { location <0, 1, -5> look_at 0 angle 40 }
light_source { <5, 5, -5> color rgb 1 }
sphere { 0, 1 pigment { checker rgb 1, rgb <1, 0, 0> scale 0.25 } finish { diffuse 0.8 } }
plane { y, -1 pigment { color rgb <0.5, 0.6, 0.7> } }
""",
    "csg.pov": """#declare R = 0.5;
difference { box { -1, 1 } sphere { 0, 1.3 } rotate <10, 20, 30> }
intersection { cylinder { -y, y, R } torus { 1, R } translate x * 3 }
union { cone { 0, 1, y, 0 open } disc { 0, y, 1 } clipped_by { plane { x, 0 } } }
""",
    "language.pov": """#declare V = <1, 2, 3>;
#declare A = array[3] { 1, 2, 3 };
#macro Add(X, Y) (X + Y) #end
#local I = 0;
#while (I < 10)
  #declare I = I + 1;
  #switch (I) #case (1) #debug "one\\n" #break #range (2, 5) #declare S = concat("x", str(I, 0, 2)); #break #else #end
#end
#for (J, 0, 4, 2) sphere { V * J, Add(J, 1) / 10 } #end
#if (vlength(V) > 3 & A[1] = 2) box { -V, V } #else #error "no" #end
#ifdef (S) #undef S #end
""",
    "includes.pov": """#include "local.inc"
#include "sub/near.inc"
#include "lib.inc"
object { Local } object { Lib(FromSub) pigment { LibColor } }
""",
    "escapes.pov": """#include "../outside.inc"
#include "link.inc"
#include "/etc/passwd"
""",
    "file_io.pov": """#fopen F "data.txt" read
#read (F, A, B, V, S)
#fclose F
#fopen W "out.txt" write
#write (W, A, ",", V, "\\n")
#fclose W
#fopen R "out.txt" read
#read (R, X)
sphere { V, abs(A) }
""",
    "mesh.pov": """mesh2 { vertex_vectors { 3, <0,0,0>, <1,0,0>, <0,1,0> }
  face_indices { 1, <0, 1, 2> } }
mesh { triangle { <0,0,0>, <1,0,0>, <0,1,0> } smooth_triangle { 0, y, x, y, z, y } }
polygon { 4, <0,0>, <1,0>, <1,1>, <0,0> }
quartic { <1,0,0,0,0,0,0,0,0,-2, 0,0,0,0,0,0,0,0,0,0, 0,0,0,0,0,0,0,0,0,0, 0,0,0,0,1> }
""",
    "infinite_while.pov": "#while (1) #end\n",
    "macro_recursion.pov": "#macro R() R() #end\nR()\n",
    "self_include.pov": '#include "scene.pov"\n',
}


def pov_corpus():
    files = dict(POV_SCENES)
    for relative in SAMPLE_HEADS:
        path = SAMPLES / relative
        if path.is_file():
            files["head_" + path.name] = path.read_bytes()[:HEAD_BYTES]
    return files


PARAM_SPECS = [
    "gaussian:radius=1.5,sigma=0.5",
    "fuzz:radius=2,count=5,free=-1e300,enabled=off,tint=[1,2,3],mode=b,label=some text",
    "fuzz:tint=0.5,mode=c,label=",
    "fuzz:count=64,radius=1e-3,enabled=yes",
    "fuzz:radius=[1,2],tint=[1,[2],3]",
    "box",
    "table:values=[0,1,0.5,0.25]",
    "trapezoid:ramp=0.25",
    "table:values=[0]",
]


def descriptor_corpus():
    rng = random.Random(7)  # fixed: the corpus is committed
    return {"random_%d" % i: bytes(rng.getrandbits(8) for _ in range(n))
            for i, n in enumerate((64, 160, 320, 640))}


def write(harness, files):
    folder = HERE / "corpus" / harness
    folder.mkdir(parents=True, exist_ok=True)
    for name, data in files.items():
        path = folder / name
        path.write_bytes(data if isinstance(data, bytes) else data.encode())


def main():
    write("gltf", gltf_corpus())
    write("pov", pov_corpus())
    write("params", {"spec_%d" % i: s for i, s in enumerate(PARAM_SPECS)})
    write("descriptor", descriptor_corpus())
    return 0


if __name__ == "__main__":
    sys.exit(main())
