#!/usr/bin/env python3
"""What `make` does before it installs or builds anything.

A clone whose path holds whitespace builds, but catkin's test runner and roslaunch split paths at
spaces, so that almost every test and the demo would fail far from the cause; one with a colon
fails in the middle of the build (make's target patterns) and would split ROS's path lists. The
Makefile stops first and says why. Checked on copies of the Makefile alone, dry-run (`make -n`), so that nothing
is installed or built.

Usage: test_makefile.py [--junit FILE]   (from the repository or its catkin link folder)
"""
import pathlib
import shutil
import subprocess
import tempfile
import unittest

import junit_main
from make_environment import clean_make_environment

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


def dry_run(folder, target):
    """`make -n target` on a copy of the Makefile in folder: (exit status, stdout + stderr)."""
    shutil.copy(REPOSITORY / "Makefile", folder / "Makefile")
    done = subprocess.run(["make", "-n", "--no-print-directory", "-C", str(folder), target],
                          capture_output=True, text=True, env=clean_make_environment())
    return done.returncode, done.stdout + done.stderr


class Makefile(unittest.TestCase):
    def setUp(self):
        self.scratch = pathlib.Path(tempfile.mkdtemp(prefix="acc_makefile_"))

    def tearDown(self):
        shutil.rmtree(self.scratch)

    def test_a_path_with_whitespace_or_a_colon_stops_before_anything_is_installed(self):
        for parent in ("field data", "field\tdata", "run:1"):
            folder = self.scratch / parent / "acc_identification"
            folder.mkdir(parents=True)
            for target in ("deps", "build", "test", "demo"):
                status, output = dry_run(folder, target)
                self.assertEqual(status, 2, output)
                self.assertIn("holds whitespace or a colon", output)
                self.assertNotIn("apt-get", output)

    def test_a_path_without_whitespace_goes_on_to_install_and_build(self):
        folder = self.scratch / "acc_identification"
        folder.mkdir()
        status, output = dry_run(folder, "build")
        self.assertEqual(status, 0, output)
        self.assertIn("apt-get", output)
        self.assertIn("catkin_make", output)


if __name__ == "__main__":
    junit_main.run(Makefile)
