"""Running a piece of bpy work on Blender's main thread from a render engine's render().

F12 in Blender's window runs the render as a job on another thread, whose context has no window,
no active object and no view layer, and on which operators must not run: Blender's glTF exporter
(an operator that also moves the scene's frame) fails there with `'Context' object has no
attribute 'active_object'`. Under `blender -b`, or a blocking `bpy.ops.render.render()` from a
script, render() runs on the main thread itself and the work runs directly.

Blender's timers are the way onto the main thread, but registering one from another thread
crashes Blender 3.4 (measured: a segfault in the main loop), so one timer, registered with the
add-on, takes the work from a queue (the pattern of Blender's own bpy.app.timers example).
"""

import queue
import threading

import bpy

IDLE_POLL_S = 0.2  # how long a request from the render thread waits at most to start
WAIT_SLICE_S = 0.1

_requests = queue.SimpleQueue()


def main_window(scene):
    """The window showing `scene` (the first if none does): the context operators expect."""
    windows = list(bpy.context.window_manager.windows)
    return next((w for w in windows if w.scene == scene), windows[0] if windows else None)


class _Request:
    def __init__(self, scene, work):
        self.scene, self.work = scene, work
        self.value = self.error = None
        self.done = threading.Event()

    def run(self):
        window = main_window(self.scene)
        try:
            if window is None:
                self.value = self.work()
            else:
                with bpy.context.temp_override(window=window, screen=window.screen):
                    self.value = self.work()
        except Exception as e:  # handed to the render thread, which reports it
            self.error = e
        self.done.set()


def _serve_requests():
    while True:
        try:
            _requests.get_nowait().run()
        except queue.Empty:
            return IDLE_POLL_S


def run_on_main_thread(scene, work):
    """Returns work()'s result, or raises its exception, having run it on the main thread with
    the context of `scene`'s window."""
    if threading.current_thread() is threading.main_thread():
        return work()
    request = _Request(scene, work)
    _requests.put(request)
    while not request.done.wait(WAIT_SLICE_S):
        pass
    if request.error is not None:
        raise request.error
    return request.value


def register():
    # persistent: the timer survives loading another .blend file
    bpy.app.timers.register(_serve_requests, first_interval=IDLE_POLL_S, persistent=True)


def unregister():
    if bpy.app.timers.is_registered(_serve_requests):
        bpy.app.timers.unregister(_serve_requests)
