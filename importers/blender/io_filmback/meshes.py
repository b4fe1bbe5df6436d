"""Which UV map each TEXCOORD_n of an exported mesh holds (the mesh's FILMBACK_blender object).

Blender 3.4's exporter writes TEXCOORD_n from uv_layers[n], every layer in the mesh's order,
whether or not a material uses it (gltf2_blender_gather_primitives_extract.py; measured by
tests/blender/material_export_test.py): the names are read from the layers, as many as the
primitives have TEXCOORD attributes.
"""


def mesh_extension(gltf_mesh, blender_mesh):
    """{"uv_maps": [...], "active_render_uv_map": name}, or None for a mesh without UV maps."""
    layers = blender_mesh.uv_layers
    if len(layers) == 0:
        return None
    count = max((sum(1 for name in p.attributes if name.startswith("TEXCOORD_"))
                 for p in gltf_mesh.primitives), default=0)
    active = next((layer.name for layer in layers if layer.active_render), layers[0].name)
    return {"uv_maps": [layers[i].name for i in range(min(count, len(layers)))],
            "active_render_uv_map": active}
