"""POV-Ray .ini files (docs/pov.md ".ini files"), end to end through the built `filmback`:
`render scene.ini` renders the frames the .ini names, its clock running from Initial_Clock to
Final_Clock as POV-Ray computes it, into the outputs Output_File_Name names; `render scene.pov
--ini FILE` reads the same options, the command line's own winning; a checkpoint is not resumed
with other declarations; unknown options are warnings naming the line; a bad .ini exits 1 naming file:line:column; a portfolio scene renders through
its own .ini.

Run: ini_test.py --filmback BIN --scratch DIR [unittest names...]; --list prints the case names
(CMake registers one CTest test per case from it).
"""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import case_main
from frames_test import compare

FILMBACK = None  # set by configure()
PORTFOLIO = Path("/usr/share/doc/povray/examples/portfolio")
STANDARD_INCLUDES = Path("/usr/share/povray-3.7/include")

# A sphere whose place is the clock's: x = 2 clock - 1.
MOVING_POV = ("camera { location <0, 0, -5> look_at <0, 0, 0> }\n"
              "light_source { <0, 5, -5> color rgb 1 }\n"
              "#ifndef (Radius) #declare Radius = 0.5; #end\n"
              "sphere { <2 * clock - 1, 0, 0>, Radius pigment { color rgb 1 } }\n")
# Frames 1 to 3 with the clock from 0 to 1: 0, 0.5, 1; the subset stops at frame 2.
MOVING_INI = ("; two frames of three\n"
              "Input_File_Name=moving.pov\n"
              "+W24 +H24\n"
              "Antialias=off\n"
              "Initial_Frame=1\nFinal_Frame=3\nInitial_Clock=0\nFinal_Clock=1\n"
              "Subset_End_Frame=2\n"
              "Output_File_Name=shot\nOutput_File_Type=E\n"
              "Jitter=off\n"
              "Pause_when_Done=off\n")


class IniTest(case_main.FolderCase):
    run_timeout = 300

    def setUp(self):
        super().setUp()
        (self.dir / "moving.pov").write_text(MOVING_POV)
        (self.dir / "moving.ini").write_text(MOVING_INI)

    def test_the_clock_follows_the_ini_frames(self):
        result = self.run_cli("render", "moving.ini", "-q", "--stats-json", "stats.json")
        self.assertEqual(result.returncode, 0, result.stderr)
        # POV-Ray's names: Output_File_Name, the frame padded to Final_Frame's width (one digit).
        self.assertTrue((self.dir / "shot1.exr").exists(), os.listdir(self.dir))
        self.assertTrue((self.dir / "shot2.exr").exists(), os.listdir(self.dir))
        self.assertFalse((self.dir / "shot3.exr").exists())  # past Subset_End_Frame
        self.assertIn("warning: moving.ini:12: 'Jitter': not used by filmback", result.stderr)
        self.assertNotIn("Pause_when_Done", result.stderr)
        report = json.loads((self.dir / "stats.json").read_text())
        self.assertIn("moving.ini:12: 'Jitter': not used by filmback (docs/pov.md \".ini files\")",
                      report["frame_reports"][0]["warnings"])
        image = report["frame_reports"][0]["image"]
        # Antialias=off: 16 samples per POV-Ray ray (docs/pov.md ".ini files").
        self.assertEqual((image["width"], image["height"], image["samples_per_pixel"]),
                         (24, 24, 16))
        # Each frame is the .pov rendered with the clock POV-Ray gives it: frame 1 clock 0,
        # frame 2 clock 0.5; the two differ.
        for frame, clock in ((1, "0"), (2, "0.5")):
            result = self.run_cli("render", "moving.pov", "--frame", frame, "--clock", clock,
                                  "--res", "24x24", "--spp", "16", "-q",
                                  "-o", "single%d.exr" % frame)
            self.assertEqual(result.returncode, 0, result.stderr)
        # --frame 3 typed: the .ini's clock at frame 3 (Final_Clock, 1), into POV-Ray's name of it.
        result = self.run_cli("render", "moving.ini", "--frame", "3", "-q")
        self.assertEqual(result.returncode, 0, result.stderr)
        result = self.run_cli("render", "moving.pov", "--frame", "3", "--clock", "1",
                              "--res", "24x24", "--spp", "16", "-q", "-o", "single3.exr")
        self.assertEqual(result.returncode, 0, result.stderr)
        same = compare([(self.dir / "shot1.exr", self.dir / "single1.exr"),
                        (self.dir / "shot2.exr", self.dir / "single2.exr"),
                        (self.dir / "shot3.exr", self.dir / "single3.exr"),
                        (self.dir / "shot1.exr", self.dir / "shot2.exr")])[0]
        self.assertEqual(same, [True, True, True, False])

    def test_ini_beside_a_pov_and_the_command_line_wins(self):
        (self.dir / "big.ini").write_text("+W24 +H24\nAntialias=on\nAntialias_Depth=2\n"
                                          "Declare=Radius=0.25\n[Small]\n+W8 +H8\n")
        result = self.run_cli("render", "moving.pov", "--ini", "big.ini[small]", "-o", "a.exr",
                              "-q", "--stats-json", "a.json")
        self.assertEqual(result.returncode, 0, result.stderr)
        image = json.loads((self.dir / "a.json").read_text())["image"]
        # The [Small] section's size; depth 2: 16 x 2 x 2 samples.
        self.assertEqual((image["width"], image["height"], image["samples_per_pixel"]), (8, 8, 64))
        result = self.run_cli("render", "moving.pov", "--ini", "big.ini", "--res", "12x10",
                              "--spp", "4", "-o", "b.exr", "-q", "--stats-json", "b.json")
        self.assertEqual(result.returncode, 0, result.stderr)
        image = json.loads((self.dir / "b.json").read_text())["image"]
        self.assertEqual((image["width"], image["height"], image["samples_per_pixel"]), (12, 10, 4))
        # Declare reaches the scene: Radius 0.25 draws a smaller sphere than the default 0.5.
        for name, extra in (("declared.exr", ["--ini", "big.ini"]), ("default.exr", [])):
            result = self.run_cli("render", "moving.pov", *extra, "--res", "12x10", "--spp", "4",
                                  "--clock", "0.5", "-o", name, "-q")
            self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(compare([(self.dir / "declared.exr", self.dir / "default.exr")])[0],
                         [False])

    def test_resume_refuses_a_checkpoint_of_other_declarations(self):
        # A checkpoint of the scene with Declare=Radius=0.25 (an interrupted render's), then
        # --resume without the .ini: the same .pov, but another scene.
        (self.dir / "radius.ini").write_text("Declare=Radius=0.25\n")
        render = ["-o", "r.exr", "--res", "32x32", "--spp", "100000", "-q"]
        process = subprocess.Popen([FILMBACK, "render", "moving.pov", "--ini", "radius.ini",
                                    "--checkpoint-every", "0.01s", *render], cwd=self.dir,
                                   env=case_main.cli_env(), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        deadline = time.monotonic() + 60
        while not (self.dir / "r.checkpoint.exr").exists() and time.monotonic() < deadline:
            time.sleep(0.01)
        process.send_signal(signal.SIGINT)
        process.communicate(timeout=60)
        self.assertTrue((self.dir / "r.checkpoint.exr").exists())
        result = self.run_cli("render", "moving.pov", "--resume", *render)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("written for another render", result.stderr)

    def test_a_bad_ini_exits_non_zero_naming_file_line_column(self):
        (self.dir / "bad.ini").write_text("Input_File_Name=moving.pov\n+W24\nHeight = tall\n")
        result = self.run_cli("render", "bad.ini", "-o", "x.png", "-q")
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("bad.ini:3:10: error: Height 'tall': expected a number", result.stderr)
        # Huge values an .ini may hold, each within its own bound, but too much together.
        (self.dir / "huge.ini").write_text("Input_File_Name=moving.pov\n+W32768 +H32768\n")
        result = self.run_cli("render", "huge.ini", "-o", "x.png", "-q")
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("huge.ini: error: Width 32768 and Height 32768: 1073741824 pixels, expected "
                      "at most 268435456", result.stderr)
        (self.dir / "long.ini").write_text("Input_File_Name=moving.pov\n+KFI-1e9 +KFF1e9\n"
                                           "Output_File_Name=f\n")
        result = self.run_cli("render", "long.ini", "-q")
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("long.ini: error: frames -1000000000 to 1000000000: expected at most",
                      result.stderr)
        (self.dir / "loop.ini").write_text("Input_File_Name=moving.pov\nInclude_Ini=loop.ini\n")
        result = self.run_cli("render", "loop.ini", "-o", "x.png", "-q")
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("loop.ini:2:13: error: 'loop.ini': includes itself", result.stderr)
        self.assertEqual(sorted(os.listdir(self.dir)),
                         ["bad.ini", "huge.ini", "long.ini", "loop.ini", "moving.ini",
                          "moving.pov"])

    def test_library_paths_add_to_the_standard_includes(self):
        if not STANDARD_INCLUDES.is_dir():
            self.skipTest("Debian's povray-includes is not installed")
        # colors.inc from the standard folder, mine.inc from -L, theirs.inc from the .ini's
        # Library_Path: POV-Ray searches them all.
        for folder, name in (("mine", "MyRadius"), ("theirs", "TheirColour")):
            (self.dir / folder).mkdir()
            value = "0.5" if folder == "mine" else "Red"
            (self.dir / folder / (folder + ".inc")).write_text(f"#declare {name} = {value};\n")
        (self.dir / "included.pov").write_text(
            '#include "colors.inc"\n#include "mine.inc"\n#include "theirs.inc"\n'
            "camera { location <0, 0, -5> look_at <0, 0, 0> }\n"
            "light_source { <0, 5, -5> color White }\n"
            "sphere { 0, MyRadius pigment { color TheirColour } }\n")
        (self.dir / "included.ini").write_text("Input_File_Name=included.pov\n+W8 +H8\n"
                                               "Library_Path=theirs\n")
        result = self.run_cli("render", "included.ini", "-L", "mine", "-o", "i.exr", "-q")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue((self.dir / "i.exr").exists())

    def test_a_portfolio_scene_renders_through_its_ini(self):
        ini = PORTFOLIO / "c_colors.ini"
        if not ini.exists():
            self.skipTest("Debian's povray-examples is not installed")
        # Its .ini: frames 1 to 130 at 150x100, Output_File_Name=c_colors, the frame padded to
        # Final_Frame's three digits; two tiny frames here, the command line winning.
        result = self.run_cli("render", ini, "--frames", "1-2", "--res", "16x16", "--spp", "1",
                              "-q")
        self.assertEqual(result.returncode, 0, result.stderr)
        frames = [self.dir / "c_colors001.png", self.dir / "c_colors002.png"]
        for f in frames:
            self.assertTrue(f.exists(), os.listdir(self.dir))
        # Frame n shows the colour of colorArr[frame_number - 1]: the two frames differ.
        self.assertEqual(compare([tuple(frames)])[0], [False])


def configure(args):
    global FILMBACK
    FILMBACK = str(Path(args.filmback).resolve())


if __name__ == "__main__":
    sys.exit(case_main.main(IniTest, __doc__, configure))
