"""filmback as a Blender render engine: F12 exports the shot to a temporary folder through the
add-on's exporter, runs the `filmback` command on it and loads its EXR into the Render Result.
While filmback runs, each new preview it writes (--preview) is loaded too: the image fills in.

Each render() is one frame (Ctrl+F12 calls it once per frame of the range), exported at the frame
Blender is rendering. Esc (test_break) sends filmback SIGINT, on which it writes the image so far
and exits 130 (docs/cli.md, "Interrupts and checkpoints"): that partial image is loaded too.
"""

import collections
import os
import shutil
import signal
import subprocess
import tempfile
import threading
import time

import bpy

from . import exr_header, filmback_cli, render_settings
from .gltf_export import export_gltf
from . import main_thread

# The view layer's pass switches filmback writes (docs/blender.md, "Passes"): the property, the
# pass's name, its channels and its kind, as Cycles registers them.
RENDER_PASSES = (
    ("use_pass_z", "Depth", "Z", "VALUE"),
    ("use_pass_normal", "Normal", "XYZ", "VECTOR"),
    ("use_pass_diffuse_color", "DiffCol", "RGB", "COLOR"),
    ("use_pass_glossy_color", "GlossCol", "RGB", "COLOR"),
    ("use_pass_emit", "Emit", "RGB", "COLOR"),
    ("use_pass_vector", "Vector", "XYZW", "VECTOR"),
)
# The view layer's Cryptomatte switches (docs/blender.md, "Cryptomatte"): the property and the
# pass's name. Each is cryptomatte_levels() / 2 passes of channels r, g, b, a (lower-case, as in
# the files Blender writes of Cycles' passes), "CryptoObject00", "01", ..., two levels each.
CRYPTOMATTE_PASSES = (
    ("use_pass_cryptomatte_object", "CryptoObject"),
    ("use_pass_cryptomatte_material", "CryptoMaterial"),
    ("use_pass_cryptomatte_asset", "CryptoAsset"),
)

POLL_INTERVAL_S = 0.05
STDERR_LINES_KEPT = 200  # warnings and errors; what a broken filmback prints past them is dropped

# For tests only: `blender -b` has no Esc key, so this many seconds into filmback's render the
# engine acts as if test_break() had answered yes (docs/blender.md, "Rendering from Blender").
TEST_CANCEL_AFTER_S_ENV = "FILMBACK_TEST_CANCEL_AFTER_S"

# For tests only: how many progress lines the last render read (tests/blender's cancel case
# checks that a render of a second moved the progress bar before it ended).
last_render_progress_lines = 0
# For tests only: how many of filmback's previews the last render showed (the cancel case checks
# that the image filled in before the render ended).
last_render_previews_shown = 0


class StderrReader:
    """Reads filmback's stderr on a thread (a full pipe would stall the render), keeping its last
    lines and the last progress fraction."""

    def __init__(self, stream):
        self.lines = collections.deque(maxlen=STDERR_LINES_KEPT)
        self.fraction = 0.0
        self.progress_lines = 0
        self._thread = threading.Thread(target=self._read, args=(stream,), daemon=True)
        self._thread.start()

    def _read(self, stream):
        for line in stream:
            fraction = filmback_cli.progress_fraction(line)
            if fraction is None:
                self.lines.append(line)
            else:  # progress lines are not kept: a long render would push its warnings out
                self.fraction = fraction
                self.progress_lines += 1

    def text(self):
        self._thread.join()
        return "".join(self.lines)


def result_size(render):
    """The Render Result's width and height: the size after the percentage, rounded as Blender
    does (and as the export says)."""
    return (render.resolution_x * render.resolution_percentage // 100,
            render.resolution_y * render.resolution_percentage // 100)


def cryptomatte_levels(view_layer):
    """The view layer's Cryptomatte Levels as filmback takes them: Cycles writes
    ceil(levels / 2) RGBA layers of at most 16 levels, so an odd number counts as the next even
    one."""
    levels = min(max(int(view_layer.pass_cryptomatte_depth), 2), 16)
    return levels + levels % 2


def enabled_passes(view_layer):
    """(name as --passes takes it, [(Render Result pass, channels, kind)]) for each pass of
    RENDER_PASSES and CRYPTOMATTE_PASSES the view layer has switched on."""
    passes = [(name, [(name, channels, kind)]) for prop, name, channels, kind in RENDER_PASSES
              if getattr(view_layer, prop)]
    passes += [(name, [(f"{name}{i:02d}", "rgba", "COLOR")
                       for i in range(cryptomatte_levels(view_layer) // 2)])
               for prop, name in CRYPTOMATTE_PASSES if getattr(view_layer, prop)]
    return passes


def preview_mtime_ns(path):
    """When filmback last replaced its preview; None before the first one."""
    try:
        return os.stat(path).st_mtime_ns
    except FileNotFoundError:
        return None


def export_frame(path, frame):
    """The shot at `frame` into `path`. The exporter and the add-on's hooks read the context's
    scene, which Blender has set to the frame it renders; a render of another frame (an API call)
    moves it there first."""
    if bpy.context.scene.frame_current != frame:
        bpy.context.scene.frame_set(frame)
    export_gltf(path)


class FilmbackRenderEngine(bpy.types.RenderEngine):
    bl_idname = render_settings.ENGINE_ID
    bl_label = "filmback"
    bl_use_postprocess = True  # the compositor and sequencer run on filmback's image

    def update_render_passes(self, scene=None, renderlayer=None):
        """The passes the compositor's Render Layers node offers: Combined, and those of
        RENDER_PASSES and CRYPTOMATTE_PASSES the view layer switched on."""
        self.register_pass(scene, renderlayer, "Combined", 4, "RGBA", "COLOR")
        for _, result_passes in enabled_passes(renderlayer):
            for name, channels, kind in result_passes:
                self.register_pass(scene, renderlayer, name, len(channels), channels, kind)

    def render(self, depsgraph):
        scene = depsgraph.scene
        executable = render_settings.executable(bpy.context)
        if executable is None:
            self.report({"ERROR"}, "filmback: not found on PATH nor at the path set in the "
                                   "add-on's preferences")
            return
        folder = tempfile.mkdtemp(prefix="filmback-render-")
        try:
            self.render_in(folder, scene, depsgraph.view_layer, executable)
        finally:
            shutil.rmtree(folder, ignore_errors=True)

    def render_in(self, folder, scene, view_layer, executable):
        frame = scene.frame_current
        self.update_stats("", f"filmback: exporting frame {frame}")
        scene_path = os.path.join(folder, "shot.gltf")
        try:
            main_thread.run_on_main_thread(scene, lambda: export_frame(scene_path, frame))
        except RuntimeError as e:
            self.report({"ERROR"}, f"filmback: export failed: {e}")
            return
        output_path = os.path.join(folder, "shot.exr")
        preview_path = os.path.join(folder, "preview.exr")
        settings = scene.filmback
        passes = enabled_passes(view_layer)
        for _, result_passes in passes:
            for name, channels, _ in result_passes:
                self.add_pass(name, len(channels), channels)
        self.with_passes = bool(passes)
        command = filmback_cli.render_command(executable, scene_path, output_path, preview_path,
                                              settings.samples, settings.sampler,
                                              settings.integrator.strip(),
                                              settings.filter.strip(),
                                              [name for name, _ in passes], view_layer.name,
                                              cryptomatte_levels(view_layer))
        self.update_stats("", f"filmback: rendering frame {frame}")
        try:
            status, stderr_text = self.run(command, preview_path, scene.render)
        except OSError as e:
            self.report({"ERROR"}, f"filmback: cannot run {executable}: {e}")
            return
        if status == 0 or (status in filmback_cli.INTERRUPTED_STATUSES and
                           os.path.exists(output_path)):
            for warning in filmback_cli.warnings(stderr_text):
                self.report({"WARNING"}, warning)
            self.show(output_path, scene.render)
            if self.with_passes:
                self.add_cryptomatte_metadata(output_path)
            self.update_progress(1.0)
        elif status not in filmback_cli.INTERRUPTED_STATUSES:
            message = filmback_cli.error_message(stderr_text) or f"exit status {status}"
            self.report({"ERROR"}, message)

    def run(self, command, preview_path, render):
        """Runs filmback until it exits, interrupting it once on Esc and showing each new
        preview it writes; returns its exit status and stderr."""
        process = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.PIPE, text=True, errors="replace")
        reader = StderrReader(process.stderr)
        started = time.monotonic()
        cancel_after_s = float(os.environ.get(TEST_CANCEL_AFTER_S_ENV, "inf"))
        interrupted = False
        shown_mtime_ns = None  # the preview last shown; filmback renames each new one into place
        previews_shown = 0
        while process.poll() is None:
            if not interrupted and (self.test_break() or
                                    time.monotonic() - started >= cancel_after_s):
                process.send_signal(signal.SIGINT)
                interrupted = True
            mtime_ns = preview_mtime_ns(preview_path)
            if mtime_ns is not None and mtime_ns != shown_mtime_ns:
                self.show(preview_path, render)
                shown_mtime_ns = mtime_ns
                previews_shown += 1
            self.update_progress(reader.fraction)
            time.sleep(POLL_INTERVAL_S)
        stderr_text = reader.text()  # joins the reader: its count is final
        global last_render_progress_lines, last_render_previews_shown
        last_render_progress_lines = reader.progress_lines
        last_render_previews_shown = previews_shown
        return process.returncode, stderr_text

    def show(self, exr_path, render):
        """An EXR of filmback's into the Render Result: each preview while filmback goes on, then
        the final image, which replaces the last preview."""
        result = self.begin_result(0, 0, *result_size(render))
        if self.with_passes:  # a multi-layer EXR: every pass by its layer and pass names
            result.load_from_file(exr_path)
        else:
            result.layers[0].load_from_file(exr_path)
        self.update_result(result)
        self.end_result(result)


    def add_cryptomatte_metadata(self, exr_path):
        """Cryptomatte's manifests (the EXR's cryptomatte/<key>/... attributes) into the whole
        Render Result's metadata, where the Cryptomatte node looks for them and from which Blender
        writes them into the files it saves: what Cycles does with its own (get_result(), not a
        tile's result, holds the metadata)."""
        result = self.get_result()
        for name, value in exr_header.string_attributes(exr_path).items():
            if name.startswith("cryptomatte/"):
                result.stamp_data_add_field(name, value)


def register():
    bpy.utils.register_class(FilmbackRenderEngine)
    main_thread.register()


def unregister():
    main_thread.unregister()
    bpy.utils.unregister_class(FilmbackRenderEngine)
