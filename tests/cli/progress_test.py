"""Progress reporting for a program reading filmback's stderr on a pipe (docs/cli.md,
"--progress-every"), end to end through the built `filmback`: progress lines come at the asked
interval even with no terminal and with --quiet, the final image is bit-identical with and
without the option, and a bad interval is a usage error naming the option.

Run: progress_test.py --filmback BIN --scratch DIR [unittest names...]; --list prints the case
names (CMake registers one CTest test per case from it).
"""

import re
import sys
from pathlib import Path

import case_main
from never_lose_test import images_identical

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "default" / "default.gltf"
# About a second on one thread: long enough for several lines at a tenth of a second.
SECOND_LONG = ["--res", "160x90", "--spp", "64", "--threads", "1", "-q"]


class ProgressTest(case_main.FolderCase):
    run_timeout = 120

    def test_lines_on_a_pipe_even_when_quiet(self):
        done = self.run_cli("render", SCENE, "-o", "a.exr", *SECOND_LONG, "--progress-every",
                            "0.1s")
        self.assertEqual(done.returncode, 0, done.stderr)
        percents = [float(p) for p in re.findall(r"^progress: ([\d.]+)%", done.stderr, re.M)]
        self.assertGreaterEqual(len(percents), 2, done.stderr)
        self.assertEqual(percents, sorted(percents))
        self.assertTrue(all(0 <= p <= 100 for p in percents), percents)

    def test_final_image_unchanged(self):
        plain = self.run_cli("render", SCENE, "-o", "plain.exr", *SECOND_LONG)
        reported = self.run_cli("render", SCENE, "-o", "reported.exr", *SECOND_LONG,
                                "--progress-every", "0.1s")
        self.assertEqual((plain.returncode, reported.returncode), (0, 0), reported.stderr)
        self.assertNotIn("progress:", plain.stderr)
        identical, report = images_identical(self.dir / "plain.exr", self.dir / "reported.exr")
        self.assertTrue(identical, report)

    def test_bad_interval_refused(self):
        for bad in ["0", "-1", "soon", "5x"]:
            refused = self.run_cli("render", SCENE, "-o", "bad.exr", "--progress-every", bad)
            self.assertEqual(refused.returncode, 2, bad)
            self.assertIn("--progress-every", refused.stderr, bad)
            self.assertFalse((self.dir / "bad.exr").exists())


if __name__ == "__main__":
    sys.exit(case_main.main(ProgressTest, __doc__))
