"""A Blender camera as the FILMBACK_blender camera extension and as EXT_camera_physical."""

from mathutils import Vector

# Frames over which varying lens values are written, at most: a bound on the file's size.
MAX_TRACK_FRAMES = 100000


def camera_extension(obj, scene, frame):
    """Every physical value of the camera at `frame`, in Blender's units (mm, f-number, metres,
    radians)."""
    cam = obj.data
    out = {
        "sensor_width_mm": cam.sensor_width,
        "sensor_height_mm": cam.sensor_height,
        "sensor_fit": cam.sensor_fit.lower(),
        "clip_near_m": cam.clip_start,
        "clip_far_m": cam.clip_end,
    }
    # Evaluated at `frame`: Blender's glTF exporter steps through frames for animation.
    out.update(at_frame(scene, frame, lambda: lens_values(obj)))
    if cam.type == "ORTHO":
        out["ortho_scale_m"] = cam.ortho_scale
    elif cam.type == "PANO":
        out["panoramic_unsupported"] = True
    dof = cam.dof
    if dof.use_dof:
        out["aperture_blades"] = dof.aperture_blades
        out["aperture_rotation_rad"] = dof.aperture_rotation
        out["aperture_ratio"] = dof.aperture_ratio
    per_frame = lens_per_frame(obj, scene)
    if per_frame is not None:
        out["per_frame"] = per_frame
    return out


def ext_camera_physical(cam, lens_mm):
    """The draft extension's focal length (`lens_mm`, the exported frame's) and sensor size, in
    glTF's unit, the metre."""
    if cam.type != "PERSP":
        return None
    return {"focalLength": lens_mm / 1000.0,
            "sensorSize": [cam.sensor_width / 1000.0, cam.sensor_height / 1000.0]}


def at_frame(scene, frame, evaluate):
    """`evaluate()` with the scene at `frame`, the scene's frame restored after."""
    current = scene.frame_current
    scene.frame_set(frame)
    try:
        return evaluate()
    finally:
        scene.frame_set(current)


def focus_distance(obj):
    """Blender focuses on the plane through the focus object normal to the view axis (not at
    its Euclidean distance), else at focus_distance."""
    dof = obj.data.dof
    if dof.focus_object is None:
        return dof.focus_distance
    axis = -(obj.matrix_world.to_3x3() @ Vector((0.0, 0.0, 1.0))).normalized()
    offset = dof.focus_object.matrix_world.translation - obj.matrix_world.translation
    return max(offset.dot(axis), 1e-6)


def lens_values(obj):
    """The lens values Blender animates, under the extension's names: focal length and shift, and
    with depth of field on, focus distance (or the focus object's plane) and f-stop."""
    cam = obj.data
    values = {"focal_length_mm": cam.lens, "shift_x": cam.shift_x, "shift_y": cam.shift_y}
    if cam.dof.use_dof:
        values["focus_distance_m"] = focus_distance(obj)
        values["fstop"] = cam.dof.aperture_fstop
    return values


def lens_per_frame(obj, scene):
    """Each lens value that varies over the frame range (an animated lens, or a focus object), one
    per frame from frame_start on: {"first_frame": F, name: [value, ...], ...}; None when none
    varies. The render interpolates linearly between frames (docs/camera-model.md, "Animated
    lenses")."""
    cam = obj.data
    animated = cam.animation_data is not None and (cam.animation_data.action is not None or
                                                   len(cam.animation_data.drivers) > 0)
    if cam.dof.focus_object is None and not animated:
        return None
    first, last = scene.frame_start, scene.frame_end
    if last - first + 1 > MAX_TRACK_FRAMES:
        raise ValueError(f"{obj.name}: {last - first + 1} frames; lens values are written for at "
                         f"most {MAX_TRACK_FRAMES}")
    frames = [at_frame(scene, frame, lambda: lens_values(obj)) for frame in range(first, last + 1)]
    out = {"first_frame": first}
    for name in frames[0]:
        values = [values[name] for values in frames]
        if max(values) != min(values):
            out[name] = values
    return out if len(out) > 1 else None
