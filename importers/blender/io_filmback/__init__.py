"""filmback's Blender add-on: one glTF export carries the shot as Cycles renders it, and the
filmback render engine (render_engine.py) renders that export from inside Blender.

Hooks Blender's own glTF exporter (io_scene_gltf2's user extensions: an enabled add-on whose
module defines `glTF2ExportUserExtension` is called back while the file is gathered) and adds the
`FILMBACK_blender` extension (docs/blender.md, "What is carried") to cameras, lights, subdivided
meshes, materials, meshes' UV maps and the scene, and `EXT_camera_physical` (KhronosGroup/glTF pull
request 2608) to cameras, and `FILMBACK_deformation` (deformation.py) to the nodes of meshes
Blender deforms.

Blender 3.4.1's exporter calls the hooks with these arguments (io_scene_gltf2/blender/exp/, the
trailing `export_settings` always last); a hook's exception is printed and swallowed by the
exporter (io/exp/gltf2_io_user_extensions.py), so a failure shows as a missing extension.
- gather_scene_hook(scene, blender_scene): once per scene.
- gather_node_hook(node, blender_object): once per object.
- gather_mesh_hook(mesh, blender_mesh, blender_object, vertex_groups, modifiers, skip_filter,
  materials): once per glTF mesh (cached by mesh data, modifiers and materials).
- gather_material_hook(material, blender_material): once per glTF material, and the exporter
  makes one per Blender material *and* active render UV index of the meshes using it (its cache
  key), sometimes calling the hook twice on the same one: the extension is built once per Blender
  material and shared.
- gather_gltf_extensions_hook(gltf): after Blender's own image files are written, before the
  JSON is: the extension's images are written then (images.py).
"""

bl_info = {
    "name": "filmback glTF extensions",
    "author": "filmback",
    "version": (1, 2, 0),
    "blender": (3, 4, 0),
    "location": "File > Export > glTF 2.0; Render Properties > Render Engine > filmback",
    "description": "Adds Blender's physical camera, lights, world, render and colour "
                   "settings, material node trees and subdivision surfaces to glTF exports, "
                   "for filmback, and renders with filmback",
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
        self._images = None  # images.ImageFiles, made by the first hook that refers an image
        self.materials = {}  # Blender material pointer -> its extension object

    def _add(self, gltf_object, name, data):
        if gltf_object.extensions is None:
            gltf_object.extensions = {}
        gltf_object.extensions[name] = self.Extension(name=name, extension=data, required=False)

    def gather_scene_hook(self, gltf2_scene, blender_scene, export_settings):
        from . import shot
        self._add(gltf2_scene, EXTENSION,
                  shot.scene_extension(blender_scene, self.frame, self.images(export_settings)))

    def gather_material_hook(self, gltf2_material, blender_material, export_settings):
        from . import materials
        key = blender_material.as_pointer()
        if key not in self.materials:
            self.materials[key] = materials.material_extension(blender_material,
                                                               self.images(export_settings))
        self._add(gltf2_material, EXTENSION, self.materials[key])

    def gather_mesh_hook(self, gltf2_mesh, blender_mesh, blender_object, vertex_groups,
                         modifiers, skip_filter, materials, export_settings):
        from . import meshes
        data = meshes.mesh_extension(gltf2_mesh, blender_mesh)
        if data is not None:
            self._add(gltf2_mesh, EXTENSION, data)

    def _add_mesh_shapes(self, gltf2_node, blender_object, scene, data):
        """The path the mesh takes (deformation.py): Blender's evaluated deformation on the node,
        its evaluated mesh in place of the gathered one, or its subdivision cage in `data`; and
        the path in the exporter's report (Blender's console)."""
        from . import deformation, subdivision
        outcome = deformation.deformation_extension(blender_object, gltf2_node, scene,
                                                    self.frame)
        if outcome.extension is not None:
            self._add(gltf2_node, deformation.EXTENSION, outcome.extension)
        if outcome.cage:
            data["subdivision"] = subdivision.subdivision_extension(blender_object,
                                                                    gltf2_node.mesh)
        if outcome.path is not None:
            print(f"filmback: mesh object '{blender_object.name}': {outcome.path}")

    def images(self, export_settings):
        if self._images is None:
            from .images import ImageFiles
            self._images = ImageFiles([export_settings["gltf_filedirectory"],
                                       export_settings["gltf_texturedirectory"]])
        return self._images

    def gather_gltf_extensions_hook(self, gltf, export_settings):
        import os
        import urllib.parse
        folder = export_settings["gltf_filedirectory"]
        blender_files = [os.path.join(folder, urllib.parse.unquote(image.uri))
                         for image in (gltf.images or []) if isinstance(image.uri, str)]
        self.images(export_settings).write(folder, blender_files)

    def gather_node_hook(self, gltf2_node, blender_object, export_settings):
        if blender_object is None:
            return
        import bpy

        from . import camera, lights
        data = {}
        if blender_object.type == "CAMERA" and gltf2_node.camera is None and \
                blender_object.data.type == "PANO" and export_settings.get("gltf_cameras"):
            gltf2_node.camera = camera.panoramic_gltf_camera(blender_object, bpy.context.scene)
        if blender_object.type == "CAMERA" and gltf2_node.camera is not None:
            ours = camera.camera_extension(blender_object, bpy.context.scene, self.frame)
            self._add(gltf2_node.camera, EXTENSION, ours)
            physical = camera.ext_camera_physical(blender_object.data, ours["focal_length_mm"])
            if physical is not None:
                self._add(gltf2_node.camera, "EXT_camera_physical", physical)
        elif blender_object.type == "LIGHT":
            data["light"] = lights.light_extension(blender_object.data)
        elif blender_object.type == "MESH" and not export_settings.get("gltf_apply"):
            # With Apply Modifiers the exported mesh is already evaluated: no cage to carry.
            self._add_mesh_shapes(gltf2_node, blender_object, bpy.context.scene, data)
        if data:
            self._add(gltf2_node, EXTENSION, data)


def register():
    from . import render_engine, render_settings
    render_settings.register()
    render_engine.register()


def unregister():
    from . import render_engine, render_settings
    render_engine.unregister()
    render_settings.unregister()
