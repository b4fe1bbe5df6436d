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
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from roundtrip_test import (  # noqa: E402
    addon_zip, blender_env, fresh_folder, skip_unless_installed)

SCREEN = "1280x720x24"  # the screenshot's size
TIMEOUT_S = 420  # F12, Ctrl+F12 over three frames and the Esc stage, beside CI's other tests
PYTHON_ERROR_EXIT = 2  # Blender's own exit status is 1 after Esc (WM_exit: exit(G.is_break))


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
    r = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT_S, env=env)
    print(r.stdout)
    print(r.stderr, file=sys.stderr)
    if r.returncode not in (0, 1) or not os.path.exists(os.path.join(a.scratch, "passed")):
        sys.exit(f"engine_window_case.py failed (exit {r.returncode})")
    left = [name for name in os.listdir(temporary) if name.startswith("filmback")]
    if left:
        sys.exit(f"temporary files left in {temporary}: {left}")
    if a.screenshot:
        shutil.copyfile(os.path.join(a.scratch, "window.png"), a.screenshot)


if __name__ == "__main__":
    main()
