"""Frame sequences (docs/cli.md, "Frame sequences"), end to end through the built `filmback`:
`render --frames A-B[:STEP]` renders each frame as `render --frame N` does (bit-identical), into
output patterns whose run of '#' is the frame number; a re-run skips the frames that are done and
touches none of their files; --overwrite renders them again; a signal stops the sequence after
the frame it interrupted, whose checkpoint --resume continues; an interrupted frame writes its EXR
(marked interrupted) and no PNG or JPEG; bad ranges and patterns are usage errors that write
nothing.

Run: frames_test.py --filmback BIN --scratch DIR [unittest names...]; --list prints the case
names (CMake registers one CTest test per case from it).
"""

import json
import math
import os
import re
import signal
import struct
import subprocess
import sys
import time
from pathlib import Path

import case_main
from gltf_files import FLOAT, triangle_scene

FILMBACK = None  # set by configure()
USAGE = 2
# The triangle's node moves along x from X0 at t = 0 to X1 at t = T1, 6 m in front of the camera
# (yfov 0.8, square): at 24 fps frames 1, 2 and 3 put it at x = -0.2, 0.2 and 0.6 m.
X0, X1, T1, DEPTH_M, FPS = -0.6, 0.6, 0.125, 6.0, 24.0
SIDE_PX = 32
TINY = ["--res", "%dx%d" % (SIDE_PX, SIDE_PX), "--spp", "16", "-q"]


def moving_triangle_scene():
    """tests/cli/gltf_files.py's triangle, emitting 1 W/sr/m^2 on a black base, its node moving
    linearly (glTF LINEAR sampler) from x = X0 to X1 over [0, T1] s."""
    g = triangle_scene()
    g.doc["nodes"][0]["translation"] = [X0, 0.0, -DEPTH_M]
    g.doc["materials"] = [{"emissiveFactor": [1.0, 1.0, 1.0],
                           "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0]}}]
    g.doc["meshes"][0]["primitives"][0]["material"] = 0
    times = g.view(struct.pack("<2f", 0.0, T1))
    values = g.view(struct.pack("<6f", X0, 0.0, -DEPTH_M, X1, 0.0, -DEPTH_M))
    g.doc["animations"] = [{
        "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
        "samplers": [{"input": g.accessor(times, FLOAT, "SCALAR", 2),
                      "output": g.accessor(values, FLOAT, "VEC3", 2), "interpolation": "LINEAR"}]}]
    return g


def expected_centroid_px(frame):
    """Where the triangle's centroid (x, -1/3 m) projects at `frame`, in pixels from the top-left
    corner: a pinhole maps the plane z = -DEPTH_M by a similarity, so the image's centroid is the
    projected centroid, u = W/2 (1 + x / (d tan(yfov/2))), v = H/2 (1 - y / (d tan(yfov/2)))."""
    x = X0 + (X1 - X0) * (frame / FPS) / T1
    half_width_m = DEPTH_M * math.tan(0.4)
    return (SIDE_PX / 2 * (1 + x / half_width_m), SIDE_PX / 2 * (1 + (1 / 3) / half_width_m))


def compare(pairs, dump=False):
    """One oiiotool run (each start costs about a second on a loaded machine): whether each pair
    of images is bit-identical (--diff --fail 0: every value equal); with `dump`, also the red
    channel's centroid of each pair's first image, pixel (i, j) standing for the point
    (i + 0.5, j + 0.5), from --dumpdata's lines "Pixel (x, y): r g b" under the file's header."""
    command = ["oiiotool"] + (["--dumpdata"] if dump else [])
    for a, b in pairs:
        command += [str(a), str(b), "--diff", "--fail", "0"]
    text = subprocess.run(command, capture_output=True, text=True).stdout
    verdicts = re.findall(r"^(PASS|FAILURE)$", text, re.MULTILINE)
    assert len(verdicts) == len(pairs), text
    sums, current = {}, None
    for line in text.splitlines():
        header = re.match(r"^(\S.*?) +: +\d+ x +\d+, ", line)
        pixel = re.match(r"^ +Pixel \((\d+), (\d+)\): (\S+)", line)
        if header:
            current = sums.setdefault(header.group(1), [0.0, 0.0, 0.0])
        elif pixel and current is not None:
            x, y, red = int(pixel.group(1)), int(pixel.group(2)), float(pixel.group(3))
            current[0] += red
            current[1] += red * (x + 0.5)
            current[2] += red * (y + 0.5)
    centroids = [(sums[str(a)][1] / sums[str(a)][0], sums[str(a)][2] / sums[str(a)][0])
                 for a, _ in pairs] if dump else []
    return [v == "PASS" for v in verdicts], centroids


class FramesTest(case_main.FolderCase):
    def setUp(self):
        super().setUp()
        self.scene = moving_triangle_scene().write(self.dir / "moving.gltf")

    def render(self, *args):
        result = self.run_cli("render", self.scene, *args)
        self.assertEqual(result.returncode, 0, result.stderr)
        return result

    def test_each_frame_is_its_single_frame_render(self):
        self.render("--frames", "1-3", "-o", "f.####.exr", "--stats-json", "stats.json", *TINY)
        frames = [self.dir / ("f.%04d.exr" % n) for n in (1, 2, 3)]
        singles = [self.dir / ("single%d.exr" % n) for n in (1, 2, 3)]
        for n, single in zip((1, 2, 3), singles):
            self.render("--frame", n, "-o", single, *TINY)
        same, centroids = compare(list(zip(frames, singles)), dump=True)
        self.assertEqual(same, [True] * 3)
        # The object is where its animation puts it at each frame, 2.5 px apart (measured within
        # 0.035 px of the projection at 16 spp: the edges' sampling noise).
        for n, (u, v) in zip((1, 2, 3), centroids):
            eu, ev = expected_centroid_px(n)
            self.assertAlmostEqual(u, eu, delta=0.15, msg="frame %d" % n)
            self.assertAlmostEqual(v, ev, delta=0.15, msg="frame %d" % n)
        self.assertGreater(centroids[1][0] - centroids[0][0], 2.0)
        self.assertGreater(centroids[2][0] - centroids[1][0], 2.0)
        report = json.loads((self.dir / "stats.json").read_text())
        self.assertEqual((report["frames"], report["status"], report["exit_status"]),
                         ("1-3", "complete", 0))
        self.assertEqual([(r["frame"], r["status"], r["outputs"]) for r in report["frame_reports"]],
                         [(n, "complete", ["f.%04d.exr" % n]) for n in (1, 2, 3)])
        # The glTF file is read once: the later frames have no import stage.
        self.assertEqual(["import" in r["timings_s"] for r in report["frame_reports"]],
                         [True, False, False])
        self.assertEqual(sorted(p.name for p in self.dir.iterdir()),
                         sorted(["moving.gltf", "stats.json"] + [p.name for p in frames + singles]))

    def test_a_rerun_skips_done_frames_and_overwrite_renders_them(self):
        # Frames -1, 1 and 3, named as Blender names them: s.-01.exr, s.01.exr, s.03.exr.
        outputs = ["-o", "s.##.exr", "-o", "s.##.png"]
        self.render("--frames", "-1-3:2", *outputs, *TINY)
        files = [self.dir / ("s.%s.%s" % (n, ext)) for n in ("-01", "01", "03")
                 for ext in ("exr", "png")]
        before = {f: os.stat(f) for f in files}
        (self.dir / "s.01.png").unlink()  # frame 1 is no longer done
        result = self.render("--frames", "-1-3:2", *outputs, "--stats-json", "stats.json", *TINY)
        for n, name in ((-1, "-01"), (3, "03")):
            self.assertIn("filmback: frame %d: skipped, s.%s.exr, s.%s.png exist" % (n, name, name),
                          result.stderr)
        self.assertNotIn("frame 1: skipped", result.stderr)
        after = {f: os.stat(f) for f in files}
        for f in files:
            same = (after[f].st_mtime_ns, after[f].st_ino) == (before[f].st_mtime_ns,
                                                               before[f].st_ino)
            self.assertEqual(same, "s.01." not in f.name, f.name)
        report = json.loads((self.dir / "stats.json").read_text())
        self.assertEqual([(r["frame"], r["status"]) for r in report["frame_reports"]],
                         [(-1, "skipped"), (1, "complete"), (3, "skipped")])
        # --overwrite: every file written anew (a new file renamed over the old one).
        self.render("--frames", "-1-3:2", *outputs, "--overwrite", *TINY)
        for f in files:
            self.assertNotEqual(os.stat(f).st_ino, after[f].st_ino, f.name)

    def test_pov_ray_scenes_are_read_again_for_each_frame_number(self):
        # The sphere's place is frame_number's: frames 0 and 1 differ, and each is its --frame
        # render, which reads the scene with that frame_number.
        scene = self.dir / "moving.pov"
        scene.write_text("camera { location <0, 0, -5> look_at <0, 0, 0> }\n"
                         "light_source { <0, 5, -5> color rgb 1 }\n"
                         "sphere { <frame_number - 0.5, 0, 0>, 0.5 pigment { color rgb 1 } }\n")

        def render(*args):
            return self.run_cli("render", scene, *args, *TINY)
        result = render("--frames", "0-1", "-o", "p.#.exr", "--stats-json", "stats.json")
        self.assertEqual(result.returncode, 0, result.stderr)
        for frame in (0, 1):
            result = render("--frame", frame, "-o", "single%d.exr" % frame)
            self.assertEqual(result.returncode, 0, result.stderr)
        p0, p1, s0, s1 = (self.dir / n for n in ("p.0.exr", "p.1.exr", "single0.exr", "single1.exr"))
        self.assertEqual(compare([(p0, s0), (p1, s1), (p0, p1)])[0], [True, True, False])
        report = json.loads((self.dir / "stats.json").read_text())
        self.assertEqual(["import" in r["timings_s"] for r in report["frame_reports"]],
                         [True, True])

    def test_a_signal_stops_the_sequence_and_resume_continues_the_frame(self):
        # The signal comes once a frame has written a checkpoint: that frame, k, holds samples
        # (unless it ended just then and frame k + 1 had none yet: then k + 1 writes nothing).
        render = ["--res", "32x32", "--spp", "1024", "--checkpoint-every", "0.05s", "-q"]
        sequence = ["--frames", "1-3", "-o", "f.#.exr", *render]
        process = subprocess.Popen([FILMBACK, "render", str(self.scene), *sequence,
                                    "--stats-json", "interrupted.json"],
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                   env=case_main.cli_env(), cwd=self.dir)
        self.addCleanup(lambda: process.poll() is None and process.kill())
        deadline = time.monotonic() + 60
        while not list(self.dir.glob("f.*.checkpoint.exr")) and process.poll() is None:
            self.assertLess(time.monotonic(), deadline, "no checkpoint written")
            time.sleep(0.01)
        process.send_signal(signal.SIGINT)
        _, stderr = process.communicate(timeout=120)
        self.assertEqual(process.returncode, 128 + signal.SIGINT, "no frame was interrupted")
        report = json.loads((self.dir / "interrupted.json").read_text())
        self.assertEqual(report["status"], "interrupted")
        k = len(report["frame_reports"])  # the frames that started; the next one never did
        self.assertEqual([r["status"] for r in report["frame_reports"]],
                         ["complete"] * (k - 1) + ["interrupted"])
        # The frame it stopped is saved with its checkpoint, or has nothing when no sample was.
        partial = (self.dir / ("f.%d.exr" % k)).exists()
        self.assertEqual((self.dir / ("f.%d.checkpoint.exr" % k)).exists(), partial, stderr)
        self.assertEqual(sorted(p.name for p in self.dir.glob("f.?.exr")),
                         ["f.%d.exr" % n for n in range(1, k + partial)])
        # A partial image is no done frame: the re-run continues frame k, renders the later ones.
        resumed = self.run_cli("render", self.scene, *sequence, "--resume",
                               "--stats-json", "stats.json")
        self.assertEqual(resumed.returncode, 0, resumed.stderr)
        report = json.loads((self.dir / "stats.json").read_text())
        self.assertEqual([(r["status"], r.get("checkpoint", {}).get("resumed"))
                          for r in report["frame_reports"]],
                         [("skipped", None)] * (k - 1) + [("complete", partial)] +
                         [("complete", False)] * (3 - k))
        self.assertEqual(list(self.dir.glob("*.checkpoint.exr")), [])
        self.render("--frame", k, "-o", "single.exr", *render)
        self.assertEqual(compare([(self.dir / ("f.%d.exr" % k), self.dir / "single.exr")])[0],
                         [True])

    def test_an_interrupted_frame_writes_its_exr_and_no_8_bit_image(self):
        # A half-rendered PNG or JPEG would look finished: only the EXR, marked interrupted, is
        # written, so the frame is not done and a re-run renders it.
        sequence = ["--frames", "1", "-o", "f.#.exr", "-o", "f.#.png", "-o", "f.#.jpg",
                    "--res", "32x32", "--spp", "100000", "--checkpoint-every", "0.05s", "-q"]
        process = subprocess.Popen([FILMBACK, "render", str(self.scene), *sequence],
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                   env=case_main.cli_env(), cwd=self.dir)
        self.addCleanup(lambda: process.poll() is None and process.kill())
        deadline = time.monotonic() + 60
        while not (self.dir / "f.1.checkpoint.exr").exists() and process.poll() is None:
            self.assertLess(time.monotonic(), deadline, "no checkpoint written")
            time.sleep(0.01)
        process.send_signal(signal.SIGINT)
        stdout, stderr = process.communicate(timeout=120)
        self.assertEqual(process.returncode, 128 + signal.SIGINT, stderr)
        for eight_bit in ("f.1.png", "f.1.jpg"):
            self.assertIn("filmback: interrupted: %s not written" % eight_bit, stderr)
        self.assertEqual(sorted(p.name for p in self.dir.glob("f.1.*")),
                         ["f.1.checkpoint.exr", "f.1.exr"])
        info = subprocess.run(["oiiotool", "--info", "-v", str(self.dir / "f.1.exr")],
                              capture_output=True, text=True).stdout
        self.assertRegex(info, r"filmback/interrupted: 1\b")
        self.assertRegex(stdout, r"filmback: interrupted \(signal 2\) after [0-9.]+ s: pixels of "
                                 r"32x32 hold \d+ to [1-9]\d* of 100000 samples")

    def test_bad_ranges_and_patterns_are_usage_errors_writing_nothing(self):
        # More bad ranges are unit-tested (FrameRange.BadRangesAreUsageErrorsSayingWhy).
        cases = [
            (["--frames", "5-3", "-o", "f.#.exr"], "--frames '5-3': expected A <= B"),
            (["--frames", "1-10:0", "-o", "f.#.exr"], "--frames '1-10:0': expected a STEP of 1"),
            (["--frames", "a-b", "-o", "f.#.exr"], "--frames 'a-b': expected A-B[:STEP] or N"),
            (["--frames", "1-2", "-o", "f.#.exr", "-o", "f.png"],
             "output 'f.png': expected a run of '#' in the file name with --frames"),
            (["--frames", "1-2", "-o", "f.#.exr", "--checkpoint", "c.exr"],
             "--checkpoint 'c.exr': expected a run of '#'"),
            (["-o", "f.####.exr"], "output 'f.####.exr': '#' stands for the frame number"),
            (["--frames", "9-10", "-o", "f.#.exr", "-o", "f.##.exr"],
             "output 'f.10.exr': the same file as output 'f.10.exr'"),
        ]
        for args, message in cases:
            result = self.run_cli("render", self.scene, *args, *TINY)
            self.assertEqual(result.returncode, USAGE, args)
            self.assertIn(message, result.stderr, args)
            self.assertEqual(sorted(os.listdir(self.dir)), ["moving.gltf"], args)


def configure(args):
    global FILMBACK
    FILMBACK = str(Path(args.filmback).resolve())


if __name__ == "__main__":
    sys.exit(case_main.main(FramesTest, __doc__, configure))
