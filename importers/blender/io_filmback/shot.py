"""Blender's render settings and world as the scene's FILMBACK_blender extension."""

import os

from . import images

# Samples of the shutter curve written, uniformly spaced over the open shutter.
SHUTTER_CURVE_SAMPLES = 65


def scene_extension(scene, frame, image_files):
    """The scene's object; the world's image is referred to `image_files` (images.ImageFiles)."""
    r = scene.render
    out = {
        "resolution_x_px": r.resolution_x * r.resolution_percentage // 100,
        "resolution_y_px": r.resolution_y * r.resolution_percentage // 100,
        "resolution_percentage": r.resolution_percentage,
        "pixel_aspect_x": r.pixel_aspect_x,
        "pixel_aspect_y": r.pixel_aspect_y,
        "fps": r.fps,
        "fps_base": r.fps_base,
        "frame": frame,
        "frame_start": scene.frame_start,
        "frame_end": scene.frame_end,
    }
    out.update(view_settings(scene))
    if r.use_motion_blur:
        out.update(shutter(scene))
    cycles = getattr(scene, "cycles", None)
    if cycles is not None:
        out.update({
            "filter_type": cycles.pixel_filter_type,
            "filter_width_px": cycles.filter_width,
            "film_exposure": cycles.film_exposure,
            "samples": cycles.samples,
            "use_adaptive_sampling": cycles.use_adaptive_sampling,
            "adaptive_threshold": cycles.adaptive_threshold,
            "adaptive_min_samples": cycles.adaptive_min_samples,
            "max_bounces": cycles.max_bounces,
            "diffuse_bounces": cycles.diffuse_bounces,
            "glossy_bounces": cycles.glossy_bounces,
            "transmission_bounces": cycles.transmission_bounces,
        })
    out.update(world(scene, image_files, out))
    return out


def view_settings(scene):
    """Colour Management as Blender applies it to what it shows and to 8-bit files: view
    transform, look (the OCIO look's name, "None" for none), exposure in stops, gamma, display,
    and the dither noise it adds when quantising. The OCIO config is Blender's own unless $OCIO
    names another, as Blender reads it at start-up (colormanagement.c)."""
    view = scene.view_settings
    out = {"view_transform": view.view_transform, "look": view.look,
           "exposure_stops": view.exposure, "gamma": view.gamma,
           "display_device": scene.display_settings.display_device,
           "dither_intensity": scene.render.dither_intensity}
    config = os.environ.get("OCIO")
    if config:
        out["color_management_config"] = config
    return out


def shutter(scene):
    """Open and close times in seconds relative to the frame's time, and the curve's weights.
    Seconds on the file's timeline, frame / fps: Blender's exporter times animation keys so,
    leaving fps_base out, and the shutter must meet the keys where Blender's frames do."""
    r = scene.render
    length = r.motion_blur_shutter / r.fps
    # Cycles' setting (scene.cycles); Eevee always centres the shutter on the frame.
    position = getattr(getattr(scene, "cycles", None), "motion_blur_position", "CENTER")
    start = {"START": 0.0, "CENTER": -0.5, "END": -1.0}[position] * length
    mapping = r.motion_blur_shutter_curve
    mapping.initialize()
    curve = mapping.curves[0]
    n = SHUTTER_CURVE_SAMPLES
    out = {"shutter_open_s": start, "shutter_close_s": start + length,
           "shutter_curve": [mapping.evaluate(curve, i / (n - 1)) for i in range(n)]}
    # Cycles' rolling shutter (rows read top to bottom), with motion blur only, as Cycles.
    rolling = getattr(getattr(scene, "cycles", None), "rolling_shutter_type", "NONE")
    if rolling != "NONE":
        out["rolling_shutter_type"] = rolling
        out["rolling_shutter_duration"] = scene.cycles.rolling_shutter_duration
    return out


def world(scene, image_files, holder):
    """The world's Background colour and strength; an Environment Texture's image is written
    next to the exported file and named by a relative URI, holder["world_hdr_uri"], once the
    export ends (images.py)."""
    w = scene.world
    if w is None:
        return {"world_color": [0.0, 0.0, 0.0], "world_strength": 0.0}
    if not w.use_nodes:
        return {"world_color": list(w.color), "world_strength": 1.0}
    output = next((n for n in w.node_tree.nodes
                   if n.type == "OUTPUT_WORLD" and n.is_active_output), None)
    links = output.inputs["Surface"].links if output is not None else []
    if not links or links[0].from_node.type != "BACKGROUND":
        return {"world_color": [0.0, 0.0, 0.0], "world_strength": 0.0, "world_unsupported": True}
    background = links[0].from_node
    out = {"world_color": list(background.inputs["Color"].default_value)[:3],
           "world_strength": background.inputs["Strength"].default_value}
    colour_links = background.inputs["Color"].links
    if colour_links and colour_links[0].from_node.type == "TEX_ENVIRONMENT":
        image = colour_links[0].from_node.image
        reason = images.problem(image) if image is not None else None
        if image is not None and reason is None:
            image_files.refer(image, holder, "world_hdr_uri")
            out["world_color"] = [1.0, 1.0, 1.0]
        elif image is not None:
            out["world_unsupported"] = True
            print(f"filmback: world '{w.name}': image '{image.name}' {reason}")
    elif colour_links:
        out["world_unsupported"] = True
    return out

