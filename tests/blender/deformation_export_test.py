"""The add-on's FILMBACK_deformation (importers/blender/io_filmback/deformation.py) against bpy.

    deformation_export_test.py --scratch DIR

deformation_export_scene.py builds meshes that take each path (an armature, a keyed shape key,
nothing, a Remesh modifier, a Decimate ratio keyed within the shutter, an armature under a
Subdivision Surface, an Array of a keyed shape key, subdivision cages), exports them through the
add-on and checks the written shapes against Blender's evaluated meshes; this driver checks the
export's report in Blender's console. Exit 77 (CTest's skip) without `blender`.
"""

import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from roundtrip_test import blender, fresh_folder, skip_unless_installed  # noqa: E402

# The path each mesh took, as the export reports it.
REPORT = ["filmback: mesh object 'bent': Blender's evaluated deformation, 5 times",
          "filmback: mesh object 'keyed': Blender's evaluated deformation, 5 times",
          "filmback: mesh object 'remeshed': Blender's evaluated mesh (its modifiers change the "
          "topology), still",
          "filmback: mesh object 'decimated': the topology changes within the shutter; the "
          "frame's shape is exported without deformation blur",
          "filmback: mesh object 'subdivided': Blender's evaluated mesh (its modifiers change "
          "the topology) and deformation, 5 times",
          "filmback: mesh object 'arrayed': Blender's evaluated mesh (its modifiers change "
          "the topology) and deformation, 5 times",
          "filmback: mesh object 'posed_cage': subdivision cage evaluated at the frame (nothing "
          "before its Subdivision Surface moves within the shutter)"]
# Meshes nothing deforms: no report.
SILENT = ("plain", "caged")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--scratch", required=True)
    a = p.parse_args()
    skip_unless_installed("blender")
    fresh_folder(a.scratch)
    r = blender("--python-exit-code", "1", "--python",
                os.path.join(HERE, "deformation_export_scene.py"), "--", a.scratch)
    output = r.stdout + r.stderr
    print(output)
    if r.returncode != 0:
        sys.exit(f"deformation_export_scene.py failed ({r.returncode})")
    missing = [line for line in REPORT if line not in output]
    if missing:
        sys.exit(f"not in the export's report: {missing}")
    for name in SILENT:
        if f"filmback: mesh object '{name}'" in output:
            sys.exit(f"the export reports a path for '{name}', which nothing deforms")


if __name__ == "__main__":
    main()
