"""The command line of the end-to-end Python scripts (tests/cli/cli_test.py, never_lose_test.py,
tests/hard/hard_cli_test.py, tests/hostile/hostile_test.py), as filmback_add_python_cases in
tests/CMakeLists.txt calls them: `--list` prints the case names, the test methods the script's
TestCase class defines without their `test_`; `--filmback BIN --scratch DIR [case...]` runs the
cases named (a case name or unittest's Class.test_name), or all of them.
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path


def cli_env():
    """The environment filmback runs in: without FILMBACK_PLUGIN_PATH, so that the build's own
    plugins, found beside the executable, are the ones tested."""
    return {k: v for k, v in os.environ.items() if k != "FILMBACK_PLUGIN_PATH"}


class FolderCase(unittest.TestCase):
    """A case that runs filmback in a folder of its own under --scratch, removed afterwards.
    `filmback` and `scratch` are set by main(); `run_timeout` bounds one command (seconds)."""
    filmback = None
    scratch = None
    run_timeout = 600

    def setUp(self):
        self.dir = Path(tempfile.mkdtemp(prefix=self._testMethodName + "-", dir=self.scratch))
        self.addCleanup(shutil.rmtree, self.dir, True)

    def run_cli(self, *args):
        return subprocess.run([self.filmback, *map(str, args)], capture_output=True, text=True,
                              env=cli_env(), cwd=self.dir, timeout=self.run_timeout)


def main(case_class, doc, configure=None, add_options=None):
    """Runs the command line for `case_class`'s own cases and returns the exit status: 0 when all
    pass. `add_options(parser)` adds the script's own options; `configure(args)`, when given,
    hands the parsed options (--filmback, --scratch, the script's own) to the code under test
    before a case runs; FolderCase gets --filmback and --scratch in any case."""
    parser = argparse.ArgumentParser(description=doc)
    parser.add_argument("--filmback", help="the filmback executable")
    parser.add_argument("--scratch", help="folder for the test files (created)")
    parser.add_argument("--list", action="store_true", help="print the case names and exit")
    if add_options:
        add_options(parser)
    args, rest = parser.parse_known_args()
    cases = sorted(name[len("test_"):] for name in vars(case_class) if name.startswith("test_"))
    if args.list:
        print("\n".join(cases))
        return 0
    if not args.filmback or not args.scratch:
        parser.error("--filmback and --scratch are required")
    os.makedirs(args.scratch, exist_ok=True)
    FolderCase.filmback = str(Path(args.filmback).resolve())
    FolderCase.scratch = Path(args.scratch).resolve()
    if configure:
        configure(args)
    prefix = case_class.__name__ + "."
    names = [n if n.startswith(prefix) else prefix + "test_" + n for n in rest or cases]
    program = unittest.main(module=sys.modules[case_class.__module__],
                            argv=[sys.argv[0], "-v", *names], exit=False)
    return 0 if program.result.wasSuccessful() else 1
