"""The object's modifiers as Cycles' render evaluates them, for the add-on's own evaluations of
the depsgraph (deformation.py, subdivision.py).

Python gets only the viewport's depsgraph (bpy.context.evaluated_depsgraph_get; Blender 3.4 has
no Python call that builds one in render mode), where a modifier counts when shown in the
viewport and a Subdivision Surface or Multiresolution refines to its viewport levels. While
`as_rendered` is active each modifier is shown in the viewport exactly when it is shown in
renders and refines to its render levels; everything is put back afterwards. What the render
mode changes elsewhere (geometry nodes' Is Viewport, particle display amounts, simplify's
separate limits) is not carried.
"""

import contextlib

import bpy

# Modifiers with separate viewport and render levels: (viewport property, render property).
LEVELS = {"SUBSURF": ("levels", "render_levels"), "MULTIRES": ("levels", "render_levels")}


@contextlib.contextmanager
def as_rendered(obj):
    saved = []
    try:
        for m in obj.modifiers:
            saved.append((m, "show_viewport", m.show_viewport))
            if m.show_viewport != m.show_render:
                m.show_viewport = m.show_render
            viewport, render = LEVELS.get(m.type, (None, None))
            if viewport is not None and getattr(m, viewport) != getattr(m, render):
                saved.append((m, viewport, getattr(m, viewport)))
                setattr(m, viewport, getattr(m, render))
        yield
    finally:
        for m, name, value in reversed(saved):
            if getattr(m, name) != value:
                setattr(m, name, value)
        bpy.context.evaluated_depsgraph_get()
