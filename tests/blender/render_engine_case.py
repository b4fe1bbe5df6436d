"""Runs inside `blender -b` for render_engine_test.py: installs the add-on from a zip as a user
does, builds a small animated shot, renders it with the filmback engine and checks one case.

    blender -b --factory-startup --python render_engine_case.py -- ZIP FILMBACK OUT CASE

Writes OUT/passed when the case passes; an AssertionError's message goes to stderr otherwise.
"""

import json
import os
import struct
import subprocess
import sys
import tempfile
import time

import bpy
import numpy

HERE = os.path.dirname(os.path.abspath(__file__))

WIDTH_PX, HEIGHT_PX = 64, 36
SAMPLES = 4
FIRST_FRAME, LAST_FRAME = 1, 3
MARKER_X_BY_FRAME = {1: -1.0, 2: 0.0, 3: 1.0}  # the emissive marker's keyed x, m
CANCEL_SAMPLES = 1_000_000  # filmback's most; far more than a second's worth at 64 x 36
CANCEL_RETURN_LIMIT_S = 20.0  # export, a few seconds of rendering, the stop and the load


def install_addon(zip_path, filmback):
    bpy.ops.preferences.addon_install(filepath=zip_path)
    bpy.ops.preferences.addon_enable(module="io_filmback")
    assert "io_filmback" in bpy.context.preferences.addons, "the add-on is not enabled"
    bpy.context.preferences.addons["io_filmback"].preferences.filmback_path = filmback


def emissive_material(name, strength):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = strength
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(emission.outputs["Emission"], output.inputs["Surface"])
    return material


def toon_material():
    """A Toon BSDF: the add-on carries it as a DIFFUSE with a warning, which filmback prints and
    the engine reports."""
    material = bpy.data.materials.new("Toon")
    material.use_nodes = True
    tree = material.node_tree
    toon = tree.nodes.new("ShaderNodeBsdfToon")
    tree.links.new(toon.outputs["BSDF"], tree.nodes["Material Output"].inputs["Surface"])
    return material


def build_shot():
    # The factory startup's cube, light and camera go; reading an empty factory file instead
    # would also reset the preferences, disabling the add-on.
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    scene = bpy.context.scene
    scene.render.engine = "FILMBACK"
    scene.render.resolution_x, scene.render.resolution_y = WIDTH_PX, HEIGHT_PX
    scene.render.resolution_percentage = 100
    scene.frame_start, scene.frame_end = FIRST_FRAME, LAST_FRAME
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"
    scene.filmback.samples = SAMPLES

    bpy.ops.mesh.primitive_plane_add(size=20)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.8, location=(0, 0, 0.8))
    bpy.context.object.data.materials.append(toon_material())
    bpy.ops.object.light_add(type="POINT", location=(2, -2, 4))
    bpy.context.object.data.energy = 800
    bpy.ops.mesh.primitive_cube_add(size=0.6, location=(0, 1.5, 2.2))
    marker = bpy.context.object
    marker.data.materials.append(emissive_material("Marker", 10.0))
    for frame, x in MARKER_X_BY_FRAME.items():
        marker.location.x = x
        marker.keyframe_insert("location", index=0, frame=frame)
    bpy.ops.object.camera_add(location=(0, -8, 3), rotation=(1.3, 0, 0))
    scene.camera = bpy.context.object
    scene.frame_set(FIRST_FRAME)
    return scene


def pixels(exr_path):
    """The file's RGBA values as Blender loads a float EXR (no colour conversion)."""
    image = bpy.data.images.load(exr_path, check_existing=False)
    values = numpy.empty(len(image.pixels), dtype=numpy.float32)
    image.pixels.foreach_get(values)
    bpy.data.images.remove(image)
    return values.reshape(-1, 4)


def command_line_render(filmback, out, frame, extra_args=()):
    """export_shot's export of the scene at `frame`, rendered by the command line with the
    engine's settings (and `extra_args`); returns the EXR's path."""
    # Appended, so that the installed add-on, not the repository's, stays the one in use.
    sys.path.append(os.path.join(HERE, "..", "..", "importers", "blender"))
    import export_shot
    bpy.context.scene.frame_set(frame)
    gltf = os.path.join(out, f"cli_{frame}.gltf")
    exr = os.path.join(out, f"cli_{frame}.exr")
    export_shot.export(gltf)
    settings = bpy.context.scene.filmback
    r = subprocess.run([filmback, "render", gltf, "-o", exr, "--spp", str(settings.samples),
                        "--sampler", settings.sampler, "-q", *extra_args],
                       capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, f"command-line render failed: {r.stderr}"
    return exr


def assert_bit_identical(engine_exr, cli_exr, size=(WIDTH_PX, HEIGHT_PX)):
    engine, cli = pixels(engine_exr), pixels(cli_exr)
    assert engine.shape == (size[0] * size[1], 4), engine.shape
    assert engine.shape == cli.shape, (engine.shape, cli.shape)
    assert numpy.isfinite(engine).all(), "non-finite pixels"
    assert engine[:, :3].max() > 0, "an all-black image"
    differing = int(numpy.count_nonzero((engine != cli).any(axis=1)))
    assert differing == 0, f"{differing} of {len(engine)} pixels differ from the command line's"


def assert_engine_and_plugins_listed(scene):
    """filmback in Render Properties' engine list (the enum took it); the panel's plugin lists as
    `filmback plugins` prints them (the panel draws what filmback_cli.plugin_names returns)."""
    from io_filmback import filmback_cli, render_settings
    assert scene.render.engine == "FILMBACK", scene.render.engine
    plugins = filmback_cli.plugin_names(render_settings.executable(bpy.context))
    assert "path" in plugins["integrator"] and "gaussian" in plugins["filter"], plugins


def case_still(filmback, out):
    scene = build_shot()
    assert_engine_and_plugins_listed(scene)
    scene.render.filepath = os.path.join(out, "engine.exr")
    bpy.ops.render.render(write_still=True)
    assert_bit_identical(scene.render.filepath, command_line_render(filmback, out, FIRST_FRAME))
    print("engine's EXR bit-identical to the command line's")


def marker_column(rgba):
    """The image column holding most of the emissive marker's light (its brightest pixels)."""
    image = rgba[:, 0].reshape(HEIGHT_PX, WIDTH_PX)
    bright = image >= image.max() * 0.9
    return numpy.nonzero(bright)[1].mean()


def case_animation(filmback, out):
    scene = build_shot()
    scene.render.filepath = os.path.join(out, "anim_")
    bpy.ops.render.render(animation=True)
    columns = []
    for frame in range(FIRST_FRAME, LAST_FRAME + 1):
        engine_exr = os.path.join(out, f"anim_{frame:04d}.exr")
        assert os.path.exists(engine_exr), f"frame {frame} was not written"
        assert_bit_identical(engine_exr, command_line_render(filmback, out, frame))
        columns.append(marker_column(pixels(engine_exr)))
    # The marker moves +x (rightwards in the image) by 1 m per frame.
    assert columns[0] < columns[1] < columns[2], f"marker columns {columns}"
    print("three frames, each bit-identical to its command-line render; marker columns", columns)


def case_bad_setting(filmback, out):
    scene = build_shot()
    scene.filmback.integrator = "nosuch"
    try:
        bpy.ops.render.render()
    except RuntimeError as e:
        message = str(e)
    else:
        raise AssertionError("a render with an unknown integrator reported no error")
    assert "Error" in message and "unknown integrator plugin 'nosuch'" in message, message
    print("reported:", message)


def case_cancel(filmback, out):
    scene = build_shot()
    scene.filmback.samples = CANCEL_SAMPLES
    # Cycles' adaptive sampling (on by default, exported with the shot) lets this shot converge
    # in well under a second: off, the render runs until the engine cancels it.
    scene.cycles.use_adaptive_sampling = False
    scene.render.filepath = os.path.join(out, "cancelled.exr")
    started = time.monotonic()
    bpy.ops.render.render(write_still=True)
    elapsed = time.monotonic() - started
    assert elapsed < CANCEL_RETURN_LIMIT_S, f"the cancelled render took {elapsed:.1f} s"
    rgba = pixels(scene.render.filepath)
    assert numpy.isfinite(rgba).all() and rgba[:, :3].max() > 0, "no partial image"
    from io_filmback import render_engine
    progress_lines = render_engine.last_render_progress_lines
    # Without --progress-every a piped filmback prints one line at 0.5 s, then one every 10 s.
    assert progress_lines >= 2, f"{progress_lines} progress lines before the cancel (--progress-every)"
    # filmback writes its first preview a second (filmback_cli.PREVIEW_EVERY) into rendering.
    previews = render_engine.last_render_previews_shown
    assert previews >= 1, "no preview shown before the render was cancelled (--preview)"
    print(f"cancelled render returned after {elapsed:.1f} s with a partial image, "
          f"{progress_lines} progress lines and {previews} previews shown")


def depth_pass(exr_path, out, name):
    """The file's ViewLayer.Depth.Z, as Blender loads it from a copy with it as R, G and B
    (oiiotool; kept under its layer's name, Blender would take the copy for a multi-layer file)."""
    copy = os.path.join(out, name)
    subprocess.run(["oiiotool", exr_path, "--ch", ",".join(c + "=ViewLayer.Depth.Z" for c in "RGB"),
                    "-o", copy], check=True, capture_output=True, timeout=60)
    return pixels(copy)[:, 0]


def case_passes(filmback, out):
    """The view layer's Z and Vector passes switched on: the engine asks filmback for Depth and
    Vector and loads them into the Render Result, which Blender writes into its multi-layer EXR as
    it writes Cycles'."""
    scene = build_shot()
    view_layer = scene.view_layers[0]
    assert view_layer.name == "ViewLayer", view_layer.name
    view_layer.use_pass_z = True
    view_layer.use_pass_vector = True
    scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = os.path.join(out, "engine.exr")
    bpy.ops.render.render(write_still=True)
    cli = command_line_render(filmback, out, FIRST_FRAME, ["--passes", "Depth,Vector"])
    engine_depth = depth_pass(scene.render.filepath, out, "engine_depth.exr")
    cli_depth = depth_pass(cli, out, "cli_depth.exr")
    assert engine_depth.shape == (WIDTH_PX * HEIGHT_PX,), engine_depth.shape
    assert (engine_depth < 1e3).any() and (engine_depth == 1e10).any(), \
        "expected both hits and the background's 1e10 m in the depth"
    differing = int(numpy.count_nonzero(engine_depth != cli_depth))
    assert differing == 0, f"{differing} depth pixels differ from the command line's"
    engine_vector = channels(scene.render.filepath, out, "engine_vector", "ViewLayer.Vector.")
    cli_vector = channels(cli, out, "cli_vector", "ViewLayer.Vector.")
    assert sorted(engine_vector) == ["ViewLayer.Vector." + c for c in "WXYZ"], sorted(engine_vector)
    # The marker moves 1 m per frame along x (its keys may start at this frame: X or Z).
    assert any((engine_vector["ViewLayer.Vector." + c] != 0).any() for c in "XZ"), \
        "no motion in the Vector pass"
    for name, values in engine_vector.items():
        differing = int(numpy.count_nonzero(values != cli_vector[name]))
        assert differing == 0, f"{differing} pixels of {name} differ from the command line's"
    print("engine's Depth and Vector passes bit-identical to the command line's")


def channels(exr_path, out, name, pattern):
    """{channel: values} of the file's channels whose names start with `pattern`, as 32-bit
    floats (oiiotool copies four at a time into a file of their own, which Blender loads)."""
    listing = subprocess.run(["oiiotool", "--info", "-v", exr_path], check=True,
                             capture_output=True, text=True, timeout=60).stdout
    names = [c for c in listing.split("channel list: ")[1].splitlines()[0].split(", ")
             if c.startswith(pattern)]
    assert names, f"no {pattern}* channel in {exr_path}"
    values = {}
    for k in range(0, len(names), 4):
        group = (names[k:k + 4] + names[k:k + 1] * 4)[:4]
        copy = os.path.join(out, f"{name}_{k}.exr")
        subprocess.run(["oiiotool", exr_path, "--ch",
                        ",".join(f"{c}={n}" for c, n in zip("RGBA", group)), "-o", copy],
                       check=True, capture_output=True, timeout=60)
        loaded = pixels(copy)
        for column, channel in enumerate(group):
            values[channel] = loaded[:, column]
    return values


CRYPTOMATTE_CASE_LEVELS = 10  # the view layer's Cryptomatte Levels; Blender's default is 6


def case_cryptomatte(filmback, out):
    """The view layer, renamed, with its Cryptomatte switches on at 10 levels: the engine asks
    filmback for CryptoObject, CryptoMaterial and CryptoAsset, five RGBA layers each, in a layer of
    the view layer's name, loads their layers into
    the Render Result and its manifests into the Render Result's metadata; Blender's multi-layer
    EXR of it has both, equal to the command line's, and the compositor's Cryptomatte node,
    reading the Render Result, mattes the sphere by its name: each pixel its coverage, decoded
    from the command line's layers through its manifest."""
    scene = build_shot()
    view_layer = scene.view_layers[0]
    view_layer.name = layer = "Shot Layer"
    view_layer.use_pass_cryptomatte_object = True
    view_layer.use_pass_cryptomatte_material = True
    view_layer.use_pass_cryptomatte_asset = True
    view_layer.pass_cryptomatte_depth = CRYPTOMATTE_CASE_LEVELS
    scene.use_nodes = True
    tree = scene.node_tree
    crypto = tree.nodes.new("CompositorNodeCryptomatteV2")  # source: the Render Result
    tree.links.new(tree.nodes["Render Layers"].outputs["Image"], crypto.inputs["Image"])
    crypto.layer_name = f"{layer}.CryptoObject"
    crypto.matte_id = "Sphere"
    tree.links.new(crypto.outputs["Matte"], tree.nodes["Composite"].inputs["Image"])
    scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = os.path.join(out, "engine.exr")
    bpy.ops.render.render(write_still=True)
    cli = command_line_render(filmback, out, FIRST_FRAME,
                              ["--passes", "CryptoObject,CryptoMaterial,CryptoAsset",
                               "--view-layer", layer,
                               "--cryptomatte-levels", str(CRYPTOMATTE_CASE_LEVELS)])
    engine = channels(scene.render.filepath, out, "engine", f"{layer}.Crypto")
    cli_values = channels(cli, out, "cli", f"{layer}.Crypto")
    assert sorted(engine) == sorted(cli_values), (sorted(engine), sorted(cli_values))
    assert len(engine) == 3 * CRYPTOMATTE_CASE_LEVELS // 2 * 4, sorted(engine)
    for name, values in cli_values.items():
        differing = int(numpy.count_nonzero(engine[name] != values))
        assert differing == 0, f"{name}: {differing} values differ from the command line's"
    from io_filmback import exr_header
    engine_header = exr_header.string_attributes(scene.render.filepath)
    cli_header = exr_header.string_attributes(cli)
    for key, value in cli_header.items():
        if key.startswith("cryptomatte/"):
            assert engine_header.get(key) == value, (key, engine_header.get(key), value)
    key = next(k[:-len("/name")] for k, v in cli_header.items()
               if k.startswith("cryptomatte/") and v == f"{layer}.CryptoObject")
    manifest = json.loads(cli_header[key + "/manifest"])
    # The id as Cryptomatte stores it: the hash's bits as a float (an exponent of 0 or 255 moved
    # off; the sphere's hash has neither, checked).
    sphere_hash = int(manifest["Sphere"], 16)
    assert 0 < (sphere_hash >> 23) & 0xFF < 255, manifest["Sphere"]
    sphere_id = numpy.frombuffer(struct.pack("<I", sphere_hash), dtype=numpy.float32)[0]
    expected = numpy.zeros_like(cli_values[f"{layer}.CryptoObject00.r"])
    for rgba in range(CRYPTOMATTE_CASE_LEVELS // 2):
        for id_channel, coverage_channel in (("r", "g"), ("b", "a")):
            prefix = f"{layer}.CryptoObject{rgba:02d}."
            expected += numpy.where(cli_values[prefix + id_channel] == sphere_id,
                                    cli_values[prefix + coverage_channel], 0.0)
    assert (expected == 1.0).any() and (expected == 0.0).any(), "the sphere is not in the shot"
    matte = channels(scene.render.filepath, out, "matte", "Composite.Combined.R")
    worst = float(numpy.abs(matte["Composite.Combined.R"] - expected).max())
    assert worst < 1e-6, f"the Cryptomatte node's matte is {worst} from the sphere's coverage"
    print(f"the Cryptomatte node's matte of the sphere matches its coverage in "
          f"{len(expected)} pixels")


CASES = {"still": case_still, "animation": case_animation, "bad_setting": case_bad_setting,
         "cancel": case_cancel, "passes": case_passes, "cryptomatte": case_cryptomatte}


def main():
    zip_path, filmback, out, case = sys.argv[sys.argv.index("--") + 1:]
    install_addon(zip_path, filmback)
    CASES[case](filmback, out)
    # Blender keeps its own session folder (blender_XXXXXX) there until it quits.
    left = [name for name in os.listdir(tempfile.gettempdir()) if name.startswith("filmback")]
    assert not left, f"temporary files left in {tempfile.gettempdir()}: {left}"
    with open(os.path.join(out, "passed"), "w") as f:
        f.write(case + "\n")


if __name__ == "__main__":
    main()
