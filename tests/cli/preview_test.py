"""The live image a program shows while filmback renders (docs/cli.md, "--preview"), end to end
through the built `filmback`: the preview is an EXR of the frame's size, written atomically (no
temporary left behind), the final image is bit-identical with and without it, and --preview
without --preview-every, the reverse, or a preview that is not an EXR are usage errors naming the
option.

Run: preview_test.py --filmback BIN --scratch DIR [unittest names...]; --list prints the case
names (CMake registers one CTest test per case from it).
"""

import re
import subprocess
import sys

import case_main
from never_lose_test import images_identical
# About a second on one thread: long enough for several previews at a tenth of a second.
from progress_test import SCENE, SECOND_LONG



def image_size(file):
    """(width, height) as OpenImageIO's iinfo reads the file's header; it fails on a broken file."""
    info = subprocess.run(["iinfo", str(file)], capture_output=True, text=True, check=True)
    width, height = re.search(r": +(\d+) x +(\d+)", info.stdout).groups()
    return int(width), int(height)


class PreviewTest(case_main.FolderCase):
    run_timeout = 120

    def test_preview_written_and_final_image_unchanged(self):
        for reconstruction in ["importance", "splat"]:
            with self.subTest(reconstruction=reconstruction):
                common = [*SECOND_LONG, "--reconstruction", reconstruction]
                plain = self.run_cli("render", SCENE, "-o", "plain.exr", *common)
                previewed = self.run_cli("render", SCENE, "-o", "previewed.exr", *common,
                                         "--preview", "live.exr", "--preview-every", "0.1s")
                self.assertEqual((plain.returncode, previewed.returncode), (0, 0),
                                 previewed.stderr)
                self.assertEqual(image_size(self.dir / "live.exr"), (160, 90))
                identical, report = images_identical(self.dir / "plain.exr",
                                                     self.dir / "previewed.exr")
                self.assertTrue(identical, report)
                self.assertEqual(sorted(p.name for p in self.dir.iterdir()),
                                 ["live.exr", "plain.exr", "previewed.exr"])
                for name in ["live.exr", "plain.exr", "previewed.exr"]:
                    (self.dir / name).unlink()

    def test_incomplete_or_non_exr_preview_refused(self):
        for args, option in [(["--preview", "live.exr"], "--preview"),
                             (["--preview-every", "1s"], "--preview-every"),
                             (["--preview", "live.png", "--preview-every", "1s"], "--preview"),
                             (["--preview", "live.exr", "--preview-every", "soon"],
                              "--preview-every")]:
            with self.subTest(args=args):
                refused = self.run_cli("render", SCENE, "-o", "bad.exr", *args)
                self.assertEqual(refused.returncode, 2, refused.stderr)
                self.assertIn(option, refused.stderr)
                self.assertEqual(list(self.dir.iterdir()), [])


if __name__ == "__main__":
    sys.exit(case_main.main(PreviewTest, __doc__))
