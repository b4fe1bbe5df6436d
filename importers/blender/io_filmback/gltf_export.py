"""One way to write a shot for filmback: Blender's glTF exporter with the settings filmback reads
(cameras, lights, custom properties, modifiers unapplied so that a subdivision surface travels as
its cage), with this add-on's hooks carrying the rest. export_shot.py and the render engine both
export through it, so that an F12 render and a command-line render of an export are the same
render."""

import os

import bpy


def export_gltf(path, **options):
    """Writes `path` (.gltf with a .bin beside it, or .glb); `options` go to Blender's exporter."""
    settings = dict(export_format="GLB" if path.endswith(".glb") else "GLTF_SEPARATE",
                    export_cameras=True, export_lights=True, export_extras=True,
                    export_apply=False, export_yup=True)
    settings.update(options)
    result = bpy.ops.export_scene.gltf(filepath=os.path.abspath(path), **settings)
    if result != {"FINISHED"}:
        raise RuntimeError(f"Blender's glTF exporter did not finish: {result}")
