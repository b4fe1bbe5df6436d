"""Render passes (docs/cli.md, "--passes") end to end through the built `filmback`: the passes go
into the same EXR as the beauty with Blender's multi-layer names, whose Combined is bit-identical
to a render without --passes; Vector is 0 where nothing moves; an unknown pass, one filmback does not write, and --passes with parts,
checkpoints or splatting are usage errors naming what was refused.

Run: passes_test.py --filmback BIN --scratch DIR [unittest names...]; --list prints the case
names (CMake registers one CTest test per case from it).
"""

import re
import subprocess
import sys

import case_main
from never_lose_test import images_identical
from progress_test import SCENE

QUICK = ["--res", "48x27", "--spp", "4", "-q"]
ALL_PASSES = "Depth,Normal,DiffCol,GlossCol,Emit,Denoising Albedo,Denoising Normal"


def exr_header(file):
    """OpenImageIO's iinfo -v of the file: its channel list and attributes."""
    return subprocess.run(["iinfo", "-v", str(file)], capture_output=True, text=True,
                          check=True).stdout


class PassesTest(case_main.FolderCase):
    run_timeout = 120

    def test_passes_in_the_beauty_exr_with_blender_names(self):
        plain = self.run_cli("render", SCENE, "-o", "plain.exr", *QUICK)
        layers = self.run_cli("render", SCENE, "-o", "layers.exr", *QUICK, "--passes",
                              ALL_PASSES)
        self.assertEqual((plain.returncode, layers.returncode), (0, 0), layers.stderr)
        header = exr_header(self.dir / "layers.exr")
        channels = re.search(r"channel list: (.*)", header).group(1).split(", ")
        expected = ["ViewLayer.Combined." + c for c in "RGBA"] + ["ViewLayer.Depth.Z"] + [
            f"ViewLayer.{name}.{c}" for name, letters in [
                ("Normal", "XYZ"), ("DiffCol", "RGB"), ("GlossCol", "RGB"), ("Emit", "RGB"),
                ("Denoising Albedo", "RGB"), ("Denoising Normal", "XYZ")] for c in letters]
        self.assertEqual(sorted(channels), sorted(expected))
        self.assertIn("BlenderMultiChannel", header)
        # Combined, renamed back to R, G, B, is the plain render's image bit for bit.
        subprocess.run(["oiiotool", "layers.exr", "--ch",
                        "R=ViewLayer.Combined.R,G=ViewLayer.Combined.G,B=ViewLayer.Combined.B",
                        "-o", "combined.exr"], cwd=self.dir, check=True)
        identical, report = images_identical(self.dir / "plain.exr", self.dir / "combined.exr")
        self.assertTrue(identical, report)
        self.assertNotIn("ViewLayer", exr_header(self.dir / "plain.exr"))

    def test_cryptomatte_layers_and_manifests_as_blender_writes_them(self):
        crypto = self.run_cli("render", SCENE, "-o", "crypto.exr", *QUICK, "--passes",
                              "CryptoObject,CryptoMaterial")
        self.assertEqual(crypto.returncode, 0, crypto.stderr)
        header = exr_header(self.dir / "crypto.exr")
        channels = re.search(r"channel list: (.*)", header).group(1).split(", ")
        expected = ["ViewLayer.Combined." + c for c in "RGBA"] + [
            f"ViewLayer.{layer}0{rank}.{c}" for layer in ("CryptoObject", "CryptoMaterial")
            for rank in range(3) for c in "rgba"]
        self.assertEqual(sorted(channels), sorted(expected))
        # Blender 3.4's keys: the first 7 hex digits of MurmurHash3 of the layer's full name.
        for key, layer in [("542cafa", "ViewLayer.CryptoObject"),
                           ("c7dbf5e", "ViewLayer.CryptoMaterial")]:
            self.assertIn(f'cryptomatte/{key}/name: "{layer}"', header)
            self.assertIn(f'cryptomatte/{key}/hash: "MurmurHash3_32"', header)
            self.assertIn(f'cryptomatte/{key}/conversion: "uint32_to_float32"', header)
            # iinfo writes the JSON's quotes as \".
            self.assertRegex(header,
                             rf'cryptomatte/{key}/manifest: "{{\\"\w+\\":\\"[0-9a-f]{{8}}\\"')
        self.assertIn('\\"Sphere\\":\\"', header)  # the default scene's sphere node

    def test_vector_channels_zero_on_a_still_scene_and_refused_for_a_panorama(self):
        still = self.run_cli("render", SCENE, "-o", "vector.exr", *QUICK, "--passes", "Vector")
        self.assertEqual(still.returncode, 0, still.stderr)
        channels = re.search(r"channel list: (.*)",
                             exr_header(self.dir / "vector.exr")).group(1).split(", ")
        self.assertEqual(sorted(channels), sorted(["ViewLayer.Combined." + c for c in "RGBA"] +
                                                  ["ViewLayer.Vector." + c for c in "XYZW"]))
        # Nothing moves, camera included: every pixel's vector is 0 (oiiotool's channel bounds).
        stats = subprocess.run(["oiiotool", "--stats", "vector.exr"], cwd=self.dir,
                               capture_output=True, text=True, check=True).stdout
        lows = re.search(r"Min: (.*)", stats).group(1).split()
        highs = re.search(r"Max: (.*)", stats).group(1).split()
        order = re.search(r"channel list: (.*)", exr_header(self.dir / "vector.exr")).group(1)
        for i, name in enumerate(order.split(", ")):
            if name.startswith("ViewLayer.Vector."):
                self.assertEqual((float(lows[i]), float(highs[i])), (0.0, 0.0), name)
        refused = self.run_cli("render", SCENE, "-o", "pano.exr", *QUICK, "--passes", "Vector",
                               "--camera-model", "equirectangular")
        self.assertEqual(refused.returncode, 2, refused.stderr)
        self.assertIn("--passes Vector", refused.stderr)
        self.assertIn("equirectangular", refused.stderr)
        self.assertFalse((self.dir / "pano.exr").exists())

    def test_unknown_or_unwritten_pass_refused(self):
        for passes, named in [("Depth,Shadow", "'Shadow'"), ("depth", "'depth'"),
                              ("Normal,TransCol", "'TransCol'")]:
            with self.subTest(passes=passes):
                refused = self.run_cli("render", SCENE, "-o", "bad.exr", *QUICK, "--passes",
                                       passes)
                self.assertEqual(refused.returncode, 2, refused.stderr)
                self.assertIn("--passes", refused.stderr)
                self.assertIn(named, refused.stderr)
                self.assertEqual(list(self.dir.iterdir()), [])

    def test_cryptomatte_levels_set_the_layers_and_are_checked(self):
        two = self.run_cli("render", SCENE, "-o", "two.exr", *QUICK, "--passes", "CryptoObject",
                           "--cryptomatte-levels", "2")
        self.assertEqual(two.returncode, 0, two.stderr)
        channels = re.search(r"channel list: (.*)", exr_header(self.dir / "two.exr")).group(1)
        self.assertEqual(sorted(c for c in channels.split(", ") if "Crypto" in c),
                         [f"ViewLayer.CryptoObject00.{c}" for c in "abgr"])
        for args, named in [(["--passes", "CryptoObject", "--cryptomatte-levels", "3"], "'3'"),
                            (["--passes", "CryptoObject", "--cryptomatte-levels", "18"], "18"),
                            (["--passes", "Depth", "--cryptomatte-levels", "4"], "without")]:
            with self.subTest(args=args):
                refused = self.run_cli("render", SCENE, "-o", "bad.exr", *QUICK, *args)
                self.assertEqual(refused.returncode, 2, refused.stderr)
                self.assertIn("--cryptomatte-levels", refused.stderr)
                self.assertIn(named.strip("'"), refused.stderr)
                self.assertFalse((self.dir / "bad.exr").exists())

    def test_view_layer_names_the_channels_and_needs_passes(self):
        named = self.run_cli("render", SCENE, "-o", "named.exr", *QUICK, "--passes", "Depth",
                             "--view-layer", "Shot Layer")
        self.assertEqual(named.returncode, 0, named.stderr)
        channels = re.search(r"channel list: (.*)", exr_header(self.dir / "named.exr")).group(1)
        self.assertEqual(sorted(channels.split(", ")),
                         ["Shot Layer.Combined." + c for c in "ABGR"] + ["Shot Layer.Depth.Z"])
        for args, named in [(["--view-layer", "Shot Layer"], "without --passes"),
                            (["--passes", "Depth", "--view-layer", ""], "empty")]:
            with self.subTest(args=args):
                refused = self.run_cli("render", SCENE, "-o", "bad.exr", *QUICK, *args)
                self.assertEqual(refused.returncode, 2, refused.stderr)
                self.assertIn("--view-layer", refused.stderr)
                self.assertIn(named, refused.stderr)
                self.assertFalse((self.dir / "bad.exr").exists())

    def test_passes_with_parts_checkpoints_or_splatting_refused(self):
        for args, option in [(["--tile", "0/2"], "--tile"),
                             (["--checkpoint-every", "1s"], "checkpoints"),
                             (["--reconstruction", "splat"], "splat")]:
            with self.subTest(args=args):
                refused = self.run_cli("render", SCENE, "-o", "bad.exr", *QUICK, *args,
                                       "--passes", "Depth")
                self.assertEqual(refused.returncode, 2, refused.stderr)
                self.assertIn("--passes", refused.stderr)
                self.assertIn(option, refused.stderr)
                self.assertEqual(list(self.dir.iterdir()), [])


if __name__ == "__main__":
    sys.exit(case_main.main(PassesTest, __doc__))
