"""What the filmback render engine is told: the add-on's preference (where filmback is), the
scene's render settings (`scene.filmback`) and their panel in Render Properties."""

import subprocess

import bpy

from . import filmback_cli

ENGINE_ID = "FILMBACK"


def addon_preferences(context):
    return context.preferences.addons[__package__].preferences


def executable(context):
    return filmback_cli.find_executable(addon_preferences(context).filmback_path)


class FilmbackPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    filmback_path: bpy.props.StringProperty(
        name="filmback",
        description="The filmback executable; empty: `filmback` found on PATH",
        subtype="FILE_PATH")

    def draw(self, context):
        self.layout.prop(self, "filmback_path")
        found = filmback_cli.find_executable(self.filmback_path)
        self.layout.label(text=f"using {found}" if found else "filmback not found",
                          icon="NONE" if found else "ERROR")


class FilmbackSceneSettings(bpy.types.PropertyGroup):
    samples: bpy.props.IntProperty(name="Samples", description="Samples per pixel (--spp)",
                                   default=16, min=1, max=1_000_000)  # filmback's --spp range
    sampler: bpy.props.EnumProperty(
        name="Sampler", description="How sample values are drawn (--sampler)",
        items=[(name, name, "") for name in filmback_cli.SAMPLERS])
    # Free text, not a list: a plugin takes parameters (`path:max_depth=4`) and a plugin path
    # may hold plugins this Blender session has not listed.
    integrator: bpy.props.StringProperty(
        name="Integrator", description="Integrator plugin spec (--integrator); empty: path")
    filter: bpy.props.StringProperty(
        name="Filter",
        description="Pixel filter plugin spec (--filter); empty: the scene's Film > Pixel Filter")


class FILMBACK_PT_render_settings(bpy.types.Panel):  # noqa: N801 (Blender's naming)
    bl_label = "filmback"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {ENGINE_ID}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        settings = context.scene.filmback
        layout = self.layout
        for name in ("samples", "sampler", "integrator", "filter"):
            layout.prop(settings, name)
        found = executable(context)
        if found is None:
            layout.label(text="filmback not found: set its path in the add-on's preferences",
                         icon="ERROR")
            return
        try:
            plugins = filmback_cli.plugin_names(found)
        except (OSError, RuntimeError, subprocess.SubprocessError) as e:
            layout.label(text=f"`filmback plugins` failed: {e}", icon="ERROR")
            return
        for kind in ("integrator", "filter"):
            layout.label(text=f"{kind}s: {', '.join(plugins.get(kind, [])) or 'none found'}")


# Blender's own panels that show for any engine listing them; the Output and Dimensions panels
# (Format, Frame Range, Output) are the ones a filmback render reads.
COMPATIBLE_PANELS = ("RENDER_PT_format", "RENDER_PT_frame_range", "RENDER_PT_output",
                     "RENDER_PT_color_management", "RENDER_PT_stamp")

CLASSES = (FilmbackPreferences, FilmbackSceneSettings, FILMBACK_PT_render_settings)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.filmback = bpy.props.PointerProperty(type=FilmbackSceneSettings)
    for name in COMPATIBLE_PANELS:
        panel = getattr(bpy.types, name, None)
        if panel is not None and hasattr(panel, "COMPAT_ENGINES"):
            panel.COMPAT_ENGINES.add(ENGINE_ID)


def unregister():
    for name in COMPATIBLE_PANELS:
        panel = getattr(bpy.types, name, None)
        if panel is not None and hasattr(panel, "COMPAT_ENGINES"):
            panel.COMPAT_ENGINES.discard(ENGINE_ID)
    del bpy.types.Scene.filmback
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
