"""Never losing a render (docs/cli.md, "Interrupts and checkpoints"), end to end through the
built `filmback`: a full disk or a read-only folder gives a clear error and leaves no temporary
file; SIGINT or SIGTERM stops a render within a second and writes the image it has into its
EXR (no PNG: it would look finished), with each pixel's sample count in its metadata and a
`samples` channel, and exits with 128 + the
signal; a second signal exits at once and leaves no temporary file; a checkpointed render that is
interrupted and resumed ends bit-identical to one that was never stopped; --stats-json tells what
happened, also when the render fails.

Run: never_lose_test.py --filmback BIN --scratch DIR [unittest names...]; --list prints the case
names (CMake registers one CTest test per case from it).
"""

import json
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import case_main

FILMBACK = None  # set by configure()
SCENE = Path(__file__).resolve().parents[2] / "scenes" / "default" / "default.gltf"
# Long enough to be interrupted (tens of seconds at full speed), small enough to write at once.
# Not quiet: the plan line tells the test that the render is about to run.
LONG = ["--res", "320x180", "--spp", "4096"]


def exr_info(path):
    """oiiotool's verbose header listing (channel names, filmback/* metadata) and pixel stats."""
    return subprocess.run(["oiiotool", "--info", "-v", "--stats", str(path)], capture_output=True,
                          text=True, check=True).stdout


def metadata_int(info, name):
    found = re.search(r"%s: (-?\d+)" % re.escape(name), info)
    return int(found.group(1)) if found else None


def images_identical(a, b):
    """Every pixel value equal (idiff with zero tolerance): the bit-identity the issue asks for."""
    result = subprocess.run(["idiff", "-fail", "0", "-warn", "0", str(a), str(b)],
                            capture_output=True, text=True)
    return result.returncode == 0, result.stdout


class InterruptTest(case_main.FolderCase):
    def start(self, *args):
        """A render in the background; unless quiet, its plan line is read first: the render loop
        is about to run (before that, a signal ends filmback at once, with nothing to save)."""
        process = subprocess.Popen([FILMBACK, "render", str(SCENE), *map(str, args)],
                                   stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                                   env=case_main.cli_env(), cwd=self.dir)
        self.addCleanup(lambda: process.poll() is None and process.kill())
        if "-q" not in args:
            self.assertTrue(process.stdout.readline().startswith("filmback: camera"))
        return process

    def wait_for(self, condition, seconds=60):
        deadline = time.monotonic() + seconds
        while not condition():
            self.assertLess(time.monotonic(), deadline, "timed out waiting")
            time.sleep(0.02)

    def assert_no_temporaries(self):
        hidden = [p.name for p in self.dir.iterdir() if p.name.startswith(".")]
        self.assertEqual(hidden, [], "temporary files left behind")

    def interrupt_once(self, signal_number):
        stats = self.dir / "stats.json"
        process = self.start("-o", "out.exr", "-o", "out.png", "--stats-json", stats, *LONG)
        time.sleep(0.5)
        process.send_signal(signal_number)
        sent = time.monotonic()
        stdout, _ = process.communicate(timeout=60)
        waited = time.monotonic() - sent
        self.assertEqual(process.returncode, 128 + signal_number, stdout)
        report = json.loads(stats.read_text())
        self.assertEqual(report["status"], "interrupted")
        self.assertEqual(report["interrupt"]["signal"], signal_number)
        # The render loop itself stops within a second of the signal; the whole process, which
        # also writes the EXR, is given a generous bound for a loaded machine.
        self.assertLess(report["interrupt"]["stop_latency_s"], 1.0)
        self.assertLess(waited, 10.0)
        info = exr_info(self.dir / "out.exr")
        self.assertIn("samples", re.search(r"channel list: (.*)", info).group(1))
        self.assertEqual(metadata_int(info, "filmback/interrupted"), 1)
        fewest = metadata_int(info, "filmback/fewest_samples")
        most = metadata_int(info, "filmback/most_samples")
        self.assertGreaterEqual(fewest, 1)
        self.assertLess(most, 4096)
        self.assertEqual(report["counts"]["fewest_samples_in_a_pixel"], fewest)
        # No PNG: a half-rendered 8-bit image carries no mark and would look finished.
        self.assertFalse((self.dir / "out.png").exists())
        for count in re.findall(r"(?:NanCount|InfCount): ([\d ]+)", info):
            self.assertEqual(sum(int(v) for v in count.split()), 0, "non-finite pixels")
        self.assert_no_temporaries()

    def test_sigint_writes_the_image_it_has(self):
        self.interrupt_once(signal.SIGINT)

    def test_sigterm_writes_the_image_it_has(self):
        self.interrupt_once(signal.SIGTERM)

    def test_second_signal_exits_at_once(self):
        # A large image, so that the first signal's write is still going when the second comes.
        process = self.start("-o", "big.exr", "--res", "4096x4096", "--spp", "4096")
        time.sleep(0.5)
        process.send_signal(signal.SIGINT)
        time.sleep(0.05)
        process.send_signal(signal.SIGINT)
        sent = time.monotonic()
        process.communicate(timeout=60)
        self.assertEqual(process.returncode, 128 + signal.SIGINT)
        self.assertLess(time.monotonic() - sent, 5.0)
        self.assert_no_temporaries()

    def test_resumed_render_is_bit_identical(self):
        # Importance sampling, splatting (the tiles' sums are in the checkpoint) and adaptive
        # sampling (the convergence map is; more samples, since converged pixels stop early).
        for spp, variant in ((64, []), (64, ["--reconstruction", "splat", "--filter", "gaussian"]),
                             (256, ["--adaptive-threshold", "0.01", "--adaptive-min-samples", "16"])):
            with self.subTest(variant=" ".join(variant)):
                self.resume_and_compare(spp, ["--res", "96x54", "--spp", str(spp), "-q", *variant])

    def resume_and_compare(self, spp, render):
        for name in ("whole.exr", "part.exr"):
            (self.dir / name).unlink(missing_ok=True)
        whole = self.run_cli("render", SCENE, "-o", "whole.exr", *render)
        self.assertEqual(whole.returncode, 0, whole.stderr)
        process = self.start("-o", "part.exr", "--checkpoint-every", "0.2s", *render)
        checkpoint = self.dir / "part.checkpoint.exr"
        self.wait_for(lambda: checkpoint.exists() or process.poll() is not None)
        process.send_signal(signal.SIGINT)
        process.communicate(timeout=60)
        if process.returncode == 0:
            self.skipTest("the render finished before the signal (machine too fast)")
        self.assertEqual(process.returncode, 128 + signal.SIGINT)
        self.assertTrue(checkpoint.exists(), "an interrupted checkpointed render keeps its checkpoint")
        self.assertLess(metadata_int(exr_info(self.dir / "part.exr"), "filmback/fewest_samples"),
                        spp)
        resumed = self.run_cli("render", SCENE, "-o", "part.exr", "--resume", *render)
        self.assertEqual(resumed.returncode, 0, resumed.stderr)
        self.assertFalse(checkpoint.exists(), "a finished render removes its checkpoint")
        same, why = images_identical(self.dir / "whole.exr", self.dir / "part.exr")
        self.assertTrue(same, why)
        self.assert_no_temporaries()

    def test_checkpoints_on_the_way_change_nothing(self):
        render = ["--res", "96x54", "--spp", "16", "-q"]
        self.assertEqual(self.run_cli("render", SCENE, "-o", "a.exr", *render).returncode, 0)
        result = self.run_cli("render", SCENE, "-o", "b.exr", "--checkpoint-every", "0.05s",
                              "--stats-json", "b.json", *render)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(images_identical(self.dir / "a.exr", self.dir / "b.exr")[0])
        self.assertFalse((self.dir / "b.checkpoint.exr").exists())
        self.assertEqual(json.loads((self.dir / "b.json").read_text())["status"], "complete")

    def test_resume_refuses_what_it_cannot_continue(self):
        render = ["--res", "64x36", "--spp", "8", "-q"]
        missing = self.run_cli("render", SCENE, "-o", "x.exr", "--resume", *render)
        self.assertEqual(missing.returncode, 1)
        self.assertIn("no checkpoint", missing.stderr)
        self.assertFalse((self.dir / "x.exr").exists())
        # A checkpoint of another render: the same file name, a different sample count.
        shutil.copy(self.make_checkpoint(), self.dir / "x.checkpoint.exr")
        other = self.run_cli("render", SCENE, "-o", "x.exr", "--resume", "--res", "64x36",
                             "--spp", "16", "-q")
        self.assertEqual(other.returncode, 1, other.stderr)
        self.assertIn("written for another render", other.stderr)
        self.assertFalse((self.dir / "x.exr").exists())
        bad = self.run_cli("render", SCENE, "-o", "x.exr", "--checkpoint-every", "soon", *render)
        self.assertEqual(bad.returncode, 2)
        self.assertIn("expected a duration", bad.stderr)
        self.assert_no_temporaries()

    def make_checkpoint(self):
        """A real checkpoint (64x36 px, 4096 spp): an interrupted render's, kept aside."""
        folder = self.dir / "made"
        folder.mkdir()
        process = subprocess.Popen([FILMBACK, "render", str(SCENE), "-o", "m.exr",
                                    "--checkpoint-every", "0.01s", "--res", "64x36", "--spp",
                                    "4096", "-q"],
                                   cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        self.wait_for((folder / "m.checkpoint.exr").exists)
        process.send_signal(signal.SIGINT)
        process.communicate(timeout=60)
        return folder / "m.checkpoint.exr"

    def test_full_disk_is_a_clear_error_and_leaves_nothing(self):
        def small_disk():  # writes past 20 kB fail with EFBIG, as on a full disk
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
            resource.setrlimit(resource.RLIMIT_FSIZE, (20000, 20000))
        result = subprocess.run([FILMBACK, "render", str(SCENE), "-o", "full.exr", "-o",
                                 "full.png", "--res", "320x180", "--spp", "1", "-q"],
                                cwd=self.dir, capture_output=True, text=True, preexec_fn=small_disk)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertRegex(result.stderr, r"^filmback: error: full\.exr: cannot write the image")
        self.assertEqual(list(self.dir.iterdir()), [], "an output or temporary was left")

    def test_read_only_folder_is_a_clear_error_and_leaves_nothing(self):
        folder = self.dir / "read-only"
        folder.mkdir()
        folder.chmod(0o555)
        self.dir.chmod(0o755)
        command = [FILMBACK, "render", str(SCENE), "-o", folder / "x.exr", "--res", "32x18",
                   "--spp", "1", "-q"]
        if os.geteuid() == 0:  # root writes anywhere: run as nobody, for whom it is read-only
            if shutil.which("setpriv") is None:
                self.skipTest("running as root without setpriv (util-linux)")
            command = ["setpriv", "--reuid=nobody", "--regid=nogroup", "--clear-groups", *command]
        result = subprocess.run(list(map(str, command)), capture_output=True, text=True)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertIn("x.exr: cannot write the image", result.stderr)
        self.assertIn("Permission denied", result.stderr)
        self.assertEqual(list(folder.iterdir()), [])

    def test_stats_json_tells_success_and_failure(self):
        ok = self.run_cli("render", SCENE, "-o", "ok.exr", "--res", "32x18", "--spp", "2", "-q",
                          "--stats-json", "ok.json")
        self.assertEqual(ok.returncode, 0, ok.stderr)
        report = json.loads((self.dir / "ok.json").read_text())
        self.assertEqual((report["status"], report["exit_status"]), ("complete", 0))
        self.assertEqual(report["image"], {"width": 32, "height": 18, "samples_per_pixel": 2,
                                           "seed": 0})
        self.assertEqual(report["models"]["sampler"], "sobol")
        self.assertEqual(report["models"]["integrator"], "path")
        self.assertEqual(report["counts"]["samples"], 32 * 18 * 2)
        for stage in ("import", "setup", "render", "write", "total"):
            self.assertGreaterEqual(report["timings_s"][stage], 0)
        (self.dir / "broken.gltf").write_text("{ not json")
        failed = self.run_cli("render", "broken.gltf", "-o", "no.exr", "--stats-json", "no.json")
        self.assertEqual(failed.returncode, 1)
        report = json.loads((self.dir / "no.json").read_text())
        self.assertEqual((report["status"], report["exit_status"]), ("error", 1))
        self.assertIn("broken.gltf", report["error"])
        self.assertFalse((self.dir / "no.exr").exists())


def configure(args):
    global FILMBACK
    FILMBACK = str(Path(args.filmback).resolve())


if __name__ == "__main__":
    sys.exit(case_main.main(InterruptTest, __doc__, configure))
