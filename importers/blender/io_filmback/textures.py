"""An Image Texture node as the extension's texture T: its image, UV map and uv_transform.

The texture coordinate chain behind the node's Vector input is followed through UV Map, Texture
Coordinate (its UV output) and Mapping nodes; the Mappings compose into one affine map of Blender
UV space, written in glTF's texture space (below). Anything else on the chain is a warning, and
the texture then uses the mesh's active render UV map untransformed.
"""

import math

from . import images, node_links

IDENTITY = ([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], [0.0, 0.0, 0.0])


def texture(node, path, context):
    """(T, None) for Image Texture `node` at group path `path`, or (None, why) when it cannot be
    carried. `context` gives `warn(node, path, text)` for what is carried only in part, and
    `images` (an images.ImageFiles)."""
    image = node.image
    if image is None:
        return None, "it has no image"
    reason = images.problem(image)
    if reason is not None:
        return None, f"its image '{image.name}' {reason}"
    if node.projection != "FLAT":
        context.warn(node, path, f"projection {node.projection} is not carried; rendered FLAT")
    if not _is_identity(node.texture_mapping):
        context.warn(node, path, "its Texture Mapping (node sidebar) is not carried")
    uv_map, (a, offset) = uv_source(node, path, context)
    out = {"uv_map": uv_map, "uv_transform": gltf_uv_transform(a, offset),
           "extension": node.extension, "interpolation": node.interpolation,
           "colorspace": images.file_colorspace(image),
           "alpha_mode": images.file_alpha_mode(image)}
    context.images.refer(image, out, "uri")
    return out, None


def uv_source(node, path, context):
    """(uv_map, (A, b)): the UV map ("" for the mesh's active render one) and the composed
    Mapping, an affine map p -> A p + b of Blender's (u, v, 0) UV vector, whose x and y address
    the image."""
    owner, socket = node, node.inputs["Vector"]
    if node_links.active_link(socket) is None:
        return "", IDENTITY  # Cycles links an unlinked image Vector to the active render UV map
    total = IDENTITY
    for _ in range(node_links.MAX_HOPS):
        src = node_links.source(socket, path)
        if isinstance(src, node_links.Constant):
            context.warn(owner, path, "has a constant texture coordinate (its Vector input is "
                                      "not linked): not carried; the active render UV map is used")
            return "", IDENTITY
        source_node, path = src.node, src.path
        if source_node.type == "UVMAP":
            if source_node.from_instancer:
                context.warn(source_node, path, "From Instancer is not carried")
            return source_node.uv_map, total
        if source_node.type == "TEX_COORD" and src.socket.identifier == "UV":
            if source_node.from_instancer:
                context.warn(source_node, path, "From Instancer is not carried")
            return "", total
        if source_node.type == "MAPPING" and source_node.vector_type != "NORMAL":
            total = _compose(total, mapping_affine(source_node, path, context))
            owner, socket = source_node, source_node.inputs["Vector"]
            continue
        what = "of type NORMAL (not affine)" if source_node.type == "MAPPING" else \
            f"(output {src.socket.name})"
        context.warn(source_node, path,
                     f"{what} on '{owner.name}'.Vector is not carried: the texture of "
                     f"'{node.name}' uses the active render UV map, untransformed")
        return "", IDENTITY
    raise ValueError(f"texture coordinates of '{node.name}' pass more than "
                     f"{node_links.MAX_HOPS} Mapping nodes")


def mapping_affine(node, path, context):
    """A Mapping node (POINT, TEXTURE or VECTOR) as (A, b), Cycles' svm_mapping
    (intern/cycles/kernel/svm/mapping_util.h):
      POINT   R (S * v) + L            TEXTURE  (R^T (v - L)) / S (x / 0 = 0)
      VECTOR  R (S * v)
    with R the XYZ Euler rotation Rz Ry Rx (util/transform.h, euler_to_transform)."""
    location = _constant_input(node, "Location", path, context) \
        if node.inputs["Location"].enabled else [0.0, 0.0, 0.0]
    r = euler_xyz(_constant_input(node, "Rotation", path, context))
    scale = _constant_input(node, "Scale", path, context)
    if node.vector_type == "TEXTURE":
        inverse_scale = [1.0 / s if s != 0.0 else 0.0 for s in scale]
        a = [[inverse_scale[i] * r[j][i] for j in range(3)] for i in range(3)]
        return a, [-sum(a[i][j] * location[j] for j in range(3)) for i in range(3)]
    a = [[r[i][j] * scale[j] for j in range(3)] for i in range(3)]
    return a, (location if node.vector_type == "POINT" else [0.0, 0.0, 0.0])


def euler_xyz(angles):
    cx, cy, cz = (math.cos(t) for t in angles)
    sx, sy, sz = (math.sin(t) for t in angles)
    return [[cy * cz, sy * sx * cz - cx * sz, sy * cx * cz + sx * sz],
            [cy * sz, sy * sx * sz + cx * cz, sy * cx * sz - sx * cz],
            [-sy, cy * sx, cy * cx]]


def gltf_uv_transform(a, b):
    """[a, b, c, d, e, f] with s = a u + b v + c, t = d u + e v + f in glTF texture space, from
    the Blender-space affine map (A, b). glTF's v runs down the image, Blender's up: v_gltf =
    1 - v_blender on both sides (the exporter writes TEXCOORD so, and the lookup flips back), so
    the map is F M F with F(u, v) = (u, 1 - v):
      s = A00 u - A01 v + (A01 + b0)
      t = -A10 u + A11 v + (1 - A11 - b1)."""
    return [a[0][0], -a[0][1], a[0][1] + b[0], -a[1][0], a[1][1], 1.0 - a[1][1] - b[1]]


def _compose(outer, inner):
    """outer after inner: p -> Ao (Ai p + bi) + bo."""
    (ao, bo), (ai, bi) = outer, inner
    a = [[sum(ao[i][k] * ai[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    return a, [sum(ao[i][k] * bi[k] for k in range(3)) + bo[i] for i in range(3)]


def _constant_input(node, name, path, context):
    socket = node.inputs[name]
    src = node_links.source(socket, path)
    if isinstance(src, node_links.Constant):
        return src.value
    value = node_links.socket_value(socket)
    context.warn(src.node, src.path, f"on '{node.name}'.{name} is not carried; its input's value "
                                     f"{format_value(value)} is used")
    return value


def _is_identity(mapping):
    return tuple(mapping.translation) == (0.0, 0.0, 0.0) and \
        tuple(mapping.rotation) == (0.0, 0.0, 0.0) and tuple(mapping.scale) == (1.0, 1.0, 1.0) \
        and (mapping.mapping_x, mapping.mapping_y, mapping.mapping_z) == ("X", "Y", "Z") and \
        not mapping.use_min and not mapping.use_max


def format_value(value):
    if isinstance(value, list):
        return "(" + ", ".join(f"{v:.6g}" for v in value) + ")"
    return f"{value:.6g}"
