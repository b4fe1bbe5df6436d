"""The `filmback` command line as the render engine uses it: where it is, what plugins it finds,
the render command for the engine's settings, and what its stderr says.

No bpy here: the engine (render_engine.py) and the panel (render_settings.py) hand in what they
read from Blender.
"""

import os
import re
import shutil
import subprocess

# `filmback plugins` prints one unindented line per plugin, `KIND NAME VERSION - description`,
# followed by its indented parameters (docs/cli.md); the `searched:` header does not match.
PLUGIN_LINE = re.compile(r"^(camera|filter|integrator) ([a-z0-9_]+) \S+ - ")

# With --progress-every filmback prints `progress: 12.5% after 10s, ETA 1m10s` at that interval
# on its piped stderr (without it, only every 10 s: short renders would show no progress).
PROGRESS_EVERY = "0.25s"
PROGRESS_LINE = re.compile(r"^progress: ([0-9.]+)%")

# With --preview filmback replaces an EXR of the image so far (atomically) at most this often
# while rendering (docs/cli.md, "--preview"): the engine shows it as the image fills in.
PREVIEW_EVERY = "1s"

# What the importer skipped, once each (core/util/diagnostics.cpp).
WARNING_LINE = re.compile(r"^(filmback: )?warning: ")

# Samplers are built in, not plugins (docs/cli.md, `--sampler KIND`).
SAMPLERS = ("sobol", "zsobol", "stratified", "independent")

# Exit statuses of an interrupted render that still wrote the image so far (docs/cli.md).
INTERRUPTED_STATUSES = (130, 143)

PLUGINS_TIMEOUT_S = 30

_plugins_by_executable = {}


def find_executable(preferred_path):
    """The filmback to run: the preferences' path when set, else `filmback` on PATH; None when
    neither names an executable file."""
    if preferred_path:
        path = os.path.abspath(os.path.expanduser(preferred_path))
        return path if os.path.isfile(path) and os.access(path, os.X_OK) else None
    return shutil.which("filmback")


def plugin_names(executable):
    """{kind: [name, ...]} from `filmback plugins`, asked once per executable (the panel redraws
    often); raises RuntimeError with filmback's message when it fails."""
    if executable not in _plugins_by_executable:
        r = subprocess.run([executable, "plugins"], capture_output=True, text=True,
                           timeout=PLUGINS_TIMEOUT_S)
        if r.returncode != 0:
            raise RuntimeError(error_message(r.stderr) or f"{executable} plugins: exit {r.returncode}")
        found = {}
        for line in r.stdout.splitlines():
            match = PLUGIN_LINE.match(line)
            if match:
                found.setdefault(match.group(1), []).append(match.group(2))
        _plugins_by_executable[executable] = found
    return _plugins_by_executable[executable]


def render_command(executable, scene_path, output_path, preview_path, samples, sampler,
                   integrator, filter_spec, passes=(), view_layer=None,
                   cryptomatte_levels=None):
    """The argument list (no shell) rendering `scene_path` into `output_path`, the image so far
    into `preview_path` while it renders. An empty integrator or filter leaves the shot's own
    (the file's pixel filter, the path integrator); `passes` are Blender's pass names written
    beside the beauty (docs/cli.md, --passes), in the layer named `view_layer`, the Cryptomatte
    ones with `cryptomatte_levels` ranks per pixel."""
    command = [executable, "render", scene_path, "-o", output_path,
               "--spp", str(samples), "--sampler", sampler, "--progress-every", PROGRESS_EVERY,
               "--preview", preview_path, "--preview-every", PREVIEW_EVERY]
    if integrator:
        command += ["--integrator", integrator]
    if filter_spec:
        command += ["--filter", filter_spec]
    if passes:
        command += ["--passes", ",".join(passes)]
        if view_layer:
            command += ["--view-layer", view_layer]
        if cryptomatte_levels and any(p.startswith("Crypto") for p in passes):
            command += ["--cryptomatte-levels", str(cryptomatte_levels)]
    return command


def progress_fraction(line):
    """The fraction done a progress line reports, or None for any other line."""
    match = PROGRESS_LINE.match(line)
    return min(float(match.group(1)) / 100.0, 1.0) if match else None


def error_message(stderr_text):
    """filmback's error lines (`filmback: error: ...`), else its last non-empty line."""
    lines = [line.strip() for line in stderr_text.splitlines() if line.strip()]
    errors = [line for line in lines if "error:" in line]
    return "\n".join(errors) if errors else (lines[-1] if lines else "")


def warnings(stderr_text):
    """filmback's warnings, in its order, each as `filmback: WHAT` (Blender's report says that
    it is a warning)."""
    return ["filmback: " + line[WARNING_LINE.match(line).end():].strip()
            for line in stderr_text.splitlines() if WARNING_LINE.match(line)]
