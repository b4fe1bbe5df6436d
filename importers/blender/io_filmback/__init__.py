"""filmback's Blender add-on: one glTF export carries the shot as Cycles renders it.

Hooks Blender's own glTF exporter (io_scene_gltf2's user extensions: an enabled add-on whose
module defines `glTF2ExportUserExtension` is called back while the file is gathered) and adds the
`FILMBACK_blender` extension (docs/blender.md, "What is carried") to cameras, lights, subdivided
meshes and the scene, and `EXT_camera_physical` (KhronosGroup/glTF pull request 2608) to cameras.
"""

bl_info = {
    "name": "filmback glTF extensions",
    "author": "filmback",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Export > glTF 2.0",
    "description": "Adds Blender's physical camera, lights, world, render settings and "
                   "subdivision surfaces to glTF exports, for filmback",
    "category": "Import-Export",
}

EXTENSION = "FILMBACK_blender"


class glTF2ExportUserExtension:  # noqa: N801 (the name Blender's exporter looks for)
    def __init__(self):
        # Built when the export starts, before the exporter steps through frames to sample
        # animation: the frame the user is on is the shot's frame.
        import bpy
        from io_scene_gltf2.io.com.gltf2_io_extensions import Extension
        self.Extension = Extension
        self.frame = bpy.context.scene.frame_current

    def _add(self, gltf_object, name, data):
        if gltf_object.extensions is None:
            gltf_object.extensions = {}
        gltf_object.extensions[name] = self.Extension(name=name, extension=data, required=False)

    def gather_scene_hook(self, gltf2_scene, blender_scene, export_settings):
        from . import shot
        self._add(gltf2_scene, EXTENSION,
                  shot.scene_extension(blender_scene, self.frame, export_settings))

    def gather_node_hook(self, gltf2_node, blender_object, export_settings):
        if blender_object is None:
            return
        import bpy

        from . import camera, lights, subdivision
        data = {}
        if blender_object.type == "CAMERA" and gltf2_node.camera is not None:
            self._add(gltf2_node.camera, EXTENSION,
                      camera.camera_extension(blender_object, bpy.context.scene, self.frame))
            physical = camera.ext_camera_physical(blender_object.data)
            if physical is not None:
                self._add(gltf2_node.camera, "EXT_camera_physical", physical)
        elif blender_object.type == "LIGHT":
            data["light"] = lights.light_extension(blender_object.data)
        elif blender_object.type == "MESH" and not export_settings.get("gltf_apply"):
            # With Apply Modifiers the exported mesh is already subdivided: no cage to carry.
            surface = subdivision.subdivision_extension(blender_object)
            if surface is not None:
                data["subdivision"] = surface
        if data:
            self._add(gltf2_node, EXTENSION, data)


def register():
    pass


def unregister():
    pass
