"""The add-on's materials, meshes' UV maps, lights and view settings against bpy (issue 14).

    material_export_test.py --scratch DIR [--node-modules DIR] CASE

Cases (one CTest test each, label blender; exit 77, CTest's skip, when a tool is missing):
  export     material_export_scene.py builds materials of every kind the add-on carries, exports
             them through Blender's exporter with the add-on and compares every value of the
             extension with bpy (material_export_checks.py); the warnings also reach Blender's
             console
  validator  that export passes the Khronos glTF validator (npm gltf-validator) with no errors
             and no warnings
"""

import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from roundtrip_test import (  # noqa: E402
    blender, fresh_folder, skip_unless_installed, require_validator, validate)

# Lines the add-on prints to Blender's console for what it does not carry.
CONSOLE_WARNINGS = ["filmback: material 'Toon': node 'Toon BSDF' (BSDF_TOON) is not carried",
                    "filmback: material 'Textured': node 'Bump' (BUMP) on 'Principled BSDF'."
                    "Clearcoat Normal is not carried"]


def export(scratch):
    """Runs material_export_scene.py into `scratch`; returns (gltf path, Blender's output)."""
    fresh_folder(scratch)
    r = blender("--python-exit-code", "1", "--python",
                os.path.join(HERE, "material_export_scene.py"), "--", scratch)
    output = r.stdout + r.stderr
    print(output)
    gltf = os.path.join(scratch, "export", "shot.gltf")
    if r.returncode != 0 or not os.path.exists(gltf):
        sys.exit(f"material_export_scene.py failed ({r.returncode})")
    return gltf, output


def case_export(a):
    _, output = export(a.scratch)
    missing = [w for w in CONSOLE_WARNINGS if w not in output]
    if missing:
        sys.exit(f"not printed to Blender's console: {missing}")


def case_validator(a):
    require_validator(a.node_modules)
    gltf, _ = export(a.scratch)
    validate(a.node_modules, gltf)


CASES = {"export": case_export, "validator": case_validator}


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--scratch", required=True)
    p.add_argument("--node-modules")
    p.add_argument("case", choices=sorted(CASES))
    a = p.parse_args()
    skip_unless_installed("blender")
    CASES[a.case](a)


if __name__ == "__main__":
    main()
