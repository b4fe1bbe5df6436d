"""Runs inside Blender with its window (not `blender -b`), under Xvfb, for engine_window_test.py:
installs the add-on from a zip, builds render_engine_case.py's shot, presses F12 as the user does
(`render.render` invoked, so Blender runs the render as a job and shows it in its render view),
takes a screenshot of Blender's window once the render is complete, then presses Ctrl+F12, then
F12 on a render far too long to finish and Esc a few seconds into it.

    blender --factory-startup --python engine_window_case.py -- ZIP FILMBACK OUT [SAMPLES]

Esc is pressed through the X server (`xdotool`, the XTEST extension), so that it reaches Blender
as a key on the keyboard does: Blender sets its break flag only for key events that come from the
window system (`Window.event_simulate`'s do not stop a render), and the engine reads it through
test_break().

Writes OUT/window.png (the screenshot), OUT/result.exr (the Render Result as Blender shows it),
OUT/anim_000N.exr (the frames), OUT/cancelled.exr (the Render Result after Esc) and OUT/passed
when each image is bit-identical to a command-line render of the add-on's export of its frame and
Esc returned promptly with a partial image. A render cancelled other than by the case's Esc quits
Blender without OUT/passed; a case not done within CASE_LIMIT_S prints where it was (each stage is
logged with its time, and every thread's Python stack) and ends Blender at once (exit 3) and the
filmback it started. Esc waits for filmback's first preview (at most
ESCAPE_WITHOUT_PREVIEW_S) and is pressed again if the render goes on (a key that came while
Blender was not reading events): its return time counts from the last press.
"""

import faulthandler
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
import traceback

import glob

import bpy
import numpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import render_engine_case as shot  # noqa: E402

WIDTH_PX, HEIGHT_PX = 480, 270  # the render view shows it at 1:1 in a 1280 x 720 window
SAMPLES = 16  # the test's; docs/blender.md's screenshot passes more
# The whole case (three renders, their checks, the Esc stage), under CI's load; the driver
# (engine_window_test.TIMEOUT_S) allows 420 s. A watchdog thread, not Blender's timers: a stop
# must also come when Blender's main thread is stuck. Past the watchdog, faulthandler's own
# thread dumps the stacks and exits, should the watchdog not get Python's lock.
CASE_LIMIT_S = 360.0
LAST_RESORT_S = CASE_LIMIT_S + 20.0
WATCH_INTERVAL_S = 0.2
SETTLE_S = 1.0  # after the render job, for the render view to redraw the final image
ESCAPE_AFTER_PREVIEW_S = 1.0  # for the engine (polling every 0.1 s) to show filmback's preview
# On a loaded machine the first preview can be late: Esc then comes this long after F12 anyway.
ESCAPE_WITHOUT_PREVIEW_S = 40.0
# An Esc the window did not take (XTEST while Blender was not reading events) is pressed again,
# at most this many times, this long apart; the return time counts from the last press.
ESCAPE_RETRY_S, ESCAPE_PRESSES = 10.0, 3


def window_override():
    """The context of Blender's main window and its largest area, which operators started from a
    timer need (a timer runs without a window in its context)."""
    window = bpy.context.window_manager.windows[0]
    area = max(window.screen.areas, key=lambda a: a.width * a.height)
    return bpy.context.temp_override(window=window, screen=window.screen, area=area)


def press_escape():
    """Esc with the pointer in the middle of Blender's window (which has the keyboard focus
    without a window manager), as the keyboard gives it. Not waited for: Blender's main thread
    must go on to read the key."""
    window = bpy.context.window_manager.windows[0]
    return subprocess.Popen(["xdotool", "mousemove", str(window.width // 2), str(window.height // 2),
                      "key", "Escape"])


def kill_own_filmback():
    """Kills the filmback processes this Blender started (the engine's render), so that a case
    that failed does not leave a render of hours behind it."""
    for stat in glob.glob("/proc/[0-9]*/stat"):
        try:
            with open(stat) as f:
                fields = f.read().rsplit(")", 1)[1].split()
            name = open(os.path.join(os.path.dirname(stat), "comm")).read().strip()
        except OSError:
            continue  # a process that ended meanwhile
        if name == "filmback" and int(fields[1]) == os.getpid():
            os.kill(int(os.path.basename(os.path.dirname(stat))), signal.SIGKILL)


def preview_written():
    """Whether filmback has written a preview of the render in progress: in the engine's
    temporary folder (under TMPDIR, which engine_window_test.py gives the case)."""
    return bool(glob.glob(os.path.join(tempfile.gettempdir(), "filmback-render-*", "preview.exr")))


def log(message):
    """A line of the case's progress on stderr, with the time since Blender started it, which
    the driver prints whether the case passed, failed or was stopped."""
    print(f"engine_window_case: {time.monotonic() - STARTED:6.1f} s: {message}", file=sys.stderr,
          flush=True)


STARTED = time.monotonic()


def show_render_properties():
    """The Properties editor on its Render tab: the engine list and filmback's settings panel."""
    for window in bpy.context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == "PROPERTIES":
                area.spaces.active.context = "RENDER"


class WindowCase:
    """F12, checked and photographed, then Ctrl+F12, each frame checked, then F12 and Esc. Blender
    calls the render handlers on the render job's thread, where registering a timer crashes it:
    they only set `state`, which a timer on the main thread watches."""

    def __init__(self, filmback, out, samples):
        self.filmback, self.out, self.samples = filmback, out, samples
        self.state = None  # "complete" or "cancelled", set by the handlers
        self.started = self.ended = None
        self.awaiting_preview = False  # Esc is due once filmback shows its first preview
        self.escape_at = self.escaped = None  # when Esc is due, when it was pressed
        self.escape_key = None  # the xdotool that pressed it
        self.escape_presses = 0
        self.check = None  # what to do once the render in progress has ended
        self.watchdog = threading.Timer(CASE_LIMIT_S, self.stop_case)
        self.watchdog.daemon = True

    def start(self):
        self.watchdog.start()
        faulthandler.dump_traceback_later(LAST_RESORT_S, exit=True)
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
        self.state, self.ended, self.check = None, None, check
        self.started = time.monotonic()
        log(f"{'Ctrl+F12' if animation else 'F12'} for {check.__name__}")
        with window_override():
            bpy.ops.render.render("INVOKE_DEFAULT", animation=animation)

    def on_render_complete(self, scene, _depsgraph=None):
        self.state = "complete"

    def on_render_cancel(self, scene, _depsgraph=None):
        self.state = "cancelled"

    def watch(self):
        now = time.monotonic()
        if self.awaiting_preview and (preview_written() or
                                      now - self.started >= ESCAPE_WITHOUT_PREVIEW_S):
            self.awaiting_preview, self.escape_at = False, now + ESCAPE_AFTER_PREVIEW_S
        if self.escape_at is not None and now >= self.escape_at:
            self.escape_key = press_escape()
            self.escape_presses += 1
            log(f"Esc pressed ({self.escape_presses}), preview written: {preview_written()}")
            self.escape_at, self.escaped = None, now
        elif (self.escaped is not None and self.state is None and
              now - self.escaped >= ESCAPE_RETRY_S and self.escape_presses < ESCAPE_PRESSES):
            self.escape_at = now
        # The handlers run before Blender's render job has ended (an animation's, or any under
        # load, can go on for seconds): until it has, operators refuse to run ("can't modify
        # blend data in this state (drawing/rendering)"), the exporter and quitting included.
        if self.state is not None and self.ended is None and not bpy.app.is_job_running("RENDER"):
            self.ended = now
            log(f"the render job ended ({self.state}) after {now - self.started:.1f} s")
        if self.ended is not None and now - self.ended >= SETTLE_S:
            try:
                if self.check():  # done
                    self.quit()
                    return None
            except Exception:
                traceback.print_exc()
                self.quit("the render did not check out")
                return None
        return WATCH_INTERVAL_S

    def stop_case(self):
        """The watchdog's: where the case was, every thread's stack, then Blender ended at once
        (it does not quit while a render job runs) with the filmback it started."""
        log(f"not done within {CASE_LIMIT_S} s: waiting for {self.check.__name__}, render "
            f"{self.state or 'running'}, Esc pressed {self.escape_presses} times")
        faulthandler.dump_traceback(file=sys.stderr, all_threads=True)
        kill_own_filmback()
        os._exit(3)

    def assert_complete(self):
        assert self.state == "complete", f"the render ended {self.state}, not complete"

    def command_line_render(self, frame):
        with window_override():  # the exporter is an operator: it needs the window's context
            return shot.command_line_render(self.filmback, self.out, frame)

    def check_still(self):
        """The F12 image in the render view: photographed, then compared; Ctrl+F12 next."""
        self.assert_complete()
        log("checking the F12 image")
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
        """Ctrl+F12: each frame's file equal to its frame's command-line render; F12 and Esc
        next, on a render that would run for hours (as render_engine_case's cancel case)."""
        self.assert_complete()
        log("checking the frames")
        for frame in range(shot.FIRST_FRAME, shot.LAST_FRAME + 1):
            frame_path = os.path.join(self.out, f"anim_{frame:04d}.exr")
            assert os.path.exists(frame_path), f"frame {frame} was not written"
            shot.assert_bit_identical(frame_path, self.command_line_render(frame),
                                      (WIDTH_PX, HEIGHT_PX))
        scene = bpy.context.scene
        scene.frame_set(shot.FIRST_FRAME)
        scene.filmback.samples = shot.CANCEL_SAMPLES
        scene.cycles.use_adaptive_sampling = False
        self.awaiting_preview = True
        self.render(self.check_cancelled)
        return False

    def check_cancelled(self):
        """Esc: the render ended cancelled, soon after the key, with the image so far shown."""
        assert self.escaped is not None, f"the long render ended ({self.state}) before Esc"
        assert self.escape_key.wait(timeout=10) == 0, "xdotool could not press Esc"
        assert self.state == "cancelled", f"the render ended {self.state} after Esc"
        returned_s = self.ended - self.escaped
        assert returned_s < shot.CANCEL_RETURN_LIMIT_S, f"Esc took {returned_s:.1f} s to stop it"
        cancelled_path = os.path.join(self.out, "cancelled.exr")
        bpy.data.images["Render Result"].save_render(cancelled_path, scene=bpy.context.scene)
        rgba = shot.pixels(cancelled_path)
        assert numpy.isfinite(rgba).all() and rgba[:, :3].max() > 0, "no partial image after Esc"
        print(f"engine_window_case: Esc stopped the render in {returned_s:.1f} s "
              f"(pressed {self.escape_presses} times), partial image kept")
        with open(os.path.join(self.out, "passed"), "w") as f:
            f.write("window\n")
        return True

    def quit(self, failure=None):
        if failure:
            log(failure)
        try:
            bpy.ops.wm.quit_blender()
        except RuntimeError:  # Blender would go on to the watchdog's limit: end it now
            traceback.print_exc()
            kill_own_filmback()
            os._exit(3)


def main():
    zip_path, filmback, out, *samples = sys.argv[sys.argv.index("--") + 1:]
    shot.install_addon(zip_path, filmback)
    # A fresh user folder would show the first run's splash over the render view.
    bpy.context.preferences.view.show_splash = False
    case = WindowCase(filmback, out, int(samples[0]) if samples else SAMPLES)
    # Blender's window exists once the event loop runs: start from its first timer tick.
    bpy.app.timers.register(lambda: case.start(), first_interval=0.5)


main()
