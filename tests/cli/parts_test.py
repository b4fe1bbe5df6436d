"""Parts of a render (docs/cli.md, "Parts of a render"), end to end through the built `filmback`:
`render --tile I/N --tile-plan` writes partial films (plans from `filmback tile-plan` too) that `merge` turns into the whole render's EXR
and PNG, pixel for pixel (idiff with zero tolerance); merge refuses a part of another scene, a
missing part and a truncated file (exit 1, the file or the uncovered pixels named, no output
written); bad --tile/--crop are usage errors (exit 2); parts of an adaptive render merge into the
same image; a part interrupted by SIGINT resumes from its checkpoint and merges into the same image. Few processes (each costs ~0.5 s of CPU to start): the
matrix (every sampler, filter, reconstruction, seed, part count) and the other refusals are
in-process, tests/unit/partial_film_test.cpp.

Run: parts_test.py --filmback BIN --scratch DIR [unittest names...]; --list prints the case names.
"""

import json
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import case_main
from never_lose_test import images_identical

FILMBACK = None  # set by configure()
SCENE = Path(__file__).resolve().parents[2] / "scenes" / "default" / "default.gltf"
# 5 rows of 16-pixel tiles, the last partial; a wide filter splatted across part borders.
RENDER = ["--res", "70x72", "--spp", "4", "-q", "--reconstruction", "splat", "--filter",
          "blackman_harris", "--sampler", "zsobol", "--seed", "5"]


class PartsTest(case_main.FolderCase):
    def render(self, *args, scene=SCENE):
        result = self.run_cli("render", scene, *args)
        self.assertEqual(result.returncode, 0, result.stderr)

    def assert_refused(self, status, named, *args):
        result = self.run_cli(*args)
        self.assertEqual(result.returncode, status, result.stderr)
        self.assertIn(named, result.stderr)
        self.assertEqual(sorted(p.name for p in self.dir.iterdir() if p.name.startswith(("out", "."))),
                         [], "an output or temporary file was left")

    def test_tiles_of_a_plan_merge_into_the_whole_render(self):
        self.render("-o", "whole.exr", "-o", "whole.png", "--stats-json", "whole.json", *RENDER)
        # A plan's uneven parts (as `filmback tile-plan` writes them), cut off the tile grid.
        plan = {"format": "filmback-tile-plan", "version": 1, "width": 70, "height": 72,
                "parts": [{"crop": [0, 37, 70, 72], "estimated_seconds": 1.5},
                          {"crop": [0, 0, 70, 37], "estimated_seconds": 1.0}]}
        (self.dir / "plan.json").write_text(json.dumps(plan))
        for i in range(2):
            self.render("--tile", f"{i}/2", "--tile-plan", "plan.json", "-o", f"plan{i}.exr",
                        *RENDER)
        result = self.run_cli("merge", "plan0.exr", "plan1.exr", "-o", "merged.exr",
                              "-o", "merged.png")
        self.assertEqual(result.returncode, 0, result.stderr)
        for extension in ("exr", "png"):
            same, why = images_identical(self.dir / f"whole.{extension}",
                                         self.dir / f"merged.{extension}")
            self.assertTrue(same, why)
        # `filmback tile-plan` from the whole render's tile times and from the parts' (a previous
        # frame's): three parts that tile the frame; a file that is no report is refused.
        for source in (["--report", "whole.json"], ["--previous", "plan0.exr", "plan1.exr"]):
            result = self.run_cli("tile-plan", "--tiles", "3", "-o", "three.json", *source)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assert_tiles_frame(json.loads((self.dir / "three.json").read_text()), 70, 72, 3)
        self.assert_refused(1, "whole.png", "tile-plan", SCENE, "--tiles", "2", "-o",
                            "out.json", "--report", "whole.png")

    def assert_tiles_frame(self, plan, width, height, parts):
        self.assertEqual((plan["width"], plan["height"], len(plan["parts"])), (width, height, parts))
        owners = [[0] * width for _ in range(height)]
        for part in plan["parts"]:
            x0, y0, x1, y1 = part["crop"]
            self.assertGreater(part["estimated_seconds"], 0)
            for y in range(y0, y1):
                for x in range(x0, x1):
                    owners[y][x] += 1
        self.assertTrue(all(o == 1 for row in owners for o in row), "parts overlap or leave gaps")

    def exr_attributes(self, file):
        """The image's metadata as `oiiotool --info -v` prints it: name -> text (quotes kept)."""
        text = subprocess.run(["oiiotool", "--info", "-v", str(self.dir / file)],
                              capture_output=True, text=True, check=True).stdout
        return dict(re.findall(r"^ +([\w/]+): (.*)$", text, re.MULTILINE))

    def test_parts_name_their_crops_and_merge_sums_their_times(self):
        # Bands of tile rows without a plan: rows 0-31 and 32-71.
        crops = ["0,0,70,32", "0,32,70,72"]
        for i in range(2):
            result = self.run_cli("render", SCENE, "--tile", f"{i}/2", "-o", f"p{i}.exr", *RENDER)
            self.assertEqual(result.returncode, 0, result.stderr)
            self.assertIn(f"filmback: rendered part {crops[i]} of 70x72 at 4 spp in ",
                          result.stdout)
        result = self.run_cli("merge", "p0.exr", "p1.exr", "-o", "merged.exr")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("filmback: merged 2 parts into 70x72; summed over the parts: ", result.stdout)
        render_s = sampling_s = 0.0
        for i in range(2):
            part = self.exr_attributes(f"p{i}.exr")
            render_s += float(part["filmback/part/render_seconds"].strip('"'))
            sampling_s += sum(float(s) for s in
                              part["filmback/part/tile_seconds"].strip('"').split())
        merged = self.exr_attributes("merged.exr")
        self.assertEqual(merged["filmback/parts"], "2")
        # 32-bit floats, which oiiotool prints to at least 6 digits: the sums to 1e-5.
        self.assertAlmostEqual(float(merged["filmback/render_seconds"]), render_s,
                               delta=1e-5 * render_s)
        self.assertAlmostEqual(float(merged["filmback/parts_sampling_seconds"]), sampling_s,
                               delta=1e-5 * sampling_s)
        self.assertGreater(sampling_s, 0)

    def test_merge_refuses_what_is_not_one_render(self):
        # Bands of tile rows: rows 0-31 and 32-71. The other refusals (seed, overlap, a corrupt
        # splat table) are PartialFilm.* in tests/unit/partial_film_test.cpp.
        self.render("--tile", "0/2", "-o", "a.exr", *RENDER)
        other_scene = self.dir / "other.gltf"
        other_scene.write_text(SCENE.read_text() + "\n")  # other bytes: another scene's digest
        shutil.copy(SCENE.with_suffix(".bin"), self.dir / "default.bin")
        self.render("--tile", "1/2", "-o", "scene.exr", *RENDER, scene=other_scene)
        data = (self.dir / "scene.exr").read_bytes()
        (self.dir / "cut.exr").write_bytes(data[: len(data) * 2 // 3])
        self.assert_refused(1, "scene.exr: a part of another render", "merge", "a.exr",
                            "scene.exr", "-o", "out.exr", "-o", "out.png")
        self.assert_refused(1, "no part covers pixels 0,32,70,72", "merge", "a.exr",
                            "-o", "out.exr")
        self.assert_refused(1, "cut.exr", "merge", "cut.exr", "a.exr", "-o", "out.exr")

    def test_bad_parts_are_usage_errors(self):
        self.assert_refused(2, "--tile '8/8'", "render", SCENE, "--tile", "8/8", "-o", "out.exr")
        self.assert_refused(2, "expected one output, a .exr", "render", SCENE, "--tile", "0/2",
                            "-o", "out.png")
        self.assert_refused(2, "outside the 70x72 frame", "render", SCENE, *RENDER,
                            "--crop", "0,0,71,10", "-o", "out.exr")

    def test_adaptive_parts_merge_into_the_whole_render(self):
        # Each part samples an apron of one pixel per convergence check (3 here) around its crop.
        render = ["--res", "70x72", "--spp", "64", "-q", "--adaptive-threshold", "0.05",
                  "--adaptive-min-samples", "16", "--seed", "3"]
        self.render("-o", "whole.exr", *render)
        for i in range(3):
            self.render("--tile", f"{i}/3", "-o", f"part{i}.exr", *render)
        result = self.run_cli("merge", "part0.exr", "part1.exr", "part2.exr", "-o", "merged.exr")
        self.assertEqual(result.returncode, 0, result.stderr)
        same, why = images_identical(self.dir / "whole.exr", self.dir / "merged.exr")
        self.assertTrue(same, why)

    def test_interrupted_part_resumes_into_the_same_image(self):
        render = ["--res", "96x54", "--spp", "64"]
        self.render("-o", "whole.exr", "-q", *render)
        process = subprocess.Popen([FILMBACK, "render", str(SCENE), "--crop", "0,0,96,54",
                                    "-o", "part.exr", "--checkpoint-every", "0.2s", *render],
                                   stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                                   env=case_main.cli_env(), cwd=self.dir)
        self.addCleanup(lambda: process.poll() is None and process.kill())
        self.assertTrue(process.stdout.readline().startswith("filmback: camera"))
        checkpoint = self.dir / "part.checkpoint.exr"
        deadline = time.monotonic() + 60
        while not checkpoint.exists() and process.poll() is None:
            self.assertLess(time.monotonic(), deadline, "timed out waiting for a checkpoint")
            time.sleep(0.02)
        process.send_signal(signal.SIGINT)
        process.communicate(timeout=60)
        if process.returncode == 0:
            self.skipTest("the part finished before it could be interrupted")
        self.assertEqual(process.returncode, 128 + signal.SIGINT)
        self.assertFalse((self.dir / "part.exr").exists(), "an interrupted part writes no film")
        # The checkpoint of another part (another crop) is refused.
        other = self.run_cli("render", SCENE, "--crop", "0,0,96,50", "-o", "part.exr",
                             "--resume", "-q", *render)
        self.assertEqual(other.returncode, 1)
        self.assertIn("written for another render", other.stderr)
        self.render("--crop", "0,0,96,54", "-o", "part.exr", "--resume", "-q", *render)
        self.assertFalse(checkpoint.exists())
        result = self.run_cli("merge", "part.exr", "-o", "merged.exr")
        self.assertEqual(result.returncode, 0, result.stderr)
        same, why = images_identical(self.dir / "whole.exr", self.dir / "merged.exr")
        self.assertTrue(same, why)


def configure(args):
    global FILMBACK
    FILMBACK = str(Path(args.filmback).resolve())


if __name__ == "__main__":
    sys.exit(case_main.main(PartsTest, __doc__, configure))
