#!/usr/bin/env python3
"""The commands of README.md and docs/*.md, run as written on the bundled data (issue 24).

A fenced block whose info string is `bash tested` is a command a reader types:

    ```bash tested
    rosrun acc_identification calibrate --split half --json fit.json "$DATA/part3.csv"
    ```

The tested blocks of one document run in order, as one bash script with `set -eo pipefail`, in a
fresh folder laid out as a clone of this repository (a link to each of its entries; build/ws is the
workspace under test, build/data is the folder's own), so that relative paths resolve as in a
clone and what the commands write stays out of the repository. The first failing command fails the
document's test, with the block's file and line; so does a roslaunch that printed a failure (it
exits with status 0 whatever its nodes did). Blocks that need hardware or run for hours (a
drive on serial ports, make test itself) are plain `bash` blocks and are not run.

Usage: test_doc_commands.py [--devel DEVEL_SPACE] [--junit FILE]
       (DEVEL_SPACE defaults to the first .../devel on CMAKE_PREFIX_PATH, as a sourced workspace sets)
"""
import json
import os
import pathlib
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import unittest

import junit_main

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
DOCUMENTS = ["README.md"] + sorted(str(path.relative_to(REPOSITORY)) for path in (REPOSITORY / "docs").glob("*.md"))
FENCE = re.compile(r"^```(\S*)(.*)$")
DOCUMENT_TIMEOUT_S = 240
# roslaunch exits with status 0 whatever its nodes did: what it prints tells a failed launch (a
# driver's FATAL, a node that died with an error, a launch file that does not parse, a bag that
# rosbag play could not open).
LAUNCH_FAILURE = re.compile(r"\[FATAL\]|RLException|rosbag play failed|process has died \[pid \d+, exit code -?[1-9]")
DEVEL = None


def tested_blocks(text):
    """[(first line number, block text)] of the ```bash tested blocks of a Markdown text."""
    blocks = []
    lines = text.splitlines()
    index = 0
    while index < len(lines):
        match = FENCE.match(lines[index])
        if match and match.group(1):
            tested = match.group(1) == "bash" and match.group(2).split() == ["tested"]
            start = index + 1
            index += 1
            while index < len(lines) and not lines[index].startswith("```"):
                index += 1
            if tested:
                blocks.append((start + 1, "\n".join(lines[start:index])))
        index += 1
    return blocks


def free_port():
    with socket.socket() as probe:
        probe.bind(("localhost", 0))
        return probe.getsockname()[1]


def devel_space():
    if DEVEL:
        return pathlib.Path(DEVEL)
    for entry in os.environ.get("CMAKE_PREFIX_PATH", "").split(":"):
        if entry.rstrip("/").endswith("/devel") and (pathlib.Path(entry) / "setup.bash").exists():
            return pathlib.Path(entry)
    raise RuntimeError("no workspace: source its devel/setup.bash or pass --devel")


def clone_like_folder(devel):
    """A folder that looks like a clone with its build: links to the repository's entries."""
    folder = pathlib.Path(tempfile.mkdtemp(prefix="acc_doc_commands_"))
    for entry in REPOSITORY.iterdir():
        if entry.name not in ("build", ".git"):
            (folder / entry.name).symlink_to(entry)
    (folder / "build").mkdir()
    (folder / "build/ws").symlink_to(devel.parent)
    return folder


def script_of(document, blocks):
    parts = ["set -eo pipefail"]
    for line, block in blocks:
        parts.append("echo '== %s:%d' >&2" % (document, line))
        parts.append(block)
    return "\n".join(parts) + "\n"


class DocumentCommands(unittest.TestCase):
    def test_the_extraction_finds_the_readme_commands(self):
        blocks = tested_blocks((REPOSITORY / "README.md").read_text())
        commands = "\n".join(block for _, block in blocks)
        for expected in ("calibrate", "diagnose", "platoon fig7", "replay_nmea.launch", "replay.launch"):
            self.assertIn(expected, commands)
        self.assertEqual(tested_blocks("```bash tested\necho a\n```\n```bash\necho b\n```\n"), [(2, "echo a")])

    def test_every_source_path_a_document_names_exists(self):
        # A file moved to another component must take its mentions along: a reader who opens
        # include/acc_identification/campaign/perturbation.h after a move finds nothing.
        named = re.compile(r"\b((?:include/acc_identification|src|scripts|test|config|launch|msg|cmake|bench)"
                           r"/[\w./-]+\.(?:h|cpp|py|sh|yaml|launch|test|msg|cmake))\b")
        missing, checked = [], 0
        for document in DOCUMENTS:
            for path in set(named.findall((REPOSITORY / document).read_text())):
                checked += 1
                if not (REPOSITORY / path).exists():
                    missing.append("%s names %s" % (document, path))
        self.assertEqual(sorted(missing), [])
        self.assertGreater(checked, 20)  # the pattern still finds the documents' paths
        self.assertTrue(named.search("see `include/acc_identification/model/acc_model.h`"))

    def test_same_results_forgives_the_last_printed_digit_and_a_bound_and_nothing_more(self):
        # The check that keeps docs/diagnosis/casale current: a build moves a fit's last digits,
        # never its words or a number beyond 1e-4 (or beyond the last decimal a sentence prints).
        def same(expected, actual):
            with tempfile.TemporaryDirectory() as folder:
                paths = [os.path.join(folder, name) for name in ("expected.json", "actual.json")]
                for path, value in zip(paths, (expected, actual)):
                    with open(path, "w") as stream:
                        json.dump(value, stream)
                checked = subprocess.run([sys.executable, str(REPOSITORY / "scripts/same_results.py"), *paths],
                                         capture_output=True, text=True)
                self.assertIn(checked.returncode, (0, 1), checked.stderr)
                return checked.returncode == 0
        self.assertTrue(same({"r": "difference 0.09912 m^2/s^2"}, {"r": "difference 0.09911 m^2/s^2"}))
        self.assertTrue(same({"eta": 2.5e-15, "r": "index 6.346e-12"}, {"eta": 1.5e-10, "r": "index 2.539e-11"}))
        self.assertTrue(same({"k1": 0.0240001}, {"k1": 0.0240}))
        self.assertFalse(same({"r": "difference 0.0991 m^2/s^2"}, {"r": "difference 0.0993 m^2/s^2"}))
        self.assertFalse(same({"r": "p = 0.062: UNDECIDED"}, {"r": "p = 0.062: UNSTABLE"}))
        self.assertFalse(same({"k1": 0.0240}, {"k1": 0.0241}))
        self.assertFalse(same({"eta": 0.0}, {"eta": 1e-6}))
        self.assertFalse(same({"r": "3 runs"}, {"r": "4 runs"}))

    def test_a_failed_launch_is_recognised(self):
        self.assertTrue(LAUNCH_FAILURE.search("[FATAL] [1.2]: gps_driver: cannot open /x.nmea"))
        self.assertTrue(LAUNCH_FAILURE.search("process has died [pid 20955, exit code 1, cmd /x]"))
        self.assertFalse(LAUNCH_FAILURE.search("process has died [pid 20955, exit code 0, cmd /x]"))
        self.assertFalse(LAUNCH_FAILURE.search("[play-6] process has finished cleanly"))


def make_document_test(document):
    def test(self):
        blocks = tested_blocks((REPOSITORY / document).read_text())
        if not blocks:
            self.skipTest("no tested commands")
        folder = clone_like_folder(devel_space())
        environment = dict(os.environ)
        environment.update({"ROS_MASTER_URI": "http://localhost:%d" % free_port(),
                            "ROS_HOME": str(folder / "build/ros_home"),
                            "ROS_LOG_DIR": str(folder / "build/ros_home/log"),
                            "PWD": str(folder)})
        environment.setdefault("ROS_HOSTNAME", "localhost")
        process = subprocess.Popen(["bash", "-c", script_of(document, blocks)], cwd=folder, env=environment,
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                   start_new_session=True)
        try:
            output, _ = process.communicate(timeout=DOCUMENT_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGINT)  # the group this test started, by its id
            try:
                output, _ = process.communicate(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                output, _ = process.communicate()
            output += "\n(timed out after %d s)" % DOCUMENT_TIMEOUT_S
        finally:
            shutil.rmtree(folder, ignore_errors=True)
        last_block = ([line for line in output.splitlines() if line.startswith("== %s:" % document)] or ["?"])[-1]
        self.assertEqual(process.returncode, 0, "a command of %s failed (block %s):\n%s"
                         % (document, last_block[3:], output[-4000:]))
        failure = LAUNCH_FAILURE.search(output)
        if failure:
            block = ([line for line in output[:failure.start()].splitlines() if line.startswith("== %s:" % document)]
                     or ["?"])[-1]
            self.fail("a launch of %s failed (block %s): %s\n%s"
                      % (document, block[3:], output[failure.start():failure.start() + 300], output[-4000:]))
    return test


for _document in DOCUMENTS:
    setattr(DocumentCommands, "test_" + re.sub(r"\W", "_", _document), make_document_test(_document))


def main():
    global DEVEL
    arguments = sys.argv[1:]
    if len(arguments) >= 2 and arguments[0] == "--devel":
        DEVEL = arguments[1]
        arguments = arguments[2:]
    junit_main.run(DocumentCommands, arguments)


if __name__ == "__main__":
    main()
