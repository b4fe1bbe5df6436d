"""The filmback render engine in Blender's window, not under `blender -b` (issue 20):

    engine_window_test.py --filmback EXE --scratch DIR [--samples N] [--screenshot PNG]

Installs the add-on from a zip into a fresh user folder and runs engine_window_case.py in a
Blender with its window on a virtual X display (xvfb-run, Debian's package `xvfb`). There F12
runs the render as a job on another thread, as it does for a user, which `blender -b` never
does: the export must still work, the image must show in the render view, and it must be
bit-identical to a command-line render of the export; Ctrl+F12 renders the frames, and Esc
(pressed through the X server) stops a long render promptly with its partial image. With --screenshot, the screenshot of
Blender's window is copied there (docs/blender.md's picture is made so).
Exit 77 (CTest's skip) when `blender`, `xvfb-run` or `xdotool` is not installed.
"""

import argparse
import os
import shutil
import signal
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from roundtrip_test import (  # noqa: E402
    addon_zip, blender_env, fresh_folder, skip_unless_installed)

SCREEN = "1280x720x24"  # the screenshot's size
TIMEOUT_S = 420  # F12, Ctrl+F12 over three frames and the Esc stage, beside CI's other tests;
# the case stops itself earlier (engine_window_case.CASE_LIMIT_S), with what it was waiting for
PYTHON_ERROR_EXIT = 2  # Blender's own exit status is 1 after Esc (WM_exit: exit(G.is_break))


def run_in_own_session(command, env):
    """Runs `command` in a session of its own and returns (exit status, stdout, stderr); the
    status is None when it ran past TIMEOUT_S, and then the whole session (xvfb-run, Xvfb,
    Blender and the filmback it started) is killed, so that what it printed can be read (killing
    xvfb-run alone leaves Blender holding the pipes)."""
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               env=env, start_new_session=True)
    try:
        stdout, stderr = process.communicate(timeout=TIMEOUT_S)
        return process.returncode, stdout, stderr
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        stdout, stderr = process.communicate()
        return None, stdout, stderr


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--filmback", required=True)
    p.add_argument("--scratch", required=True)
    p.add_argument("--samples", type=int)
    p.add_argument("--screenshot")
    a = p.parse_args()
    skip_unless_installed("blender", ("xvfb-run", "xvfb"), "xdotool")
    temporary = fresh_folder(os.path.join(fresh_folder(a.scratch), "tmp"))
    env = blender_env(dict(BLENDER_USER_SCRIPTS=os.path.join(a.scratch, "scripts"),
                           BLENDER_USER_CONFIG=os.path.join(a.scratch, "config"),
                           TMPDIR=temporary))
    command = ["xvfb-run", "--auto-servernum", "--server-args", f"-screen 0 {SCREEN}",
               "blender", "--factory-startup", "--python-exit-code", str(PYTHON_ERROR_EXIT),
               "--python", os.path.join(HERE, "engine_window_case.py"), "--",
               addon_zip(a.scratch), os.path.abspath(a.filmback), a.scratch]
    if a.samples:
        command.append(str(a.samples))
    returncode, stdout, stderr = run_in_own_session(command, env)
    print(stdout)
    print(stderr, file=sys.stderr)
    if returncode is None:
        sys.exit(f"engine_window_case.py did not end within {TIMEOUT_S} s: Blender, Xvfb and "
                 "filmback were killed (the case's log above says where it was)")
    if returncode not in (0, 1) or not os.path.exists(os.path.join(a.scratch, "passed")):
        sys.exit(f"engine_window_case.py failed (exit {returncode})")
    left = [name for name in os.listdir(temporary) if name.startswith("filmback")]
    if left:
        sys.exit(f"temporary files left in {temporary}: {left}")
    if a.screenshot:
        shutil.copyfile(os.path.join(a.scratch, "window.png"), a.screenshot)


if __name__ == "__main__":
    main()
