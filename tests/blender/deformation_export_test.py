"""The add-on's FILMBACK_deformation (importers/blender/io_filmback/deformation.py) against bpy.

    deformation_export_test.py --scratch DIR

deformation_export_scene.py builds meshes that take each path (an armature, a keyed shape key,
nothing, a Remesh modifier, a Decimate ratio keyed within the shutter), exports them through the
add-on and checks the written shapes against Blender's evaluated meshes; this driver checks the
export's report in Blender's console. Exit 77 (CTest's skip) without `blender`.
"""

import argparse
import os
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from roundtrip_test import SKIP, blender  # noqa: E402

# The path each mesh took, as the export reports it.
REPORT = ["filmback: mesh object 'bent': Blender's evaluated deformation, 5 times",
          "filmback: mesh object 'keyed': Blender's evaluated deformation, 5 times",
          "filmback: mesh object 'remeshed': glTF mesh as exported: its modifiers change the "
          "topology (deformation not carried)",
          "filmback: mesh object 'decimated': the topology changes within the shutter; the "
          "frame's shape is exported without deformation blur"]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--scratch", required=True)
    a = p.parse_args()
    if shutil.which("blender") is None:
        print("skipped: Debian package blender is not installed")
        sys.exit(SKIP)
    shutil.rmtree(a.scratch, ignore_errors=True)
    os.makedirs(a.scratch)
    r = blender("--python-exit-code", "1", "--python",
                os.path.join(HERE, "deformation_export_scene.py"), "--", a.scratch)
    output = r.stdout + r.stderr
    print(output)
    if r.returncode != 0:
        sys.exit(f"deformation_export_scene.py failed ({r.returncode})")
    missing = [line for line in REPORT if line not in output]
    if missing:
        sys.exit(f"not in the export's report: {missing}")
    if "filmback: mesh object 'plain'" in output:
        sys.exit("the export reports a path for 'plain', which nothing deforms")


if __name__ == "__main__":
    main()
