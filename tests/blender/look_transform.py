"""The Blender side of the view-transform test (tests/blender/blender_look_test.cpp).

Has Blender save, as it saves a render, a synthetic float image through Color Management:

    blender -b --factory-startup --python look_transform.py -- OUTDIR VIEW LOOK EXPOSURE GAMMA DITHER

writes OUTDIR/blender.png (8-bit RGB, written by `render.render(write_still=True)`: the
display-buffer path of every saved render, dither included) and OUTDIR/linear.exr (the same render
result, float, scene-linear: what filmback's transform takes).

The image is WIDTH x HEIGHT: each row a log ramp from 1e-4 to 1e3 (seven decades over the width),
in bands of grey, the primaries and secondaries, two saturated mixes and one with a slightly
negative red (a negative filter lobe's value). HEIGHT is not a multiple of 64, so that the last of
Blender's 64-row conversion tasks is a short one (the dither hashes a pixel's place in its task).
The compositor passes the image to the render result (an Image node into the Composite node);
Workbench renders the empty scene under it in no time.
"""

import os
import sys

import bpy

WIDTH, HEIGHT = 256, 150
BANDS = [(1, 1, 1), (1, 0, 0), (0, 1, 0), (0, 0, 1), (0, 1, 1), (1, 0, 1), (1, 1, 0),
         (1, 0.2, 0.05), (0.1, 0.3, 1), (-0.02, 0.5, 1)]


def source_pixels():
    """RGBA floats, Blender's order: bottom row first."""
    ramp = [1e-4 * 1e7 ** (x / (WIDTH - 1)) for x in range(WIDTH)]
    pixels = []
    for row in range(HEIGHT):
        band = BANDS[row * len(BANDS) // HEIGHT]
        gain = 1 + 0.013 * (row % 8)  # rows of a band differ a little: the dither sees them all
        for v in ramp:
            pixels += [c * v * gain if c >= 0 else c for c in band] + [1.0]
    return pixels


def render_png_and_exr(scene, png, exr):
    """Renders `scene` once: the 8-bit RGB PNG as Blender saves every render
    (`render.render(write_still=True)`: Color Management's display buffer, dither included), and
    the same render result as a scene-linear float EXR."""
    output = scene.render.image_settings
    output.file_format, output.color_mode, output.color_depth = "PNG", "RGB", "8"
    scene.render.filepath = png
    bpy.ops.render.render(write_still=True)
    output.file_format, output.color_depth, output.exr_codec = "OPEN_EXR", "32", "ZIP"
    bpy.data.images["Render Result"].save_render(exr, scene=scene)


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 6:
        raise SystemExit("usage: blender -b --factory-startup --python look_transform.py -- "
                         "OUTDIR VIEW LOOK EXPOSURE GAMMA DITHER")
    out_dir, view, look, exposure, gamma, dither = args
    os.makedirs(out_dir, exist_ok=True)
    image = bpy.data.images.new("source", WIDTH, HEIGHT, alpha=True, float_buffer=True)
    image.pixels.foreach_set(source_pixels())

    scene = bpy.context.scene
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    scene.render.resolution_percentage = 100
    scene.use_nodes = True
    tree = scene.node_tree
    tree.nodes.clear()
    source = tree.nodes.new("CompositorNodeImage")
    source.image = image
    composite = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(source.outputs["Image"], composite.inputs["Image"])

    scene.display_settings.display_device = "sRGB"
    settings = scene.view_settings
    settings.view_transform, settings.look = view, look
    settings.exposure, settings.gamma = float(exposure), float(gamma)
    scene.render.dither_intensity = float(dither)

    render_png_and_exr(scene, os.path.join(out_dir, "blender.png"),
                       os.path.join(out_dir, "linear.exr"))


if __name__ == "__main__":
    main()
