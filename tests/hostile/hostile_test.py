"""Hostile scene files (issue 7, docs/reliability.md): files crafted to crash, hang, exhaust memory or
read outside their folder. Each is written at test time (the large and binary ones are generated,
not committed), rendered by the built `filmback`, and must end with exit status 1, one error line
saying what was refused, no output file, within the CPU-time bound, and, in the sanitized build,
without a leak: LeakSanitizer runs when filmback exits and turns a leak into exit status 23.

Time: CPU seconds of the filmback process (user + system, from the kernel's accounting of the
child), not the wall clock, so that a loaded 2-core machine cannot make the bound flaky; a hang
that sleeps instead of computing is caught by the wall-clock timeout of 60 s.

Run: hostile_test.py --filmback BIN --scratch DIR [--cpu-seconds S] [case...]; --list prints the cases.
"""

import os
import resource
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "cli"))
import case_main  # noqa: E402
from gltf_files import triangle_scene  # noqa: E402

FILMBACK = None
SCRATCH = None
CPU_SECONDS = 1.0
WALL_SECONDS = 60


class HostileTest(unittest.TestCase):
    def setUp(self):
        self.dir = Path(tempfile.mkdtemp(prefix=self._testMethodName + "-", dir=SCRATCH))
        self.addCleanup(shutil.rmtree, self.dir, True)
        self.scenes = self.dir / "scenes"
        self.scenes.mkdir()
        self.out = self.dir / "out"
        self.out.mkdir()

    def write(self, name, data):
        path = self.scenes / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data) if isinstance(data, bytes) else path.write_text(data)
        return path

    def assert_refused(self, scene, *fragments, options=()):
        """Renders `scene`: exit 1, one error line naming the scene file (POV-Ray messages name it as
        `file:line:column` by its name) and holding each fragment,
        nothing in the output folder, at most CPU_SECONDS of processor time."""
        env = {k: v for k, v in os.environ.items() if k != "FILMBACK_PLUGIN_PATH"}
        env["ASAN_OPTIONS"] = "detect_leaks=1:" + env.get("ASAN_OPTIONS", "")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        size = () if "--res" in options else ("--res", "16x16")
        result = subprocess.run([FILMBACK, "render", str(scene), "-o", str(self.out / "image.exr"),
                                 *size, "--spp", "1", "-q", *options],
                                capture_output=True, text=True, env=env, stdin=subprocess.DEVNULL,
                                timeout=WALL_SECONDS)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        print("\n$ filmback render %s\nexit %d, %.3f s CPU\n%s" % (scene, result.returncode, cpu, result.stderr),
              end="", flush=True)
        report = "\nexit %d\nstderr:\n%s" % (result.returncode, result.stderr)
        self.assertEqual(result.returncode, 1, report)
        lines = [line for line in result.stderr.splitlines() if not line.startswith("warning: ")]
        self.assertEqual(len(lines), 1, "expected one error line" + report)
        self.assertTrue(lines[0].startswith("filmback: error: %s" % scene)
                        or lines[0].startswith("filmback: error: %s:" % scene.name), report)
        for fragment in fragments:
            self.assertIn(fragment, lines[0], report)
        self.assertEqual(sorted(os.listdir(self.out)), [], "output folder not empty" + report)
        self.assertLess(cpu, CPU_SECONDS, "took %.3f s of CPU time" % cpu)

    # --- glTF ------------------------------------------------------------------------------------

    def test_glb_chunk_longer_than_the_file(self):
        data = bytearray(triangle_scene().glb_bytes())
        json_length = struct.unpack("<I", data[12:16])[0]
        bin_at = 20 + json_length
        data[bin_at:bin_at + 4] = struct.pack("<I", 0x7FFFFFF0)  # the BIN chunk claims ~2 GiB
        self.assert_refused(self.write("chunk.glb", bytes(data)), "chunk 1 at byte %d" % bin_at,
                            "2147483632 bytes of data reach past the end of the file")

    def test_accessor_past_its_buffer(self):
        g = triangle_scene()
        g.doc["accessors"][0]["byteOffset"] = 24  # 3 VEC3 floats from byte 24 of a 36-byte view
        self.assert_refused(self.write("past.gltf", g.json_text()), "(accessors[0])",
                            "do not fit in bufferViews[0] (36 bytes)")
        g = triangle_scene()
        g.doc["bufferViews"][0]["byteLength"] = 1 << 20  # a view of 1 MiB in a 48-byte buffer
        self.assert_refused(self.write("view.glb", g.glb_bytes()), "bufferViews[0]",
                            "reach past the end of buffers[0]")

    def test_accessor_of_two_to_the_31_elements(self):
        g = triangle_scene()
        g.doc["accessors"][0]["count"] = 2 ** 31
        self.assert_refused(self.write("huge.gltf", g.json_text()), "(accessors[0])",
                            "2147483648 elements of 12 bytes", "do not fit in bufferViews[0]")

    def test_cyclic_node_graph(self):
        g = triangle_scene()
        a = g.node(name="a", children=[])
        b = g.node(root=False, name="b", children=[a])
        g.doc["nodes"][a]["children"] = [b]
        self.assert_refused(self.write("cycle.gltf", g.json_text()), "nodes[%d].children[0]" % b,
                            "nodes[%d] is reached a second time" % a)

    def test_uri_escaping_the_folder(self):
        g = triangle_scene()
        (self.dir / "secret.bin").write_bytes(bytes(g.bin))
        self.assert_refused(self.write("escape.gltf", g.json_text(buffer_uri="../secret.bin")),
                            "buffers[0].uri: '../secret.bin' refers outside the scene's folder")
        self.assert_refused(self.write("encoded.gltf", g.json_text(buffer_uri="%2E%2E/secret.bin")),
                            "buffers[0].uri: '%2E%2E/secret.bin' refers outside the scene's folder")
        os.symlink(self.dir / "secret.bin", self.scenes / "link.bin")
        self.assert_refused(self.write("link.gltf", g.json_text(buffer_uri="link.bin")),
                            "'link.bin' refers outside the scene's folder")
        self.assert_refused(self.write("passwd.gltf", g.json_text(buffer_uri="/etc/passwd")),
                            "buffers[0].uri: '/etc/passwd' is an absolute path")

    def test_network_uri(self):
        g = triangle_scene()
        self.assert_refused(self.write("http.gltf", g.json_text(buffer_uri="http://127.0.0.1:9/a.bin")),
                            "buffers[0].uri: 'http://127.0.0.1:9/a.bin' is a 'http:' URI",
                            "never opens a network connection")
        self.assert_refused(self.write("file.gltf", g.json_text(buffer_uri="file:///etc/passwd")),
                            "buffers[0].uri: 'file:///etc/passwd' is a 'file:' URI")

    def test_no_network_system_call(self):
        """strace sees every system call of filmback and its threads: a render, and a refused
        http: URI, make none of the network family (socket, connect, sendto, ...)."""
        strace = shutil.which("strace")
        if not strace:
            self.skipTest("strace is not installed (Debian package strace)")
        g = triangle_scene()
        env = dict(os.environ, ASAN_OPTIONS="detect_leaks=0")  # LeakSanitizer cannot run under ptrace
        for name, text, status in (("render.gltf", g.json_text(), 0),
                                   ("http.gltf", g.json_text(buffer_uri="http://127.0.0.1:9/a.bin"), 1)):
            trace = self.dir / (name + ".trace")
            result = subprocess.run([strace, "-f", "-qq", "-e", "trace=network", "-o", str(trace), FILMBACK,
                                     "render", str(self.write(name, text)), "-o", str(self.out / "image.exr"),
                                     "--res", "16x16", "--spp", "1", "-q"],
                                    capture_output=True, text=True, env=env, stdin=subprocess.DEVNULL,
                                    timeout=WALL_SECONDS)
            self.assertEqual(result.returncode, status, result.stderr)
            self.assertEqual(trace.read_text(), "", "network system calls by filmback")

    def test_render_larger_than_the_memory_limit(self):
        scene = self.write("big.gltf", triangle_scene().json_text())
        self.assert_refused(scene, "the render needs about 1.07374 GB (film 1.07374 GB",
                            "more than the memory limit of 0.0671089 GB (--memory-limit)",
                            options=("--res", "4096x4096", "--memory-limit", "64M"))

    def test_subdivision_to_a_billion_triangles(self):
        """Blender's highest render level on an 8 x 8 quad cage: 2^29 triangles (64 GB), refused
        from the cage's size before refinement allocates any of them."""
        g = triangle_scene()
        g.doc["extensionsUsed"] = ["FILMBACK_blender"]
        positions = [c for j in range(9) for i in range(9) for c in (i, j, 0)]
        faces = [v for j in range(8) for i in range(8)
                 for v in (9 * j + i, 9 * j + i + 1, 9 * j + i + 10, 9 * j + i + 9)]
        g.doc["nodes"][0]["extensions"] = {"FILMBACK_blender": {"subdivision": {
            "cage_positions": positions, "cage_face_sizes": [4] * 64, "cage_face_vertices": faces,
            "levels_render": 11}}}
        self.assert_refused(self.write("subdivision.gltf", g.json_text()), "the render needs about",
                            "geometry and BVH 64.4245 GB",
                            "more than the memory limit of 8.58993 GB (--memory-limit)",
                            options=("--memory-limit", "8G"))

    # --- POV-Ray ---------------------------------------------------------------------------------

    def test_infinite_while(self):
        self.assert_refused(self.write("while.pov", "#while (1) #end\n"),
                            "while.pov:1:12: more than 500000 loop iterations (limit)")

    def test_infinite_macro_recursion(self):
        self.assert_refused(self.write("macro.pov", "#macro R() R() #end\nR()\n"),
                            "macro calls nested deeper than 256 (limit)",
                            "in macro R called from macro.pov:2:1)")

    def test_include_of_itself(self):
        self.assert_refused(self.write("self.pov", '#include "self.pov"\n'),
                            "includes nested deeper than 32 (limit)")

    def test_include_of_etc_passwd(self):
        self.assert_refused(self.write("passwd.pov", '#include "/etc/passwd"\n'),
                            'passwd.pov:1:10: cannot include "/etc/passwd": an absolute path is refused')
        (self.dir / "secret.inc").write_text("sphere { 0, 1 }\n")
        self.assert_refused(self.write("up.pov", '#include "../secret.inc"\n'),
                            'cannot include "../secret.inc": not found')
        os.symlink("/etc/passwd", self.scenes / "passwd.inc")
        self.assert_refused(self.write("link.pov", '#include "passwd.inc"\n'),
                            'cannot include "passwd.inc": not found')
        self.assert_refused(self.write("fopen.pov", '#fopen F "passwd.inc" read\n'),
                            'cannot #fopen "passwd.inc" for reading inside the scene\'s folder')


def configure(args):
    global FILMBACK, SCRATCH, CPU_SECONDS
    FILMBACK, SCRATCH, CPU_SECONDS = args.filmback, args.scratch, args.cpu_seconds


def cpu_seconds_option(parser):
    parser.add_argument("--cpu-seconds", type=float, default=1.0,
                        help="processor time each refusal may take (default 1)")


if __name__ == "__main__":
    sys.exit(case_main.main(HostileTest, __doc__, configure, cpu_seconds_option))
