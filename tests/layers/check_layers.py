#!/usr/bin/python3
"""The layers of docs/architecture.md ("Layers"), checked on the source tree.

Reads every C++ source under core/ and plugins/ (tests, *_test.cpp, are not a layer and are not
read) and fails, naming the file and line, when
  - a file of core outside the front end (core/cmd/) includes importers/ or core/cmd/;
  - the scene model (core/scene/) includes anything but itself, core/math, core/image, core/util:
    the accelerator above all;
  - anything but the front end includes the conversion's tessellation (core/tessellate/);
  - a plugin or the plugin SDK includes core/ or importers/ (they see the SDK only);
  - an include climbs with ../ (it would pass the include roots the compiler holds);
  - core names a concrete plugin (a string literal that is a plugin's name, a spec
    "name:key=value", or its library name) outside the places in ALLOWED_PLUGIN_NAMES.
The plugin names are read from plugins/CMakeLists.txt, so a new plugin is checked without editing
this file. Usage: check_layers.py [SOURCE_ROOT] (default: the tree this script is in); exit 0
when the tree keeps its layers, 1 with one line per violation otherwise.
"""

import pathlib
import re
import sys

SOURCE_SUFFIXES = {".c", ".cc", ".cpp", ".h", ".hpp"}

# Where core may name a concrete plugin, and why: the shot plan holds the one table from a shot's
# projection, pixel filter and defaults to plugins. The others use the same words in another sense.
ALLOWED_PLUGIN_NAMES = {
    "core/render/shot_plan.cpp": {"perspective", "orthographic", "thinlens", "gaussian", "box",
                                  "blackman_harris", "path", "pov_fisheye", "pov_ultra_wide_angle",
                                  "pov_omnimax", "pov_panoramic", "pov_cylinder", "pov_spherical",
                                  # kModelPlugins: the projections scenes name (Cycles' panoramas)
                                  "equirectangular", "fisheye_equidistant", "fisheye_equisolid",
                                  "mirrorball", "fisheye_polynomial", "central_cylindrical",
                                  "equiangular_cubemap_face"},
    "core/render/shutter.cpp": {"box"},  # the box shutter curve, not the box filter
    # OpenImageIO's box filter averaging each MIP level from the one above, not the plugin
    "core/texture/texture_images.cpp": {"box"},
    "core/cmd/info_command.cpp": {"perspective", "orthographic"},  # the projection it prints
}


def include_rules():
    """(applies to a file?, forbids an include?, what the layer says) for each rule."""
    def under(*folders):
        return lambda path: any(path.startswith(f) for f in folders)

    def outside(*folders):
        inside = under(*folders)
        return lambda path: not inside(path)

    return [
        (lambda p: p.startswith("core/") and not p.startswith("core/cmd/"),
         under("importers/", "core/cmd/"),
         "only the front end (core/cmd/) knows the importers and the commands"),
        (under("core/scene/"),
         outside("core/scene/", "core/math/", "core/image/", "core/util/"),
         "the scene model includes only core/scene, core/math, core/image and core/util "
         "(not the accelerator)"),
        (outside("core/cmd/", "core/tessellate/"),
         under("core/tessellate/"),
         "only the front end uses the conversion's tessellation (core/tessellate/)"),
        (under("plugins/", "core/sdk/"),
         under("core/", "importers/"),
         "plugins and the plugin SDK see only the SDK's headers (<filmback/...>)"),
        # A quoted include is looked up beside the including file first, which no include root
        # holds: "../../importers/x.h" from core/render would reach the importers.
        (lambda p: True,
         lambda target: ".." in target.split("/"),
         "includes are spelled from the source root (\"core/scene/scene.h\"), never climbing "
         "with ../ past the include roots"),
    ]


def code_and_strings(text):
    """The text with comments blanked (line numbers kept), and each string literal with its line.

    A small C++ lexer: // and /* */ comments, "..." and '...' literals with escapes, and raw
    strings R"delim(...)delim".
    """
    code, strings = [], []
    i, line, n = 0, 1, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            end = text.find("\n", i)
            i = n if end < 0 else end
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            newlines = text.count("\n", i, end)
            code.append("\n" * newlines)
            line += newlines
            i = end
        elif c == "R" and i + 1 < n and text[i + 1] == '"' and not (i and text[i - 1].isalnum()):
            open_paren = text.find("(", i + 2)
            delimiter = ")" + text[i + 2:open_paren] + '"'
            end = text.find(delimiter, open_paren)
            end = n if end < 0 else end + len(delimiter)
            strings.append((line, text[open_paren + 1:end - len(delimiter)]))
            code.append(text[i:end])
            line += text.count("\n", i, end)
            i = end
        elif c in "\"'":
            j, value = i + 1, []
            while j < n and text[j] != c and text[j] != "\n":
                if text[j] == "\\" and j + 1 < n:
                    value.append(text[j:j + 2])
                    j += 2
                else:
                    value.append(text[j])
                    j += 1
            if c == '"':
                strings.append((line, "".join(value)))
            code.append(text[i:j + 1])
            i = j + 1
        else:
            if c == "\n":
                line += 1
            code.append(c)
            i += 1
    return "".join(code), strings


def plugin_names(root):
    """{name: kind} of every plugin plugins/CMakeLists.txt builds."""
    cmake = (root / "plugins" / "CMakeLists.txt").read_text()
    found = re.findall(r"^\s*filmback_add_plugin\(\s*(\w+)\s+(\w+)", cmake, re.MULTILINE)
    if not found:
        raise SystemExit(f"{root}/plugins/CMakeLists.txt: no filmback_add_plugin(kind name ...)")
    return {name: kind for kind, name in found}


def named_plugin(literal, plugins):
    """The plugin a string literal names: the name, a spec 'name:...', or the library's name."""
    head = literal.split(":", 1)[0]
    if head in plugins:
        return head
    for name, kind in plugins.items():
        if f"filmback_{kind}_{name}" in literal:
            return name
    return None


INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*"([^"]+)"', re.MULTILINE)


def check(root):
    """Every violation under root, one 'file:line: what' string each."""
    root = pathlib.Path(root)
    plugins = plugin_names(root)
    rules = include_rules()
    violations = []
    for folder in ("core", "plugins"):
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in SOURCE_SUFFIXES or path.stem.endswith("_test"):
                continue
            relative = path.relative_to(root).as_posix()
            code, strings = code_and_strings(path.read_text(errors="replace"))
            for match in INCLUDE.finditer(code):
                target = match.group(1)
                line = code.count("\n", 0, match.start()) + 1
                for applies, forbids, layer in rules:
                    if applies(relative) and forbids(target):
                        violations.append(f"{relative}:{line}: includes {target}: {layer}")
            if not relative.startswith("core/"):
                continue
            allowed = ALLOWED_PLUGIN_NAMES.get(relative, set())
            for line, literal in strings:
                name = named_plugin(literal, plugins)
                if name and name not in allowed:
                    violations.append(
                        f'{relative}:{line}: names the plugin "{name}" ("{literal}"): core looks '
                        "plugins up by what the scene asks for; the one table from projection to "
                        "plugin is listed in tests/layers/check_layers.py")
    return violations


def main(argv):
    root = pathlib.Path(argv[1]) if len(argv) > 1 else pathlib.Path(__file__).resolve().parents[2]
    violations = check(root)
    for v in violations:
        print(v)
    print(f"check_layers: {len(violations)} violation(s) in {root}", file=sys.stderr)
    return 1 if violations else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
