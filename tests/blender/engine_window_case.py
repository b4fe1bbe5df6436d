"""Runs inside Blender with its window (not `blender -b`), under Xvfb, for engine_window_test.py:
installs the add-on from a zip, builds render_engine_case.py's shot, presses F12 as the user does
(`render.render` invoked, so Blender runs the render as a job and shows it in its render view),
takes a screenshot of Blender's window once the render is complete, then presses Ctrl+F12.

    blender --factory-startup --python engine_window_case.py -- ZIP FILMBACK OUT [SAMPLES]

Writes OUT/window.png (the screenshot), OUT/result.exr (the Render Result as Blender shows it),
OUT/anim_000N.exr (the frames), and OUT/passed when each image is bit-identical to a command-line
render of the add-on's export of its frame. A render cancelled, or not finished within
WINDOW_TIMEOUT_S, quits Blender without OUT/passed.
"""

import os
import sys
import time
import traceback

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import render_engine_case as shot  # noqa: E402

WIDTH_PX, HEIGHT_PX = 480, 270  # the render view shows it at 1:1 in a 1280 x 720 window
SAMPLES = 16  # the test's; docs/blender.md's screenshot passes more
WINDOW_TIMEOUT_S = 180.0  # per render
WATCH_INTERVAL_S = 0.2
SETTLE_S = 1.0  # for the render view to redraw the final image before the screenshot


def window_override():
    """The context of Blender's main window and its largest area, which operators started from a
    timer need (a timer runs without a window in its context)."""
    window = bpy.context.window_manager.windows[0]
    area = max(window.screen.areas, key=lambda a: a.width * a.height)
    return bpy.context.temp_override(window=window, screen=window.screen, area=area)


def show_render_properties():
    """The Properties editor on its Render tab: the engine list and filmback's settings panel."""
    for window in bpy.context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == "PROPERTIES":
                area.spaces.active.context = "RENDER"


class WindowCase:
    """F12, checked and photographed, then Ctrl+F12, each frame checked. Blender calls the render
    handlers on the render job's thread, where registering a timer crashes it: they only set
    `state`, which a timer on the main thread watches."""

    def __init__(self, filmback, out, samples):
        self.filmback, self.out, self.samples = filmback, out, samples
        self.state = None  # "complete" or "cancelled", set by the handlers
        self.started = self.completed = None
        self.check = None  # what to do once the render in progress is complete

    def start(self):
        scene = shot.build_shot()
        scene.render.resolution_x, scene.render.resolution_y = WIDTH_PX, HEIGHT_PX
        scene.filmback.samples = self.samples
        # The render view replaces the largest area of the window (the "Image Editor" render
        # display; "Maximized Area" crashes Blender 3.4 when F12 comes from a script's timer).
        bpy.context.preferences.view.render_display_type = "AREA"
        show_render_properties()
        bpy.app.handlers.render_complete.append(self.on_render_complete)
        bpy.app.handlers.render_cancel.append(self.on_render_cancel)
        self.render(self.check_still)
        bpy.app.timers.register(self.watch, first_interval=WATCH_INTERVAL_S)

    def render(self, check, animation=False):
        self.state, self.completed, self.check = None, None, check
        self.started = time.monotonic()
        with window_override():
            bpy.ops.render.render("INVOKE_DEFAULT", animation=animation)

    def on_render_complete(self, scene, _depsgraph=None):
        self.state = "complete"

    def on_render_cancel(self, scene, _depsgraph=None):
        self.state = "cancelled"

    def watch(self):
        now = time.monotonic()
        if self.state == "complete" and self.completed is None:
            self.completed = now
        if self.completed is not None and now - self.completed >= SETTLE_S:
            try:
                if self.check():  # done
                    self.quit()
                    return None
            except Exception:
                traceback.print_exc()
                self.quit("the finished render did not check out")
                return None
        elif self.state == "cancelled":
            self.quit("the render was cancelled")
            return None
        elif now - self.started >= WINDOW_TIMEOUT_S:
            self.quit(f"no complete render within {WINDOW_TIMEOUT_S} s")
            return None
        return WATCH_INTERVAL_S

    def command_line_render(self, frame):
        with window_override():  # the exporter is an operator: it needs the window's context
            return shot.command_line_render(self.filmback, self.out, frame)

    def check_still(self):
        """The F12 image in the render view: photographed, then compared; Ctrl+F12 next."""
        with window_override():
            bpy.ops.screen.screenshot(filepath=os.path.join(self.out, "window.png"))
        scene = bpy.context.scene
        scene.render.image_settings.file_format = "OPEN_EXR"
        result_path = os.path.join(self.out, "result.exr")
        bpy.data.images["Render Result"].save_render(result_path, scene=scene)
        shot.assert_bit_identical(result_path, self.command_line_render(shot.FIRST_FRAME),
                                  (WIDTH_PX, HEIGHT_PX))
        scene.render.filepath = os.path.join(self.out, "anim_")
        self.render(self.check_animation, animation=True)
        return False

    def check_animation(self):
        """Ctrl+F12: each frame's file equal to its frame's command-line render."""
        for frame in range(shot.FIRST_FRAME, shot.LAST_FRAME + 1):
            frame_path = os.path.join(self.out, f"anim_{frame:04d}.exr")
            assert os.path.exists(frame_path), f"frame {frame} was not written"
            shot.assert_bit_identical(frame_path, self.command_line_render(frame),
                                      (WIDTH_PX, HEIGHT_PX))
        with open(os.path.join(self.out, "passed"), "w") as f:
            f.write("window\n")
        return True

    def quit(self, failure=None):
        if failure:
            print(f"engine_window_case: {failure}", file=sys.stderr)
        bpy.ops.wm.quit_blender()


def main():
    zip_path, filmback, out, *samples = sys.argv[sys.argv.index("--") + 1:]
    shot.install_addon(zip_path, filmback)
    # A fresh user folder would show the first run's splash over the render view.
    bpy.context.preferences.view.show_splash = False
    case = WindowCase(filmback, out, int(samples[0]) if samples else SAMPLES)
    # Blender's window exists once the event loop runs: start from its first timer tick.
    bpy.app.timers.register(lambda: case.start(), first_interval=0.5)


main()
