#!/usr/bin/python3
"""check_layers.py on small trees written here: a clean tree passes, and each planted violation
is reported, naming its file and line, while the same words in comments, in allowed places or in
tests are not."""

import pathlib
import sys
import tempfile
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import check_layers  # noqa: E402

PLUGINS_CMAKE = """\
filmback_add_plugin(camera perspective cameras/perspective/perspective.cpp)
filmback_add_plugin(camera thinlens cameras/thinlens/thinlens.cpp)
filmback_add_plugin(filter box filters/box/box.cpp)
filmback_add_plugin(filter gaussian filters/gaussian/gaussian.cpp)
filmback_add_plugin(integrator path integrators/path/path.cpp)
"""

CLEAN = {
    "plugins/CMakeLists.txt": PLUGINS_CMAKE,
    "plugins/cameras/perspective/perspective.cpp": '#include <filmback/plugin_abi.h>\n'
                                                   'const char* kName = "perspective";\n',
    "core/scene/scene.h": '#include "core/math/transform.h"\n#include "core/scene/solid.h"\n',
    "core/accel/solid_intersect.h": '#include "core/scene/solid.h"\n',
    "core/tessellate/csg_probe.h": '#include "core/accel/solid_intersect.h"\n',
    "core/render/shot_plan.cpp": 'constexpr const char* kDefaultFilter = "gaussian";\n'
                                 'const char* f() { return "thinlens"; }\n',
    "core/render/shutter.cpp": 'bool box(const char* s) { return s == "box"; }\n',
    "core/cmd/convert_command.cpp": '#include "importers/gltf/gltf_writer.h"\n'
                                    '#include "core/tessellate/tessellate.h"\n',
    # Words in comments, and tests, are not layers.
    "core/plugin/params.h": '// "gaussian:radius=1.5"\n/* #include "importers/x.h"\n"path" */\n',
    "core/scene/scene_test.cpp": '#include "core/accel/render_geometry.h"\nauto s = "path";\n',
}


def write_tree(root, files):
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


# Each planted file (over the clean tree) and the words its one violation must name: file:line
# and what crossed the layer.
PLANTED = {
    "scene model including the accelerator": (
        {"core/scene/csg_probe.h": '#include "core/scene/solid.h"\n\n'
                                   '#include "core/accel/solid_intersect.h"\n'},
        "core/scene/csg_probe.h:3:", "core/accel/solid_intersect.h"),
    "core outside the front end including an importer": (
        {"core/render/render_job.cpp": '  # include "importers/gltf/gltf_shot.h"\n'},
        "core/render/render_job.cpp:1:", "importers/gltf/gltf_shot.h"),
    "the renderer including the tessellation": (
        {"core/render/loop.cpp": '#include "core/tessellate/tessellate.h"\n'},
        "core/render/loop.cpp:1:", "core/tessellate/tessellate.h"),
    "core climbing to an importer with ../": (
        {"core/render/loop.cpp": '#include "../../importers/gltf/gltf_shot.h"\n'},
        "core/render/loop.cpp:1:", "../../importers/gltf/gltf_shot.h"),
    "a plugin including core": (
        {"plugins/filters/box/box.cpp": '#include "core/plugin/params.h"\n'},
        "plugins/filters/box/box.cpp:1:", "core/plugin/params.h"),
    "core naming a plugin outside the table": (
        {"core/render/film_setup.cpp": 'int a;\nauto f = "gaussian";\n'},
        "core/render/film_setup.cpp:2:", '"gaussian"'),
    "core writing a plugin spec": (
        {"core/render/x.cpp": 'auto s = std::string("box:radius=") + "0.5";\n'},
        "core/render/x.cpp:1:", '"box"'),
    "core naming a plugin's library": (
        {"core/plugin/y.cpp": 'auto f = "libfilmback_camera_thinlens.so";\n'},
        "core/plugin/y.cpp:1:", '"thinlens"'),
    "an allowed file naming another plugin": (
        {"core/render/shutter.cpp": 'constexpr const char* k = "thinlens";\n'},
        "core/render/shutter.cpp:1:", '"thinlens"'),
    "a plugin added to plugins/CMakeLists.txt, with no edit of the checker": (
        {"plugins/CMakeLists.txt": PLUGINS_CMAKE +
         "filmback_add_plugin(camera fisheye cameras/fisheye/fisheye.cpp)\n",
         "core/render/z.cpp": 'auto c = "fisheye";\n'},
        "core/render/z.cpp:1:", '"fisheye"'),
    "an include after a block comment and a raw string": (
        {"core/scene/camera.cpp": '/* one\ntwo */\nauto r = R"x(a\n"b)x";\n'
                                  '#include "core/render/render_job.h"\n'},
        "core/scene/camera.cpp:5:", "core/render/render_job.h"),
}


class CheckLayersTest(unittest.TestCase):
    def violations(self, planted):
        with tempfile.TemporaryDirectory() as folder:
            root = pathlib.Path(folder)
            write_tree(root, {**CLEAN, **planted})
            return check_layers.check(root)

    def test_clean_tree_passes(self):
        self.assertEqual(self.violations({}), [])

    def test_each_planted_violation_is_reported_naming_file_and_line(self):
        for case, (planted, *words) in PLANTED.items():
            with self.subTest(case):
                found = self.violations(planted)
                self.assertEqual(len(found), 1, found)
                for word in words:
                    self.assertIn(word, found[0])


if __name__ == "__main__":
    unittest.main()
