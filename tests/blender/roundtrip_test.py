"""Export -> import round trip of Blender's physical cameras, through the add-on (issue 4).

    roundtrip_test.py --filmback EXE --scratch DIR [--node-modules DIR] CASE

Cases (one CTest test each, label blender; exit 77, CTest's skip, when a tool is missing):
  roundtrip     every physical camera value bpy reads equals what `filmback info` prints (exact,
                float32 values widened to double; the focus object's depth, derived in float32 on both
                sides, within 4 float32 ulps)
  validator     the add-on's glTF passes the Khronos glTF validator (npm gltf-validator) with
                no errors and no warnings
  addon_install the add-on installs from a zip as a normal add-on (Preferences > Add-ons >
                Install) into a fresh user folder, and Blender's own File > Export > glTF then
                writes the FILMBACK_blender extension
  command_line  `blender -b shot.blend --python importers/blender/export_shot.py -- out.gltf`
                writes the file; a wrong output name exits non-zero with a message
"""

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
ADDON_DIR = os.path.join(HERE, "..", "..", "importers", "blender")
SKIP = 77


def blender_env(extra=None):
    """The environment without this driver's own interpreter: Blender's embedded Python takes its
    home from the first python3 on PATH, and a pyenv or venv interpreter there hides Debian's
    packages (numpy, which Blender's glTF exporter imports) from it. Debian's own folder stays
    when this driver is Debian's python3: it is the right home, and it holds `blender`."""
    own_bin = os.path.realpath(os.path.join(sys.prefix, "bin"))
    path = [p for p in os.environ.get("PATH", "").split(os.pathsep)
            if p and (os.path.realpath(p) != own_bin or own_bin == "/usr/bin") and
            ".pyenv" not in p]
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONHOME", "PYTHONPATH")}
    env["PATH"] = os.pathsep.join(path)
    env.update(extra or {})
    return env


def skip_unless_installed(*programs):
    """Exits with CTest's skip status unless every program is on PATH; each is a name that is
    its own Debian package, or a (program, package) pair."""
    for program in programs:
        name, package = program if isinstance(program, tuple) else (program, program)
        if shutil.which(name) is None:
            print(f"skipped: Debian package {package} is not installed")
            sys.exit(SKIP)


def fresh_folder(path):
    """Empties the folder `path` (making it if need be) and returns its absolute path: a case
    starts from nothing that an earlier run left."""
    shutil.rmtree(path, ignore_errors=True)
    os.makedirs(path)
    return os.path.abspath(path)


def blender(*args, env=None, blend_file=None):
    command = ["blender", "-b"] + ([blend_file] if blend_file else ["--factory-startup"])
    return subprocess.run(command + list(args), capture_output=True, text=True, timeout=240,
                          env=blender_env(env))


def driver_arguments(cases=None):
    """A driver's command line, --filmback EXE --scratch DIR, then one of `cases` when it has
    some: the parsed arguments, the scratch folder absolute and emptied. Exits SKIP (CTest's
    skip) when `blender` is not installed."""
    p = argparse.ArgumentParser()
    p.add_argument("--filmback", required=True)
    p.add_argument("--scratch", required=True)
    if cases:
        p.add_argument("case", choices=cases)
    a = p.parse_args()
    skip_unless_installed("blender")
    a.scratch = fresh_folder(a.scratch)
    return a


def build_scene(scratch):
    """Runs roundtrip_scene.py once per scratch folder; returns its folder."""
    out = os.path.join(scratch, "scene")
    if not os.path.exists(os.path.join(out, "expected.json")):
        r = blender("--python", os.path.join(HERE, "roundtrip_scene.py"), "--", out)
        if r.returncode != 0 or not os.path.exists(os.path.join(out, "shot.gltf")):
            sys.exit(f"roundtrip_scene.py failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return out


def exact_values(filmback, gltf, camera):
    r = subprocess.run([filmback, "info", gltf, "--camera", camera], capture_output=True,
                       text=True, timeout=60)
    if r.returncode != 0:
        sys.exit(f"filmback info --camera {camera} failed: {r.stderr}")
    line = next(l for l in r.stdout.splitlines() if l.strip().startswith("exact:"))
    return dict(item.split("=", 1) for item in line.split()[1:])


def case_roundtrip(a):
    folder = build_scene(a.scratch)
    with open(os.path.join(folder, "expected.json")) as f:
        expected = json.load(f)
    failures, compared = [], 0
    for camera, values in expected.items():
        printed = exact_values(a.filmback, os.path.join(folder, "shot.gltf"), camera)
        for key, want in values.items():
            got = printed.get(key)
            compared += 1
            if isinstance(want, str):
                ok = got == want
            else:
                value = float(got)
                # Only the focus object's depth is derived, by a different route on each side,
                # both in Blender's float32 mathutils: within 4 float32 ulps.
                tolerance = 4 * 2.0**-23 * abs(want) if key == "focus_distance_m" else 0.0
                ok = value == want or (math.isfinite(want) and abs(value - want) <= tolerance)
            if not ok:
                failures.append(f"{camera}.{key}: bpy {want!r}, filmback info {got!r}")
    print(f"compared {compared} values of {len(expected)} cameras")
    if failures:
        sys.exit("\n".join(failures))


def require_validator(modules):
    """Exits with CTest's skip unless the npm package gltf-validator is under `modules`."""
    if not modules or not os.path.isdir(os.path.join(modules, "gltf-validator")) or \
            shutil.which("node") is None:
        print(f"skipped: npm package gltf-validator not installed under {modules!r} "
              "(./setup.sh test installs it)")
        sys.exit(SKIP)


def validate(modules, gltf):
    """Exits with a message unless the Khronos glTF validator passes `gltf` with no errors and
    no warnings."""
    r = subprocess.run(["node", os.path.join(HERE, "validate_gltf.js"), modules, gltf],
                       capture_output=True, text=True, timeout=120)
    print(r.stdout, r.stderr)
    if r.returncode != 0 or " 0 errors, 0 warnings" not in r.stdout:
        sys.exit("the glTF validator reports errors or warnings")


def case_validator(a):
    require_validator(a.node_modules)
    validate(a.node_modules, os.path.join(build_scene(a.scratch), "shot.gltf"))


def addon_zip(folder):
    """The add-on as a user installs it: io_filmback.zip, made in `folder`; returns its path."""
    package = os.path.join(folder, "io_filmback.zip")
    with zipfile.ZipFile(package, "w") as z:
        for name in sorted(os.listdir(os.path.join(ADDON_DIR, "io_filmback"))):
            if name.endswith(".py"):
                z.write(os.path.join(ADDON_DIR, "io_filmback", name), f"io_filmback/{name}")
    return package


def case_addon_install(a):
    root = os.path.join(a.scratch, "addon_install")
    shutil.rmtree(root, ignore_errors=True)
    os.makedirs(root)
    package = addon_zip(root)
    script = os.path.join(root, "install.py")
    out = os.path.join(root, "out.gltf")
    with open(script, "w") as f:
        f.write(f"""import bpy, sys
bpy.ops.preferences.addon_install(filepath={package!r})
bpy.ops.preferences.addon_enable(module="io_filmback")
assert "io_filmback" in bpy.context.preferences.addons, "not enabled"
bpy.ops.export_scene.gltf(filepath={out!r}, export_format="GLTF_SEPARATE", export_cameras=True)
""")
    env = dict(BLENDER_USER_SCRIPTS=os.path.join(root, "scripts"),
               BLENDER_USER_CONFIG=os.path.join(root, "config"))
    r = blender("--python-exit-code", "1", "--python", script, env=env)
    installed = os.path.join(root, "scripts", "addons", "io_filmback", "__init__.py")
    if r.returncode != 0 or not os.path.exists(installed) or not os.path.exists(out):
        sys.exit(f"install failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    with open(out) as f:
        gltf = json.load(f)
    assert "FILMBACK_blender" in gltf["extensionsUsed"], gltf.get("extensionsUsed")
    assert "FILMBACK_blender" in gltf["cameras"][0]["extensions"]
    assert "FILMBACK_blender" not in gltf.get("extensionsRequired", [])
    print("installed to", installed, "and exported through File > Export > glTF 2.0")


def case_command_line(a):
    folder = build_scene(a.scratch)
    entry = os.path.join(ADDON_DIR, "export_shot.py")
    out = os.path.join(a.scratch, "command_line.gltf")
    if os.path.exists(out):
        os.remove(out)
    r = blender("--python", entry, "--", out, blend_file=os.path.join(folder, "shot.blend"))
    if r.returncode != 0 or not os.path.exists(out):
        sys.exit(f"export_shot.py failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    with open(out) as f:
        assert "FILMBACK_blender" in json.load(f)["scenes"][0]["extensions"]
    r = blender("--python", entry, "--", os.path.join(a.scratch, "out.txt"),
                blend_file=os.path.join(folder, "shot.blend"))
    if r.returncode == 0 or "usage:" not in r.stderr:
        sys.exit(f"a wrong output name: exit {r.returncode}, stderr {r.stderr!r}")


CASES = {"roundtrip": case_roundtrip, "validator": case_validator,
         "addon_install": case_addon_install, "command_line": case_command_line}


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--list", action="store_true")
    p.add_argument("--filmback")
    p.add_argument("--scratch")
    p.add_argument("--node-modules")
    p.add_argument("case", nargs="?")
    a = p.parse_args()
    if a.list:
        print(" ".join(CASES))
        return
    skip_unless_installed("blender")
    os.makedirs(a.scratch, exist_ok=True)
    CASES[a.case](a)


if __name__ == "__main__":
    main()
