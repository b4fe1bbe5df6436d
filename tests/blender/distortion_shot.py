"""The Blender side of the lens distortion test (tests/blender/blender_distortion_test.cpp).

Builds make_shot.py's kind of shot (emissive spheres, "markers", on a black world, seen by its
rotated camera) and a movie clip (a two-frame PNG sequence written here, twice the render's size)
whose solved camera has one of Blender's tracking distortion models; makes the clip the scene's
active clip and exports the scene through filmback's add-on, which writes the clip's intrinsics.
Cycles renders the undistorted shot and Blender's compositor distorts it with the Movie
Distortion node ("Distort"), as a tracked plate's CG is made in Blender.

    blender -b --factory-startup --python distortion_shot.py -- OUTDIR SHOT

writes OUTDIR/shot.gltf, OUTDIR/cycles.exr (the distorted composite) and OUTDIR/manifest.txt
(make_shot.py's records: the shot, and each marker's undistorted projection blender_x_px,
blender_y_px).
"""

import os
import sys
from dataclasses import dataclass

import bpy
from bpy_extras.object_utils import world_to_camera_view

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_shot  # noqa: E402
from make_shot import Frame, Marker, Shot  # noqa: E402


@dataclass(frozen=True)
class Distortion:
    model: str  # MovieTrackingCamera.distortion_model
    coefficients: dict  # MovieTrackingCamera property -> value
    principal_px: tuple  # in the clip's pixels, from its bottom-left corner
    # The camera names the clip by a Camera Solver constraint (the scene has no active clip)
    # instead of the clip being the scene's active clip: the add-on's two ways to find it.
    by_constraint: bool = False


# Small markers (2.5-3.5 px) inside the frame's middle 80 %, where every model keeps them on the
# image; at 256 spp each renderer's centroid noise is ~0.01 px (edge pixels only: the interior of
# an emitter is exact).
MARKERS = (
    Marker("top_left", 0.14, 0.16, 6.0, 3.0, (1.0, 1.0, 1.0), 2.0),
    Marker("top_right", 0.86, 0.15, 12.0, 2.5, (0.6, 0.8, 1.0), 4.0),
    Marker("bottom_right", 0.85, 0.84, 9.0, 3.0, (1.0, 0.6, 0.3), 3.0),
    Marker("bottom_left", 0.16, 0.85, 5.0, 3.5, (0.4, 1.0, 0.4), 2.0),
    Marker("centre", 0.52, 0.47, 4.0, 3.5, (0.9, 0.9, 0.2), 2.0),
    Marker("right", 0.90, 0.50, 7.0, 3.0, (0.2, 0.5, 1.0), 3.0),
    Marker("top", 0.45, 0.12, 20.0, 2.5, (1.0, 0.3, 0.8), 6.0),
)

SHOT = Shot(128, 80, 28.0, MARKERS, samples=256)
CLIP_SCALE = 2  # the clip is twice the render's size: the node scales the distortion by the ratio

# Coefficients that move the corner markers 2-4 px (at the render's size); the optical centre off
# the clip's middle.
DISTORTIONS = {
    "polynomial": Distortion("POLYNOMIAL", {"k1": -0.12, "k2": 0.03, "k3": -0.004}, (131.0, 77.5)),
    "division": Distortion("DIVISION", {"division_k1": -0.1, "division_k2": 0.01}, (126.5, 82.0)),
    "nuke": Distortion("NUKE", {"nuke_k1": 0.08, "nuke_k2": 0.01}, (129.0, 79.0)),
    "brown": Distortion("BROWN", {"brown_k1": -0.1, "brown_k2": 0.02, "brown_k3": -0.002,
                                  "brown_k4": 0.0002, "brown_p1": 0.004, "brown_p2": -0.003},
                        (127.5, 81.5), by_constraint=True),
}


def write_clip(out_dir, width, height):
    """A two-frame black PNG sequence, so that a MovieClip of that size exists."""
    image = bpy.data.images.new("plate", width, height)
    paths = []
    for frame in (1, 2):
        path = os.path.join(out_dir, f"plate_{frame:04d}.png")
        image.filepath_raw = path
        image.file_format = "PNG"
        image.save()
        paths.append(path)
    bpy.data.images.remove(image)
    clip = bpy.data.movieclips.load(paths[0])
    if tuple(clip.size) != (width, height):
        raise RuntimeError(f"the clip is {tuple(clip.size)}, expected {(width, height)}")
    return clip


def solve_camera(clip, camera, distortion):
    """The clip's camera as a solve would leave it: the scene camera's lens and sensor, and the
    shot's distortion."""
    tracking = clip.tracking.camera
    tracking.sensor_width = camera.data.sensor_width
    tracking.units = "MILLIMETERS"
    tracking.focal_length = camera.data.lens
    tracking.pixel_aspect = 1.0
    tracking.principal = distortion.principal_px
    tracking.distortion_model = distortion.model
    for name, value in distortion.coefficients.items():
        setattr(tracking, name, value)


def distort_in_compositor(scene, clip):
    """Render Layers -> Movie Distortion (Distort) -> Composite: the written image is distorted."""
    scene.use_nodes = True
    nodes, links = scene.node_tree.nodes, scene.node_tree.links
    nodes.clear()
    layers = nodes.new("CompositorNodeRLayers")
    node = nodes.new("CompositorNodeMovieDistortion")
    node.clip = clip
    node.distortion_type = "DISTORT"
    composite = nodes.new("CompositorNodeComposite")
    links.new(layers.outputs["Image"], node.inputs["Image"])
    links.new(node.outputs["Image"], composite.inputs["Image"])


def main():
    out_dir, name = make_shot.shot_arguments("distortion_shot.py", DISTORTIONS)
    distortion = DISTORTIONS[name]

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    make_shot.new_world(scene)
    make_shot.configure_cycles(scene, SHOT)
    camera = make_shot.build_camera(scene, SHOT)
    bpy.context.view_layer.update()
    frame = Frame(scene, camera)
    spheres = [make_shot.add_sphere(camera, frame, marker, marker.depth_m)[0]
               for marker in SHOT.markers]
    clip = write_clip(out_dir, SHOT.width_px * CLIP_SCALE, SHOT.height_px * CLIP_SCALE)
    solve_camera(clip, camera, distortion)
    if distortion.by_constraint:
        # With no reconstruction the constraint leaves the camera where it is.
        constraint = camera.constraints.new("CAMERA_SOLVER")
        constraint.use_active_clip = False
        constraint.clip = clip
    else:
        scene.active_clip = clip
    bpy.context.view_layer.update()

    w, h = SHOT.width_px, SHOT.height_px
    with open(os.path.join(out_dir, "manifest.txt"), "w") as manifest:
        manifest.write(make_shot.record("shot", name=name, samples=SHOT.samples, width_px=w,
                                        height_px=h, camera_model="perspective",
                                        aperture_blades=0))
        for marker, sphere in zip(SHOT.markers, spheres):
            centre = world_to_camera_view(scene, camera, sphere.matrix_world.translation)
            manifest.write(make_shot.record("marker", name=marker.name,
                                            blender_x_px=centre.x * w,
                                            blender_y_px=(1.0 - centre.y) * h))

    make_shot.export(os.path.join(out_dir, "shot.gltf"))
    distort_in_compositor(scene, clip)
    scene.render.filepath = os.path.join(out_dir, "cycles.exr")
    bpy.ops.render.render(write_still=True)


main()
