"""Which UV map each TEXCOORD_n of an exported mesh holds, and its texture space (the mesh's
FILMBACK_blender object).

Blender 3.4's exporter writes TEXCOORD_n from uv_layers[n], every layer in the mesh's order,
whether or not a material uses it (gltf2_blender_gather_primitives_extract.py; measured by
tests/blender/material_export_test.py): the names are read from the layers, as many as the
primitives have TEXCOORD attributes.

The texture space (Blender's object axes, unconverted) is what Cycles derives Generated texture
coordinates from, and with them the default tangent of anisotropic closures: radial about the
object's Z axis (svm_node_tangent, ShaderGraph's default Tangent input).
"""


def mesh_extension(gltf_mesh, blender_mesh):
    """{"uv_maps": [...], "active_render_uv_map": name, "texspace_location": [x, y, z],
    "texspace_size": [x, y, z]}; no UV map entries for a mesh without UV maps."""
    out = {"texspace_location": list(blender_mesh.texspace_location),
           "texspace_size": list(blender_mesh.texspace_size)}
    layers = blender_mesh.uv_layers
    if len(layers) == 0:
        return out
    count = max((sum(1 for name in p.attributes if name.startswith("TEXCOORD_"))
                 for p in gltf_mesh.primitives), default=0)
    active = next((layer.name for layer in layers if layer.active_render), layers[0].name)
    out.update({"uv_maps": [layers[i].name for i in range(min(count, len(layers)))],
                "active_render_uv_map": active})
    return out
