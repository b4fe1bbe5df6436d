"""Export a Blender shot to glTF with filmback's add-on active, for pipelines and tests.

    blender -b shot.blend --python importers/blender/export_shot.py -- out.gltf

From another bpy script (the tests in tests/blender/ do this):

    sys.path.insert(0, "<repo>/importers/blender")
    import export_shot
    export_shot.export("out.gltf")

The add-on is enabled from this folder for the session when it is not installed; Blender's own
glTF exporter writes the file, with cameras, lights, extras and modifiers unapplied (the
subdivision cage is carried instead, docs/blender.md).
"""

import os
import sys

import addon_utils
import bpy

ADDON = "io_filmback"
HERE = os.path.dirname(os.path.abspath(__file__))


def enable_addon():
    if ADDON in bpy.context.preferences.addons:
        return
    if HERE not in sys.path:
        sys.path.insert(0, HERE)
    addon_utils.enable(ADDON, default_set=True, handle_error=None)
    if ADDON not in bpy.context.preferences.addons:
        raise RuntimeError(f"could not enable the {ADDON} add-on from {HERE}")


def export(path, **options):
    """Writes `path` (.gltf with a .bin beside it, or .glb); `options` go to Blender's exporter."""
    enable_addon()
    from io_filmback.gltf_export import export_gltf
    export_gltf(path, **options)


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 1 or not args[0].endswith((".gltf", ".glb")):
        sys.stderr.write("usage: blender -b shot.blend --python export_shot.py -- out.gltf|out.glb\n")
        sys.exit(2)
    try:
        export(args[0])
    except Exception as e:  # noqa: BLE001 (a pipeline wants the message and a non-zero status)
        sys.stderr.write(f"export_shot.py: {e}\n")
        sys.exit(1)


if __name__ == "__main__":
    main()
