"""A Blender camera as the FILMBACK_blender camera extension and as EXT_camera_physical."""

import math

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
        out["panorama"] = panorama(cam)
    dof = cam.dof
    if dof.use_dof:
        out["aperture_blades"] = dof.aperture_blades
        out["aperture_rotation_rad"] = dof.aperture_rotation
        out["aperture_ratio"] = dof.aperture_ratio
    per_frame = lens_per_frame(obj, scene)
    if per_frame is not None:
        out["per_frame"] = per_frame
    distortion = lens_distortion(obj, scene)
    if distortion is not None:
        out["lens_distortion"] = distortion
    return out


# Each tracking distortion model's coefficients: MovieTrackingCamera's property per name written.
DISTORTION_COEFFICIENTS = {
    "POLYNOMIAL": {"k1": "k1", "k2": "k2", "k3": "k3"},
    "DIVISION": {"k1": "division_k1", "k2": "division_k2"},
    "NUKE": {"k1": "nuke_k1", "k2": "nuke_k2"},
    "BROWN": {"k1": "brown_k1", "k2": "brown_k2", "k3": "brown_k3", "k4": "brown_k4",
              "p1": "brown_p1", "p2": "brown_p2"},
}


def camera_clip(obj, scene):
    """The movie clip whose solved camera this camera is: its Camera Solver constraint's (or the
    scene's active clip when the constraint says so), else the scene's active clip."""
    for constraint in obj.constraints:
        if constraint.type == "CAMERA_SOLVER" and constraint.enabled:
            return scene.active_clip if constraint.use_active_clip else constraint.clip
    return scene.active_clip


def lens_distortion(obj, scene):
    """The clip's solved intrinsics in Blender 3.4's units (focal length and optical centre in the
    clip's pixels, the centre from its bottom-left corner), when its distortion is not the
    identity; None otherwise (docs/blender.md, "Lens distortion")."""
    clip = camera_clip(obj, scene)
    if clip is None or obj.data.type != "PERSP":
        return None
    tracking = clip.tracking.camera
    names = DISTORTION_COEFFICIENTS[tracking.distortion_model]
    coefficients = {key: getattr(tracking, prop) for key, prop in names.items()}
    if not any(coefficients.values()):
        return None
    width, height = clip.size
    return {"model": tracking.distortion_model.lower(), **coefficients,
            "clip_size_px": [width, height],
            "focal_length_px": tracking.focal_length_pixels,
            "principal_px": list(tracking.principal),
            "pixel_aspect": tracking.pixel_aspect}


def ext_camera_physical(cam, lens_mm):
    """The draft extension's focal length (`lens_mm`, the exported frame's) and sensor size, in
    glTF's unit, the metre."""
    if cam.type != "PERSP":
        return None
    return {"focalLength": lens_mm / 1000.0,
            "sensorSize": [cam.sensor_width / 1000.0, cam.sensor_height / 1000.0]}


# Blender's panorama types -> filmback's projection kinds (core/render/shot_plan.cpp, kModelPlugins)
# and, per kind, the plugin parameter each of Blender's values becomes: (parameter, RNA name).
PANORAMA_KINDS = {
    "EQUIRECTANGULAR": ("equirectangular", (
        ("latitude_min_rad", "latitude_min"), ("latitude_max_rad", "latitude_max"),
        ("longitude_min_rad", "longitude_min"), ("longitude_max_rad", "longitude_max"))),
    "FISHEYE_EQUIDISTANT": ("fisheye_equidistant", (("fisheye_fov_rad", "fisheye_fov"),)),
    "FISHEYE_EQUISOLID": ("fisheye_equisolid", (
        ("fisheye_lens_mm", "fisheye_lens"), ("fisheye_fov_rad", "fisheye_fov"))),
    "MIRRORBALL": ("mirrorball", ()),
    "FISHEYE_LENS_POLYNOMIAL": ("fisheye_polynomial", (
        ("fisheye_fov_rad", "fisheye_fov"),
        *((f"k{i}", f"fisheye_polynomial_k{i}") for i in range(5)))),
    "CENTRAL_CYLINDRICAL": ("central_cylindrical", (
        ("central_cylindrical_range_u_min_rad", "central_cylindrical_range_u_min"),
        ("central_cylindrical_range_u_max_rad", "central_cylindrical_range_u_max"),
        ("central_cylindrical_range_v_min_m", "central_cylindrical_range_v_min"),
        ("central_cylindrical_range_v_max_m", "central_cylindrical_range_v_max"),
        ("central_cylindrical_radius_m", "central_cylindrical_radius"))),
    "EQUIANGULAR_CUBEMAP_FACE": ("equiangular_cubemap_face", ()),
}


def panorama(cam):
    """A panoramic camera's projection: {"type": kind, parameter: value, ...}. Blender 3.x keeps
    the panorama on the Cycles settings (cam.cycles), Blender 4 on the camera itself."""
    settings = cam if hasattr(cam, "panorama_type") else cam.cycles
    kind, values = PANORAMA_KINDS[settings.panorama_type]
    return {"type": kind, **{key: getattr(settings, rna) for key, rna in values}}


def fallback_yfov(cam, scene):
    """The vertical field of view of the camera's perspective lens on this render's frame
    (Blender's sensor fit), for the core glTF camera a panoramic one carries for other viewers."""
    width = scene.render.resolution_x * scene.render.pixel_aspect_x
    height = scene.render.resolution_y * scene.render.pixel_aspect_y
    fit = cam.sensor_fit if cam.sensor_fit != "AUTO" else (
        "HORIZONTAL" if width >= height else "VERTICAL_WIDTH")
    if fit == "HORIZONTAL":
        half = cam.sensor_width / 2 * height / width
    else:
        half = (cam.sensor_height if fit == "VERTICAL" else cam.sensor_width) / 2
    return 2 * math.atan(half / cam.lens), width / height


def panoramic_gltf_camera(obj, scene):
    """Blender 3.4's glTF exporter writes no camera for a panoramic one: a core perspective camera
    (Blender's lens, for viewers without the extension), to which FILMBACK_blender is added."""
    from io_scene_gltf2.io.com import gltf2_io
    cam = obj.data
    yfov, aspect = fallback_yfov(cam, scene)
    perspective = gltf2_io.CameraPerspective(aspect_ratio=aspect, extensions=None, extras=None,
                                             yfov=yfov, zfar=cam.clip_end, znear=cam.clip_start)
    return gltf2_io.Camera(extensions=None, extras=None, name=cam.name, orthographic=None,
                           perspective=perspective, type="perspective")


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
