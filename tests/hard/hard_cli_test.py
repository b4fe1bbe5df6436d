"""The hard cases through the command line (scenes/hard/README.md): bad input from the hard scenes
exits 1 (bad usage 2) with one `file: JSON path: what` line and no output file, and a 16384-pixel-
wide render stays within a stated memory bound. Built on tests/cli/cli_test.py's CliTest (its
helpers; only the cases defined here run).

Run: hard_cli_test.py --filmback BIN --scratch DIR [case names...]; --list prints the case names
(CMake registers one CTest test per case, label `hard`).
"""

import os
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "cli"))
import case_main  # noqa: E402
import cli_test  # noqa: E402

SCENES = Path(__file__).resolve().parents[2] / "scenes" / "hard"
KIB = 1024


def report(name, error, limit, what, seconds):
    """The hard suite's line (tests/hard/hard_case.h): these cases render nothing non-finite."""
    print("[   hard   ] %s: non-finite 0, error %.4g (limit %.4g, %s), %.2f s"
          % (name, error, limit, what, seconds), flush=True)


def peak_rss_bytes(*args):
    """Runs the built filmback; returns its exit status and its peak resident set (wait4's
    ru_maxrss, KiB on Linux) in bytes."""
    child = subprocess.Popen([cli_test.FILMBACK, *map(str, args)], stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, stdin=subprocess.DEVNULL)
    _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)
    child.stderr.close()
    return child.returncode, usage.ru_maxrss * KIB


class HardCliTest(cli_test.CliTest):
    def test_focus_inside_the_focal_length_is_bad_input(self):
        scene = SCENES / "focus_inside_focal_length.gltf"
        start = time.monotonic()
        self.assert_error(self.render(scene, "-q"), cli_test.INPUT,
                          "%s: cameras[0].extensions.FILMBACK_blender.focus_distance_m: " % scene,
                          "focus distance 0.04 m is not beyond the focal length 50 mm",
                          "expected a focus distance over 0.05 m")
        report("focus inside f, CLI", 0, 0, "exit 1, file, camera, value and bound",
               time.monotonic() - start)

    def test_typed_focus_at_the_focal_length_is_bad_usage(self):
        self.assert_usage_error(SCENES / "focus_near_focal_length.gltf",
                                ["--focus-distance", "0.05", "-q"], "--focus-distance: ",
                                "focus distance 0.05 m is not beyond the focal length 50 mm")

    def test_non_finite_vertex_data_and_material_values_are_bad_input(self):
        for file, path, what in [
                ("nan_position.gltf", "meshes[0].primitives[0].attributes.POSITION (accessors[0])",
                 "element 2 is not a finite number"),
                ("inf_normal.gltf", "meshes[0].primitives[0].attributes.NORMAL (accessors[1])",
                 "element 1 is not a finite number"),
                ("inf_emission.gltf", "materials[0]", "must be finite and non-negative")]:
            self.assert_input_error(SCENES / file, path, what)

    def test_a_malformed_lens_file_is_bad_input(self):
        """The realistic camera's lens file (plugins/cameras/realistic) is untrusted: a bad number
        is named by file, line and column, exit 1, nothing written."""
        lens = self.dir / "bad_lens.dat"
        lens.write_text("# a singlet\n50 6 1.5 20\n-80 6x 1 20\n0 0 0 10\n")
        start = time.monotonic()
        result = self.render(SCENES / "aperture_f182.gltf", "-q", "--camera-model",
                             "realistic:lens=%s" % lens)
        self.assert_error(result, cli_test.INPUT, "", "camera 'realistic' refused to start: ",
                          "%s:3:5: expected a number (thickness, mm)" % lens)
        report("malformed lens file, CLI", 0, 0, "exit 1, file:line:column and what",
               time.monotonic() - start)

    def test_splat_with_a_filter_under_half_a_pixel_is_bad_usage(self):
        self.assert_usage_error(SCENES / "filter_edge.gltf",
                                ["--reconstruction", "splat", "--filter", "box:radius=0.01", "-q"],
                                "--reconstruction splat: the filter 'box:radius=0.01' reaches 0.01 px",
                                "expected at least 0.5 px")

    def test_memory_of_a_16384_pixel_wide_image_is_bounded(self):
        """Peak RSS above the same render at 1 x 1 is at most, per pixel, what the film holds
        (sums of c = 3 channels and a weight in double, a 4-byte sample count: 8(c + 1) + 4), the
        image (4c), one float copy while writing (4c) and the 8-bit PNG (c): 63 bytes; splatting
        adds its tiles' sums, (1 + 2 reach / 16)^2 8(c + 1) with the default gaussian's reach of
        2 px. Plus 16 MiB for allocator slack and per-thread buffers. Measured 57 and 101 bytes
        a pixel."""
        width, height = 16384, 128
        scene = SCENES / "wide_image.gltf"
        for reconstruction, per_pixel in [("importance", 63), ("splat", 63 + (1 + 4 / 16) ** 2 * 32)]:
            outputs = ["-o", self.out / "wide.exr", "-o", self.out / "wide.png"]
            common = ["render", scene, *outputs, "--spp", "1", "-q", "--reconstruction",
                      reconstruction]
            start = time.monotonic()
            status, base = peak_rss_bytes(*common, "--res", "1x1")
            self.assertEqual(status, 0)
            status, peak = peak_rss_bytes(*common, "--res", "%dx%d" % (width, height))
            self.assertEqual(status, 0)
            bound = width * height * per_pixel + 16 * KIB * KIB
            report("16384x%d %s, peak RSS" % (height, reconstruction), (peak - base) / bound, 1,
                   "(peak - peak at 1x1) / (W H %.0f B + 16 MiB); %.0f MiB above %.0f MiB"
                   % (per_pixel, (peak - base) / KIB / KIB, base / KIB / KIB),
                   time.monotonic() - start)
            self.assertLessEqual(peak - base, bound)


def configure(args):
    cli_test.FILMBACK, cli_test.SCRATCH = args.filmback, args.scratch


if __name__ == "__main__":
    sys.exit(case_main.main(HardCliTest, __doc__, configure))
