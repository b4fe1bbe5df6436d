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
    "core/render/render_job.h": 'constexpr const char* kDefaultFilter = "gaussian";\n',
    "core/render/render_job.cpp": 'const char* f() { return "thinlens"; }\n',
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


class CheckLayersTest(unittest.TestCase):
    def violations(self, planted):
        with tempfile.TemporaryDirectory() as folder:
            root = pathlib.Path(folder)
            write_tree(root, {**CLEAN, **planted})
            return check_layers.check(root)

    def assert_one(self, planted, *words):
        found = self.violations(planted)
        self.assertEqual(len(found), 1, found)
        for word in words:
            self.assertIn(word, found[0])

    def test_clean_tree_passes(self):
        self.assertEqual(self.violations({}), [])

    def test_scene_model_including_the_accelerator_fails(self):
        self.assert_one({"core/scene/csg_probe.h": '#include "core/scene/solid.h"\n\n'
                                                   '#include "core/accel/solid_intersect.h"\n'},
                        "core/scene/csg_probe.h:3:", "core/accel/solid_intersect.h")

    def test_core_outside_the_front_end_including_an_importer_fails(self):
        self.assert_one({"core/render/render_job.cpp": '  # include "importers/gltf/gltf_shot.h"\n'},
                        "core/render/render_job.cpp:1:", "importers/gltf/gltf_shot.h")

    def test_renderer_including_the_tessellation_fails(self):
        self.assert_one({"core/render/loop.cpp": '#include "core/tessellate/tessellate.h"\n'},
                        "core/render/loop.cpp:1:", "core/tessellate/tessellate.h")

    def test_plugin_including_core_fails(self):
        self.assert_one({"plugins/filters/box/box.cpp": '#include "core/plugin/params.h"\n'},
                        "plugins/filters/box/box.cpp:1:", "core/plugin/params.h")

    def test_core_naming_a_plugin_outside_the_table_fails(self):
        self.assert_one({"core/render/film_setup.cpp": 'int a;\nauto f = "gaussian";\n'},
                        "core/render/film_setup.cpp:2:", '"gaussian"')

    def test_core_writing_a_plugin_spec_fails(self):
        self.assert_one({"core/render/x.cpp": 'auto s = std::string("box:radius=") + "0.5";\n'},
                        "core/render/x.cpp:1:", '"box"')

    def test_core_naming_a_plugin_library_fails(self):
        self.assert_one({"core/plugin/y.cpp": 'auto f = "libfilmback_camera_thinlens.so";\n'},
                        "core/plugin/y.cpp:1:", '"thinlens"')

    def test_allowed_file_naming_another_plugin_fails(self):
        self.assert_one({"core/render/render_job.h": 'constexpr const char* k = "thinlens";\n'},
                        "core/render/render_job.h:1:", '"thinlens"')

    def test_a_new_plugin_is_checked_without_editing_the_checker(self):
        planted = {"plugins/CMakeLists.txt": PLUGINS_CMAKE +
                   "filmback_add_plugin(camera fisheye cameras/fisheye/fisheye.cpp)\n",
                   "core/render/z.cpp": 'auto c = "fisheye";\n'}
        self.assert_one(planted, "core/render/z.cpp:1:", '"fisheye"')

    def test_lines_after_block_comments_and_raw_strings_are_counted(self):
        planted = {"core/scene/camera.cpp": '/* one\ntwo */\nauto r = R"x(a\n"b)x";\n'
                                            '#include "core/render/render_job.h"\n'}
        self.assert_one(planted, "core/scene/camera.cpp:5:", "core/render/render_job.h")


if __name__ == "__main__":
    unittest.main()
