"""A Blender material's node tree as the FILMBACK_blender material extension (docs/blender.md,
"What is carried" > "Materials").

The tree is walked from the Surface input of the output node Cycles uses
(`get_output_node('CYCLES')`) as Cycles 3.4 builds its shader graph (node_links.py): shader nodes
of the table below become entries of "nodes", linked by index, each once; their inputs become
constants, textures or normal maps. What is not carried is said in "warnings", each naming the
material and the node, and printed to Blender's console.
"""

import bpy

from . import node_links, textures
from .textures import format_value

# Shader nodes carried as they are: Blender node type -> extension type. Mix and Add have shader
# sockets instead of (or beside) inputs.
CARRIED = {"BSDF_PRINCIPLED": "PRINCIPLED", "BSDF_DIFFUSE": "DIFFUSE", "BSDF_GLOSSY": "GLOSSY",
           "BSDF_GLASS": "GLASS", "EMISSION": "EMISSION", "BSDF_TRANSPARENT": "TRANSPARENT",
           "MIX_SHADER": "MIX_SHADER", "ADD_SHADER": "ADD_SHADER"}

# Shader nodes replaced by the closest carried one: Blender type -> (extension type, which of
# its inputs go into the replacement's). Any other shader with a Color input becomes a DIFFUSE
# of it; one without renders nothing.
CLOSEST = {
    "BSDF_REFRACTION": ("GLASS", ("Color", "Roughness", "IOR", "Normal")),
    "BSDF_ANISOTROPIC": ("GLOSSY", ("Color", "Roughness", "Normal")),
}
DIFFUSE_FROM = ("Color", "Normal")

# Shader nodes that render nothing on a surface in Cycles 3.4 (volumes, holdout, and Eevee's
# Specular, which Cycles has no node for), or whose closure is not a surface's.
NOTHING = {"PRINCIPLED_VOLUME", "VOLUME_ABSORPTION", "VOLUME_SCATTER", "HOLDOUT",
           "EEVEE_SPECULAR", "BACKGROUND", "SCRIPT"}

# Vector inputs that take a normal or tangent: absent when unlinked (Cycles then uses the
# surface's own), otherwise a normal map.
NORMAL_INPUTS = ("Normal", "Clearcoat Normal", "Tangent")

# Separate nodes' outputs -> the image channel they select.
CHANNELS = {"SEPRGB": {"R": "R", "G": "G", "B": "B"},
            "SEPARATE_COLOR": {"Red": "R", "Green": "G", "Blue": "B"},
            "SEPXYZ": {"X": "R", "Y": "G", "Z": "B"}}


def material_extension(material, image_files):
    """The extension object of `material`; images are referred to `image_files`
    (images.ImageFiles)."""
    walk = _Walk(material, image_files)
    out = {"blender_version": list(bpy.app.version)}
    if not material.use_nodes or material.node_tree is None:
        # Cycles renders a material without nodes as a Diffuse BSDF of its viewport colour
        # (intern/cycles/blender/shader.cpp, sync_materials).
        out["surface"] = walk.add({"type": "DIFFUSE", "name": "", "inputs": {
            "color": list(material.diffuse_color)[:3], "roughness": 0.0}})
    else:
        output = material.node_tree.get_output_node("CYCLES")
        if output is not None:
            surface = walk.shader(output.inputs["Surface"], ())
            if surface is not None:
                out["surface"] = surface
    out["nodes"] = walk.nodes
    if walk.warnings:
        out["warnings"] = walk.warnings
    return out


def label(node, path):
    """A node's name for messages: inside groups, the group nodes' names first."""
    return " > ".join(f"'{n.name}'" for n in path + (node,))


def key_name(socket):
    """The extension's key for an input: its identifier in snake case ('Base Color' ->
    'base_color')."""
    return socket.identifier.lower().replace(" ", "_")


class _Walk:
    def __init__(self, material, image_files):
        self.material = material
        self.images = image_files
        self.nodes = []
        self.warnings = []
        self._index = {}

    def warn(self, node, path, text):
        message = f"material '{self.material.name}': node {label(node, path)} ({node.type}) {text}"
        if message not in self.warnings:
            self.warnings.append(message)
            print(f"filmback: {message}")

    def add(self, entry):
        self.nodes.append(entry)
        return len(self.nodes) - 1

    # Shaders

    def shader(self, socket, path):
        """The index of the node feeding shader socket `socket`, or None (no closure)."""
        src = node_links.source(socket, path)
        if isinstance(src, node_links.Constant):
            if src.value is None:
                return None  # unlinked: no closure
            # An RGB or Value node into a shader socket: Cycles' Emission of it (below).
            colour = src.value if isinstance(src.value, list) else [src.value] * 3
            return self.add({"type": "EMISSION", "name": "", "inputs": {"color": colour,
                                                                       "strength": 1.0}})
        key = (tuple(n.as_pointer() for n in src.path), src.node.as_pointer(),
               src.socket.identifier)
        if key not in self._index:
            # An entry is added before its inputs are walked (the surface is node 0); a node
            # reached again (a shared sub-tree) finds its index. None marks a node being walked,
            # so that a cycle (Blender marks its links invalid anyway) ends.
            self._index[key] = None
            self._index[key] = self._shader_entry(src)
        return self._index[key]

    @staticmethod
    def _linked(index):
        return -1 if index is None else index

    def _shader_entry(self, src):
        node, path = src.node, src.path
        name = " > ".join(n.name for n in path + (node,))
        if src.socket.type != "SHADER":
            # Cycles turns a colour or value linked into a shader socket into an Emission of it
            # at strength 1 (ShaderGraph::connect).
            index = self.add({"type": "EMISSION", "name": name})
            self.nodes[index]["inputs"] = {"color": self._value_from(src, "RGBA", name),
                                           "strength": 1.0}
            return index
        kind = CARRIED.get(node.type)
        if kind is not None:
            return self._carried(kind, node, path, name)
        if node.type in NOTHING:
            self.warn(node, path, "is not carried: it renders nothing on a surface here")
            return None
        kind, inputs = CLOSEST.get(node.type, ("DIFFUSE", DIFFUSE_FROM))
        if kind == "DIFFUSE" and "Color" not in node.inputs:
            self.warn(node, path, "is not carried and has no Color: rendered as nothing")
            return None
        self.warn(node, path, f"is not carried; rendered as the closest, {kind} of its "
                              f"{', '.join(n for n in inputs if n in node.inputs)}")
        index = self.add({"type": kind, "name": name})
        entry = self.nodes[index]
        distribution = getattr(node, "distribution", None)
        if kind != "DIFFUSE" and distribution is not None:
            entry["distribution"] = distribution
        entry["inputs"] = self._inputs(node, path, [node.inputs[n] for n in inputs
                                                    if n in node.inputs])
        if kind == "DIFFUSE":
            entry["inputs"].setdefault("roughness", 0.0)
        return index

    def _carried(self, kind, node, path, name):
        index = self.add({"type": kind, "name": name})
        entry = self.nodes[index]
        if kind == "PRINCIPLED":
            entry["distribution"] = node.distribution
            entry["subsurface_method"] = node.subsurface_method
        elif kind in ("GLOSSY", "GLASS"):
            entry["distribution"] = node.distribution
        values = [s for s in node.inputs if s.enabled and s.type != "SHADER"]
        if values:
            entry["inputs"] = self._inputs(node, path, values)
        shaders = [s for s in node.inputs if s.type == "SHADER"]
        if shaders:
            # -1: an unlinked socket (JSON null would not survive: glTF readers such as
            # tinygltf drop nulls from arrays, which moves the next index into its place).
            entry["shaders"] = [self._linked(self.shader(s, path)) for s in shaders]
        return index

    # Inputs

    def _inputs(self, node, path, sockets):
        out = {}
        for socket in sockets:
            if socket.identifier in NORMAL_INPUTS and socket.type == "VECTOR":
                value = self._normal(node, socket, path)
            else:
                where = f"{label(node, path)}.{socket.name}"
                value = self._value_from(node_links.source(socket, path), socket.type, where,
                                         socket)
            if value is not None:
                out[key_name(socket)] = value
        return out

    def _value_from(self, src, target_type, where, target=None):
        """The value of an input of type `target_type` fed by `src`; what is not carried falls
        back to `target`'s own value (or black) with a warning."""
        if isinstance(src, node_links.Constant):
            return src.value
        fallback = node_links.socket_value(target) if target is not None else \
            node_links.zero(target_type)
        node = src.node
        if node.type == "TEX_IMAGE":
            value, why = self._texture_output(src)
        elif node.type in CHANNELS:
            value, why = self._channel(src)
        else:
            value, why = None, ""
        if value is None:
            self.warn(node, src.path, f"on {where} is not carried{why and ' (' + why + ')'}; "
                                      f"its input's value {format_value(fallback)} is used")
            return fallback
        if src.narrowed and target_type != "VALUE":
            self.warn(node, src.path, f"on {where} passes a float socket: Cycles takes its "
                                      f"luminance there, the extension carries its colour")
        return value

    def _texture_output(self, src):
        texture, why = textures.texture(src.node, src.path, self)
        if texture is None:
            return None, why
        return {"texture": texture, "output": src.socket.identifier}, None

    def _channel(self, src):
        separate = src.node
        if separate.type == "SEPARATE_COLOR" and separate.mode != "RGB":
            return None, f"mode {separate.mode}"
        channel = CHANNELS[separate.type][src.socket.identifier]
        image = node_links.source(separate.inputs[0], src.path)
        if isinstance(image, node_links.Constant) or image.node.type != "TEX_IMAGE":
            return None, "only an Image Texture's channels are carried"
        value, why = self._texture_output(image)
        if value is not None and value["output"] == "Color":
            value["channel"] = channel  # an Alpha output's channels are all the alpha
        return value, why

    def _normal(self, node, socket, path):
        """A normal input: a normal map, or None (the surface's own normal)."""
        src = node_links.source(socket, path)
        if isinstance(src, node_links.Constant):
            return None
        where = f"{label(node, path)}.{socket.name}"
        normal_map = src.node
        if normal_map.type != "NORMAL_MAP":
            self.warn(normal_map, src.path, f"on {where} is not carried; the surface's own "
                                            f"normal is used")
            return None
        colour = node_links.source(normal_map.inputs["Color"], src.path)
        texture, why = (None, "its Color is not an Image Texture's Color")
        if isinstance(colour, node_links.Output) and colour.node.type == "TEX_IMAGE" and \
                colour.socket.identifier == "Color":
            texture, why = textures.texture(colour.node, colour.path, self)
        if texture is None:
            self.warn(normal_map, src.path, f"on {where} is not carried ({why}); the surface's "
                                            f"own normal is used")
            return None
        if normal_map.space != "TANGENT":
            self.warn(normal_map, src.path, f"space {normal_map.space} is not carried; "
                                            f"rendered as TANGENT")
        strength = normal_map.inputs["Strength"]
        strength_source = node_links.source(strength, src.path)
        if isinstance(strength_source, node_links.Constant):
            strength_value = strength_source.value
        else:
            strength_value = node_links.socket_value(strength)
            self.warn(strength_source.node, strength_source.path,
                      f"on {label(normal_map, src.path)}.Strength is not carried; its input's "
                      f"value {format_value(strength_value)} is used")
        return {"normal_map": {"texture": texture, "strength": strength_value,
                               "space": normal_map.space, "uv_map": normal_map.uv_map}}
