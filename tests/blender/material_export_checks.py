"""Checks of material_export_scene.py's export against what bpy reads (run inside Blender).

`check(gltf_path, scene, materials, images)` returns a list of differences, empty when every value
of the FILMBACK_blender material, mesh, light and scene objects is what Blender holds: constants
exactly (float32 values widened to double), images as files beside the export that decode to the
source image's pixels, uv_transforms that map sample points as Blender's Mapping nodes do (computed
here with mathutils), warnings that name the node, and TEXCOORD_n data that is the UV map the
extension names.
"""

import json
import os
import urllib.parse

import bpy
import numpy as np
from mathutils import Euler, Vector

EXTENSION = "FILMBACK_blender"
# Sample points in glTF texture space (v down), inside and outside [0, 1].
SAMPLES_UV = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.3, 0.8), (-0.5, 2.25), (0.71, 0.13)]
# Blender's Mapping is computed here in mathutils' float32, the uv_transform in double: 4 float32
# ulps of the samples' images (below 4 in magnitude); measured 3.0e-7 (1.3 ulps) with Blender
# 3.4.1.
MAPPING_TOLERANCE = 4 * 2.0**-21
NORMAL_INPUTS = ("Normal", "Clearcoat Normal", "Tangent")


class Checker:
    def __init__(self, gltf_path):
        self.folder = os.path.dirname(gltf_path)
        with open(gltf_path) as f:
            self.gltf = json.load(f)
        self.failures = []
        self.compared = 0
        self.copies = {}  # name -> how many glTF objects of that name the file has

    def expect(self, where, got, want):
        self.compared += 1
        if got != want:
            self.failures.append(f"{where}: file {got!r}, bpy {want!r}")

    def extension(self, kind, name):
        items = [x for x in self.gltf.get(kind, []) if x.get("name") == name]
        if not items:
            self.failures.append(f"{kind} '{name}' is not in the file")
            return {}
        data = items[0].get("extensions", {}).get(EXTENSION)
        if data is None:
            self.failures.append(f"{kind} '{name}' has no {EXTENSION}")
            return {}
        for other in items[1:]:
            self.expect(f"{kind} '{name}' (another copy)", other["extensions"][EXTENSION], data)
        self.copies[name] = len(items)
        return data

    # Values

    def constant(self, where, got, socket):
        want = socket.default_value
        if socket.type == "RGBA":
            want = list(want)[:3]
        elif socket.type == "VECTOR":
            want = list(want)
        self.expect(where, got, want)

    def node_constants(self, where, entry, node, skip=()):
        """Every enabled value input of `node` that is unlinked is written as its value; normal
        inputs are absent; nothing else is written."""
        inputs = entry.get("inputs", {})
        keys = set()
        for socket in node.inputs:
            if not socket.enabled or socket.type == "SHADER" or socket.name in skip:
                continue
            key = socket.identifier.lower().replace(" ", "_")
            if socket.identifier in NORMAL_INPUTS:
                self.expect(f"{where}.{key} (unlinked normal: absent)", key in inputs, False)
                continue
            keys.add(key)
            self.constant(f"{where}.{key}", inputs.get(key), socket)
        extra = set(inputs) - keys - {s.identifier.lower().replace(" ", "_") for s in node.inputs
                                      if s.name in skip}
        self.expect(f"{where}: inputs not in the node", sorted(extra), [])

    def texture(self, where, value, image_node, image, output="Color", channel=None,
                uv_map="", mappings=(), file_settings=None):
        """`value` is {"texture": T, "output": ..., ["channel": ...]} for `image_node`."""
        if not isinstance(value, dict) or "texture" not in value:
            self.failures.append(f"{where}: not a texture: {value!r}")
            return
        self.expect(f"{where}.output", value["output"], output)
        self.expect(f"{where}.channel", value.get("channel"), channel)
        self.texture_object(where, value["texture"], image_node, image, uv_map, mappings,
                            file_settings)

    def texture_object(self, where, t, image_node, image, uv_map="", mappings=(),
                       file_settings=None):
        """T of `image_node`; `file_settings` (colour space, alpha mode) when the written file
        holds other than the image's own."""
        colorspace, alpha_mode = file_settings or (image.colorspace_settings.name,
                                                   image.alpha_mode)
        self.expect(f"{where}.uv_map", t["uv_map"], uv_map)
        self.expect(f"{where}.extension", t["extension"], image_node.extension)
        self.expect(f"{where}.interpolation", t["interpolation"], image_node.interpolation)
        self.expect(f"{where}.alpha_mode", t["alpha_mode"], alpha_mode)
        self.expect(f"{where}.colorspace", t["colorspace"], colorspace)
        self.uv_transform(where, t["uv_transform"], mappings)
        self.image_file(where, t, image)

    def uv_transform(self, where, transform, mappings):
        """The glTF-space transform maps each sample as Blender's Mappings (from the UV side,
        `mappings` in order) do in Blender's space, v flipped on both sides."""
        a, b, c, d, e, f = transform
        if not mappings:
            self.expect(f"{where}.uv_transform", transform, [1, 0, 0, 0, 1, 0])
            return
        for u, v in SAMPLES_UV:
            p = Vector((u, 1.0 - v, 0.0))
            for node in mappings:
                p = blender_mapping(node, p)
            want = (p.x, 1.0 - p.y)
            got = (a * u + b * v + c, d * u + e * v + f)
            self.compared += 1
            if max(abs(g - w) for g, w in zip(got, want)) > MAPPING_TOLERANCE:
                self.failures.append(f"{where}.uv_transform {transform} maps ({u}, {v}) to {got}; "
                                     f"Blender's Mapping to {want}")

    def image_file(self, where, t, image):
        """The file T names is beside the export and, read as T says (colour space, alpha
        mode), holds the image's pixels."""
        uri = t.get("uri")
        self.compared += 1
        if not isinstance(uri, str) or "/" in uri or uri.startswith("."):
            self.failures.append(f"{where}.uri {uri!r}: not a file name beside the export")
            return
        path = os.path.join(self.folder, urllib.parse.unquote(uri))
        if not os.path.isfile(path):
            self.failures.append(f"{where}.uri {uri!r}: no such file beside the export")
            return
        blender_uris = {i.get("uri") for i in self.gltf.get("images", [])}
        self.expect(f"{where}.uri {uri!r} is one of Blender's own image files",
                    uri in blender_uris, False)
        written = bpy.data.images.load(path, check_existing=False)
        try:
            written.colorspace_settings.name = t["colorspace"]
            written.alpha_mode = t["alpha_mode"]
            self.expect(f"{where}: {uri} size", tuple(written.size), tuple(image.size))
            self.expect(f"{where}: {uri} pixels equal image '{image.name}''s",
                        bool(np.array_equal(pixels(written), pixels(image))), True)
        finally:
            bpy.data.images.remove(written)

    def warning(self, data, material, *words):
        """One of the material's warnings names the material and every word."""
        self.compared += 1
        if not any(f"material '{material}'" in w and all(x in w for x in words)
                   for w in data.get("warnings", [])):
            self.failures.append(f"material '{material}': no warning naming {words}; warnings: "
                                 f"{data.get('warnings')}")


def pixels(image):
    out = np.empty(image.size[0] * image.size[1] * image.channels, dtype=np.float32)
    image.pixels.foreach_get(out)
    return out


def blender_mapping(node, p):
    """Blender's Mapping node on point p (the manual's definitions, in mathutils)."""
    location = Vector(node.inputs["Location"].default_value)
    rotation = Euler(node.inputs["Rotation"].default_value, "XYZ").to_matrix()
    scale = Vector(node.inputs["Scale"].default_value)
    if node.vector_type == "TEXTURE":
        q = rotation.transposed() @ (p - location)
        return Vector([q[i] / scale[i] if scale[i] != 0 else 0.0 for i in range(3)])
    scaled = Vector([p[i] * scale[i] for i in range(3)])
    moved = rotation @ scaled
    return moved + location if node.vector_type == "POINT" else moved


def by_type(tree, kind):
    return [n for n in tree.nodes if n.bl_idname == kind]


def surface(c, data, kind):
    nodes = data.get("nodes", [])
    index = data.get("surface")
    if index is None or not 0 <= index < len(nodes):
        c.failures.append(f"no surface node: {data}")
        return {}
    c.expect("surface node type", nodes[index]["type"], kind)
    return nodes[index]


def shaders(c, data, entry, kinds):
    nodes = data.get("nodes", [])
    out = []
    for i, kind in zip(entry.get("shaders", []), kinds):
        c.expect("shader input's type", nodes[i]["type"] if i >= 0 else None, kind)
        out.append(nodes[i] if i >= 0 else {})
    c.expect("number of shader inputs", len(entry.get("shaders", [])), len(kinds))
    return out


def check_all_inputs(c, material):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "PRINCIPLED")
    node = by_type(material.node_tree, "ShaderNodeBsdfPrincipled")[0]
    c.expect("AllInputs.name", entry.get("name"), node.name)
    c.expect("AllInputs.distribution", entry.get("distribution"), node.distribution)
    c.expect("AllInputs.subsurface_method", entry.get("subsurface_method"),
             node.subsurface_method)
    c.node_constants("AllInputs", entry, node)
    c.expect("AllInputs.warnings", data.get("warnings"), None)
    c.expect("AllInputs node count", len(data.get("nodes", [])), 1)


def check_textured(c, material, images):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "PRINCIPLED")
    tree = material.node_tree
    node = by_type(tree, "ShaderNodeBsdfPrincipled")[0]
    inputs = entry.get("inputs", {})
    linked = ("Base Color", "Roughness", "Metallic", "Sheen", "Normal", "Alpha", "Emission",
              "Clearcoat Normal")
    c.node_constants("Textured", entry, node, skip=linked)
    image_nodes = {n.image.name: n for n in by_type(tree, "ShaderNodeTexImage")}
    mappings = {m.vector_type: m for m in by_type(tree, "ShaderNodeMapping")
                if m.inputs["Vector"].links[0].from_node.bl_idname == "ShaderNodeUVMap"}
    point_first = next(m for m in by_type(tree, "ShaderNodeMapping")
                       if m.inputs["Vector"].links[0].from_node.bl_idname == "ShaderNodeTexCoord")
    texture_second = next(m for m in by_type(tree, "ShaderNodeMapping")
                          if m.vector_type == "TEXTURE")
    a, b = images["a"], images["b"]
    c.texture("Textured.base_color", inputs.get("base_color"), image_nodes[a.name], a,
              uv_map="Detail", mappings=[mappings["POINT"]])
    c.texture("Textured.roughness", inputs.get("roughness"), image_nodes[b.name], b, channel="G",
              mappings=[point_first, texture_second])
    c.texture("Textured.sheen", inputs.get("sheen"), image_nodes[b.name], b, channel="B",
              mappings=[point_first, texture_second])
    checker = images["checker"]
    c.texture("Textured.metallic", inputs.get("metallic"), image_nodes[checker.name], checker,
              channel="B")
    packed = images["packed"]
    c.texture("Textured.alpha", inputs.get("alpha"), image_nodes[packed.name], packed,
              output="Alpha")
    glow = images["glow"]
    # A generated float image is saved from Blender's float buffer: scene-linear, premultiplied.
    c.texture("Textured.emission", inputs.get("emission"), image_nodes[glow.name], glow,
              file_settings=("Linear", "PREMUL"))
    normal_map = by_type(tree, "ShaderNodeNormalMap")[0]
    written = inputs.get("normal", {}).get("normal_map", {})
    c.expect("Textured.normal.strength", written.get("strength"),
             normal_map.inputs["Strength"].default_value)
    c.expect("Textured.normal.strength is Blender's float32 0.7", written.get("strength"),
             float(np.float32(0.7)))
    c.expect("Textured.normal.space", written.get("space"), normal_map.space)
    c.expect("Textured.normal.uv_map", written.get("uv_map"), "Detail")
    normal = images["normal"]
    if "texture" in written:
        c.texture_object("Textured.normal.texture", written["texture"],
                         image_nodes[normal.name], normal)
    else:
        c.failures.append(f"Textured.normal: no normal map: {inputs.get('normal')!r}")
    c.expect("Textured.clearcoat_normal (a Bump: absent)", "clearcoat_normal" in inputs, False)
    c.warning(data, "Textured", "'Bump'", "BUMP", "Clearcoat Normal")
    c.warning(data, "Textured", "'ColorRamp'", "VALTORGB", "Specular",
              f"{node.inputs['Specular'].default_value:.6g}")
    c.expect("Textured.specular (a Color Ramp: the input's value)", inputs.get("specular"),
             node.inputs["Specular"].default_value)
    c.expect("Textured: warnings", len(data.get("warnings", [])), 2)
    uris = {inputs.get(k, {}).get("texture", {}).get("uri") for k in ("base_color", "roughness")}
    c.expect("Textured: the two tex.png images are written under two names", len(uris), 2)


def check_mix_glossy_diffuse(c, material, images):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "MIX_SHADER")
    tree = material.node_tree
    glossy_entry, diffuse_entry = shaders(c, data, entry, ["GLOSSY", "DIFFUSE"])
    glossy = by_type(tree, "ShaderNodeBsdfGlossy")[0]
    c.expect("MixGlossyDiffuse.glossy.distribution", glossy_entry.get("distribution"),
             glossy.distribution)
    c.node_constants("MixGlossyDiffuse.glossy", glossy_entry, glossy)
    c.node_constants("MixGlossyDiffuse.diffuse", diffuse_entry,
                     by_type(tree, "ShaderNodeBsdfDiffuse")[0])
    image_node = by_type(tree, "ShaderNodeTexImage")[0]
    c.texture("MixGlossyDiffuse.fac", entry.get("inputs", {}).get("fac"), image_node, images["a"])
    c.expect("MixGlossyDiffuse.warnings", data.get("warnings"), None)


def check_add_shader(c, material):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "ADD_SHADER")
    emission, diffuse = shaders(c, data, entry, ["EMISSION", "DIFFUSE"])
    tree = material.node_tree
    c.node_constants("AddShader.emission", emission, by_type(tree, "ShaderNodeEmission")[0])
    c.node_constants("AddShader.diffuse", diffuse, by_type(tree, "ShaderNodeBsdfDiffuse")[0])
    c.expect("AddShader: inputs", "inputs" in entry, False)


def check_glass(c, material):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "GLASS")
    node = by_type(material.node_tree, "ShaderNodeBsdfGlass")[0]
    c.expect("Glass.distribution", entry.get("distribution"), node.distribution)
    c.node_constants("Glass", entry, node)


def check_transparent_mix(c, material):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "MIX_SHADER")
    tree = material.node_tree
    c.node_constants("TransparentMix.mix", entry, by_type(tree, "ShaderNodeMixShader")[0])
    transparent, principled = shaders(c, data, entry, ["TRANSPARENT", "PRINCIPLED"])
    c.node_constants("TransparentMix.transparent", transparent,
                     by_type(tree, "ShaderNodeBsdfTransparent")[0])
    c.node_constants("TransparentMix.principled", principled,
                     by_type(tree, "ShaderNodeBsdfPrincipled")[0])


def check_grouped(c, material, images):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "PRINCIPLED")
    tree = material.node_tree
    group_node = by_type(tree, "ShaderNodeGroup")[0]
    inner = by_type(group_node.node_tree, "ShaderNodeBsdfPrincipled")[0]
    c.expect("Grouped.name", entry.get("name"), f"{group_node.name} > {inner.name}")
    inputs = entry.get("inputs", {})
    c.expect("Grouped.base_color (the group node's Tint)", inputs.get("base_color"),
             list(group_node.inputs["Tint"].default_value)[:3])
    c.node_constants("Grouped", entry, inner, skip=("Base Color", "Roughness", "Metallic"))
    rgb = list(by_type(tree, "ShaderNodeRGB")[0].outputs[0].default_value)
    luminance = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]
    c.compared += 1
    if abs(inputs.get("metallic", -1.0) - luminance) > 2.0**-24:
        c.failures.append(f"Grouped.metallic {inputs.get('metallic')}: not the luminance "
                          f"{luminance} of the RGB node's {rgb}")
    c.texture("Grouped.roughness", inputs.get("roughness"), by_type(tree, "ShaderNodeTexImage")[0],
              images["b"], channel="R")
    c.expect("Grouped.warnings", data.get("warnings"), None)


def check_toon(c, material):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "DIFFUSE")
    toon = by_type(material.node_tree, "ShaderNodeBsdfToon")[0]
    c.constant("Toon.color", entry.get("inputs", {}).get("color"), toon.inputs["Color"])
    c.expect("Toon.roughness", entry.get("inputs", {}).get("roughness"), 0.0)
    c.warning(data, "Toon", f"'{toon.name}'", "BSDF_TOON", "DIFFUSE")


def check_shared(c, material):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "MIX_SHADER")
    c.expect("Shared: one node in both shader inputs", entry.get("shaders"), [1, 1])
    c.expect("Shared: node count", len(data.get("nodes", [])), 2)


def check_object_coordinates(c, material, images):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "DIFFUSE")
    tree = material.node_tree
    c.texture("ObjectCoordinates.color", entry.get("inputs", {}).get("color"),
              by_type(tree, "ShaderNodeTexImage")[0], images["a"])
    coordinates = by_type(tree, "ShaderNodeTexCoord")[0]
    c.warning(data, "ObjectCoordinates", f"'{coordinates.name}'", "TEX_COORD", "Object")


def check_fallbacks(c, material, images):
    data = c.extension("materials", material.name)
    nodes = data.get("nodes", [])
    tree = material.node_tree
    mix, emission = shaders(c, data, surface(c, data, "ADD_SHADER"), ["MIX_SHADER", "EMISSION"])
    image_node = next(n for n in by_type(tree, "ShaderNodeTexImage") if n.image == images["a"])
    c.texture("Fallbacks: an image's colour into a shader socket",
              emission.get("inputs", {}).get("color"), image_node, images["a"])
    c.expect("Fallbacks: its strength", emission.get("inputs", {}).get("strength"), 1)
    glass_index, volume_index = (mix.get("shaders", []) + [-1, -1])[:2]
    c.expect("Fallbacks: Principled Volume on a surface (nothing)", volume_index, -1)
    glass = nodes[glass_index] if glass_index >= 0 else {}
    refraction = by_type(tree, "ShaderNodeBsdfRefraction")[0]
    c.expect("Fallbacks: Refraction replaced by", glass.get("type"), "GLASS")
    c.expect("Fallbacks.glass.distribution", glass.get("distribution"), refraction.distribution)
    inputs = glass.get("inputs", {})
    c.expect("Fallbacks.glass.color (an RGB node)", inputs.get("color"),
             list(by_type(tree, "ShaderNodeRGB")[0].outputs[0].default_value)[:3])
    c.constant("Fallbacks.glass.roughness (Separate HSV: the input's value)",
               inputs.get("roughness"), refraction.inputs["Roughness"])
    c.constant("Fallbacks.glass.ior", inputs.get("ior"), refraction.inputs["IOR"])
    written = inputs.get("normal", {}).get("normal_map", {})
    c.expect("Fallbacks.glass.normal.space", written.get("space"), "OBJECT")
    c.expect("Fallbacks.glass.normal.strength (a Value node)", written.get("strength"),
             by_type(tree, "ShaderNodeValue")[0].outputs[0].default_value)
    c.warning(data, "Fallbacks", "'Refraction BSDF'", "BSDF_REFRACTION", "GLASS")
    c.warning(data, "Fallbacks", "'Principled Volume'", "PRINCIPLED_VOLUME", "nothing")
    c.warning(data, "Fallbacks", "'Separate Color'", "HSV", "Roughness")
    c.warning(data, "Fallbacks", "'Normal Map'", "OBJECT", "TANGENT")
    c.expect("Fallbacks: warnings", len(data.get("warnings", [])), 4)


def check_in_export_folder(c, material, images):
    data = c.extension("materials", material.name)
    inputs = surface(c, data, "PRINCIPLED").get("inputs", {})
    image_node = by_type(material.node_tree, "ShaderNodeTexImage")[0]
    c.texture("InExportFolder.roughness", inputs.get("roughness"), image_node,
              images["in_export"], channel="G")
    c.texture("InExportFolder.metallic", inputs.get("metallic"), image_node, images["in_export"],
              channel="B")


def check_default_uv(c, material, images):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "PRINCIPLED")
    c.texture("DefaultUV.base_color", entry.get("inputs", {}).get("base_color"),
              by_type(material.node_tree, "ShaderNodeTexImage")[0], images["a"])


def check_no_nodes(c, material):
    data = c.extension("materials", material.name)
    entry = surface(c, data, "DIFFUSE")
    c.expect("NoNodes.color", entry.get("inputs", {}).get("color"),
             list(material.diffuse_color)[:3])
    c.expect("NoNodes.roughness", entry.get("inputs", {}).get("roughness"), 0.0)


def check_unlinked(c, material):
    data = c.extension("materials", material.name)
    c.expect("Unlinked.surface", data.get("surface"), None)
    c.expect("Unlinked.nodes", data.get("nodes", []), [])


def accessor_uvs(c, index):
    """TEXCOORD data of accessor `index` as (u, v) float32 pairs, sorted."""
    accessor = c.gltf["accessors"][index]
    view = c.gltf["bufferViews"][accessor["bufferView"]]
    buffer = c.gltf["buffers"][view["buffer"]]
    with open(os.path.join(c.folder, urllib.parse.unquote(buffer["uri"])), "rb") as f:
        data = f.read()
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    stride = view.get("byteStride", 8)
    values = [np.frombuffer(data, np.float32, 2, start + i * stride)
              for i in range(accessor["count"])]
    return sorted((float(u), float(v)) for u, v in values)


def layer_uvs(layer):
    """A UV layer as the exporter writes it: v flipped (1 - v) in float32, one pair per loop."""
    uvs = np.empty(len(layer.data) * 2, dtype=np.float32)
    layer.data.foreach_get("uv", uvs)
    uvs = uvs.reshape(-1, 2)
    return sorted(set((float(u), float(np.float32(1.0) - v)) for u, v in uvs))


def check_meshes(c):
    """Which layer each TEXCOORD_n holds, measured from the data, is what uv_maps says."""
    measured = {}
    for mesh in c.gltf["meshes"]:
        blender_mesh = bpy.data.meshes[mesh["name"]]
        data = mesh.get("extensions", {}).get(EXTENSION, {})
        by_data = {tuple(layer_uvs(layer)): layer.name for layer in blender_mesh.uv_layers}
        attributes = mesh["primitives"][0]["attributes"]
        names = []
        for n in range(len(attributes)):
            if f"TEXCOORD_{n}" in attributes:
                uvs = tuple(sorted(set(accessor_uvs(c, attributes[f"TEXCOORD_{n}"]))))
                names.append(by_data.get(uvs, "(no layer)"))
        measured[mesh["name"]] = names
        c.expect(f"mesh '{mesh['name']}'.uv_maps (measured from TEXCOORD data)",
                 data.get("uv_maps"), names)
        active = next(l.name for l in blender_mesh.uv_layers if l.active_render)
        c.expect(f"mesh '{mesh['name']}'.active_render_uv_map", data.get("active_render_uv_map"),
                 active)
        for key in ("texspace_location", "texspace_size"):
            c.expect(f"mesh '{mesh['name']}'.{key}", data.get(key),
                     list(getattr(blender_mesh, key)))
    print("TEXCOORD_n holds, per mesh (measured):", json.dumps(measured))


def check_light_and_view(c, scene):
    light = bpy.data.objects["Panel"].data
    node = next(n for n in c.gltf["nodes"] if n.get("name") == "Panel")
    written = node.get("extensions", {}).get(EXTENSION, {}).get("light", {})
    for key, want in (("shape", light.shape), ("size_m", light.size), ("size_y_m", light.size_y),
                      ("spread_rad", light.spread), ("energy_w", light.energy)):
        c.expect(f"light Panel.{key}", written.get(key), want)
    written = c.gltf["scenes"][0].get("extensions", {}).get(EXTENSION, {})
    view = scene.view_settings
    for key, want in (("view_transform", view.view_transform), ("look", view.look),
                      ("exposure_stops", view.exposure), ("gamma", view.gamma),
                      ("display_device", scene.display_settings.display_device),
                      ("dither_intensity", scene.render.dither_intensity)):
        c.expect(f"scene.{key}", written.get(key), want)


def check_world(c, images):
    written = c.gltf["scenes"][0].get("extensions", {}).get(EXTENSION, {})
    sky = images["sky"]
    c.image_file("scene.world_hdr_uri", {"uri": written.get("world_hdr_uri"),
                                         "colorspace": sky.colorspace_settings.name,
                                         "alpha_mode": sky.alpha_mode}, sky)
    c.expect("the world's tex.png has a name no texture has",
             written.get("world_hdr_uri") in texture_uris(c.gltf["materials"]), False)


def texture_uris(value):
    """Every "uri" inside `value` (the materials' objects)."""
    if isinstance(value, dict):
        return {value["uri"]} if isinstance(value.get("uri"), str) else \
            set().union(*(texture_uris(v) for v in value.values()))
    if isinstance(value, list):
        return set().union(*(texture_uris(v) for v in value))
    return set()


def check(gltf_path, scene, materials, images):
    c = Checker(gltf_path)
    m = {material.name: material for material in materials}
    for material in materials:
        data = c.extension("materials", material.name)
        c.expect(f"{material.name}.blender_version", data.get("blender_version"),
                 list(bpy.app.version))
    check_all_inputs(c, m["AllInputs"])
    check_textured(c, m["Textured"], images)
    check_mix_glossy_diffuse(c, m["MixGlossyDiffuse"], images)
    check_add_shader(c, m["AddShader"])
    check_glass(c, m["Glass"])
    check_transparent_mix(c, m["TransparentMix"])
    check_grouped(c, m["Grouped"], images)
    check_toon(c, m["Toon"])
    check_shared(c, m["Shared"])
    check_object_coordinates(c, m["ObjectCoordinates"], images)
    check_fallbacks(c, m["Fallbacks"], images)
    check_in_export_folder(c, m["InExportFolder"], images)
    check_default_uv(c, m["DefaultUV"], images)
    check_no_nodes(c, m["NoNodes"])
    check_unlinked(c, m["Unlinked"])
    check_meshes(c)
    c.expect("glTF materials made of DefaultUV, on meshes of two active render UV maps",
             c.copies.get("DefaultUV"), 2)
    check_light_and_view(c, scene)
    check_world(c, images)
    print(f"compared {c.compared} values of {len(materials)} materials, the meshes, a light and "
          f"the view settings: {len(c.failures)} differ")
    return c.failures
