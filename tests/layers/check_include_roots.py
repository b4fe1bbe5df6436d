#!/usr/bin/python3
"""The layers of docs/architecture.md held by the compiler: each library's include root (a folder
of links to the source folders it owns, `filmback_include_root` in CMakeLists.txt) lets it find its
own layer and those below, and no header above.

For each case, a one-line file `#include "<a header of FOLDER>"` is written where a source of the
target would sit (its quote search finds nothing beside it) and preprocessed with the target's own
include directories, as the build gives them (FLAGS_DIR/<target>.includes, one per line, written
by tests/layers/CMakeLists.txt). A header that must resolve must preprocess; one that must not must
fail naming that header as not found, and resolve once the whole source tree is added to the path
(as every library had it before the roots): so a probe cannot pass by misspelling. The header is
the first of its folder, so renaming files needs no edit here (a case may name one header).
Usage: check_include_roots.py COMPILER SOURCE_ROOT FLAGS_DIR
"""

import pathlib
import subprocess
import sys
import tempfile
import unittest

# The SDK's headers are spelled from its own root, <filmback/...>.
SPELLING_ROOTS = {"filmback": "core/sdk/filmback"}

# (target, where its probe file sits, the folder of the header it includes, must it resolve?)
# The resolving cases show the roots are not too narrow; the others are the layers.
CASES = [
    ("filmback_core", "core/render", "core/scene", True),
    ("filmback_core", "core/render", "filmback", True),
    ("filmback_core", "core/render", "importers/gltf", False),
    ("filmback_core", "core/render", "importers/pov", False),
    ("filmback_core", "core/render", "core/cmd", False),
    ("filmback_core", "core/render", "core/tessellate", False),
    ("filmback_tessellate", "core/tessellate", "core/accel", True),
    ("filmback_tessellate", "core/tessellate", "importers/gltf", False),
    ("filmback_tessellate", "core/tessellate", "core/cmd", False),
    ("filmback_importers", "importers/gltf", "core/scene", True),
    ("filmback_importers", "importers/gltf", "core/cmd", False),
    ("filmback_importers", "importers/gltf", "core/tessellate", False),
    ("filmback_pov_sdl", "importers/pov/sdl", "importers/pov", True),
    ("filmback_pov_sdl", "importers/pov/sdl", "importers/gltf", False),
    ("filmback_pov_sdl", "importers/pov/sdl", "core/cmd", False),
    # The module shares its folder with the core's loader of it: its own header.
    ("filmback_subdiv", "core/subdiv", "core/subdiv/refine.h", True),
    ("filmback_subdiv", "core/subdiv", "core/render", False),
    ("filmback", "core/cmd", "importers/gltf", True),
    ("filmback", "core/cmd", "core/tessellate", True),
]
# Every plugin (FLAGS_DIR/plugins lists their targets) sees the SDK and nothing of the host.
PLUGIN_CASES = [
    ("plugins/filters", "filmback", True),
    ("plugins/filters", "core/plugin", False),
    ("plugins/filters", "core/math", False),
    ("plugins/filters", "importers/gltf", False),
]


def first_header(source_root, folder):
    """(how an #include spells it, its path) for a header named *.h, else a folder's first."""
    if folder.endswith(".h"):
        return folder, source_root / folder
    folder_path = source_root / SPELLING_ROOTS.get(folder, folder)
    headers = sorted(folder_path.glob("*.h"))
    if not headers:
        raise AssertionError(f"{folder_path}: no header to include")
    return f"{folder}/{headers[0].name}", headers[0]


def preprocess(compiler, includes, probe_folder, spelled):
    """The compiler's result for a file in probe_folder holding only `#include "spelled"`."""
    probe_folder.mkdir(parents=True, exist_ok=True)
    probe = probe_folder / "include_probe.cpp"
    probe.write_text(f'#include "{spelled}"\n')
    command = [compiler, "-std=c++20", "-E", "-o", "/dev/null", *(f"-I{i}" for i in includes),
               str(probe)]
    return subprocess.run(command, capture_output=True, text=True)


class IncludeRootsTest(unittest.TestCase):
    compiler = source_root = flags_dir = None

    def includes_of(self, target):
        """The target's include directories in order, less the compiler's own, as CMake's
        compile line has them (an -I/usr/include would disturb the C library's #include_next)."""
        implicit = set(self.flags_dir.joinpath("implicit").read_text().splitlines())
        lines = self.flags_dir.joinpath(f"{target}.includes").read_text().splitlines()
        return list(dict.fromkeys(line for line in lines if line and line not in implicit))

    def check(self, target, probe_folder, folder, resolves):
        spelled, header = first_header(self.source_root, folder)
        includes = self.includes_of(target)
        with tempfile.TemporaryDirectory() as work:
            result = preprocess(self.compiler, includes, pathlib.Path(work) / probe_folder,
                                spelled)
        said = f"{target} ({' '.join(includes)}):\n{result.stderr}"
        if resolves:
            self.assertEqual(result.returncode, 0, said)
            return
        self.assertNotEqual(result.returncode, 0, f"{spelled} was found: {said}")
        # GCC: "<name>: No such file or directory"; clang: "'<name>' file not found".
        self.assertIn(spelled, result.stderr, said)
        self.assertRegex(result.stderr, "No such file or directory|file not found", said)
        # The same probe with the whole source tree (and the SDK's root) on the path, as before
        # the roots: it resolves, so the root alone refused it.
        whole_tree_roots = [str(self.source_root), str(self.source_root / "core" / "sdk")]
        with tempfile.TemporaryDirectory() as work:
            whole_tree = preprocess(self.compiler, [*includes, *whole_tree_roots],
                                    pathlib.Path(work) / probe_folder, spelled)
        self.assertEqual(whole_tree.returncode, 0, f"{header}: {whole_tree.stderr}")

    def test_each_library_sees_its_layer_and_those_below_only(self):
        for target, probe_folder, folder, resolves in CASES:
            with self.subTest(f"{target}: {folder} {'found' if resolves else 'not found'}"):
                self.check(target, probe_folder, folder, resolves)

    def test_plugins_see_only_the_sdk(self):
        plugins = self.flags_dir.joinpath("plugins").read_text().split()
        self.assertTrue(plugins, "no plugin targets listed")
        for target in plugins:
            for probe_folder, folder, resolves in PLUGIN_CASES:
                with self.subTest(f"{target}: {folder} {'found' if resolves else 'not found'}"):
                    self.check(target, probe_folder, folder, resolves)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit("usage: check_include_roots.py COMPILER SOURCE_ROOT FLAGS_DIR")
    IncludeRootsTest.compiler = sys.argv[1]
    IncludeRootsTest.source_root = pathlib.Path(sys.argv[2])
    IncludeRootsTest.flags_dir = pathlib.Path(sys.argv[3])
    unittest.main(argv=sys.argv[:1])
