#!/usr/bin/env python3
"""The launch files and tools as a newcomer types them (issue 24).

- replay_nmea.launch and replay.launch take log and bag paths relative to the directory roslaunch
  was started in (the nodes themselves run in ROS_HOME), and end on their own: replay_nmea.launch
  after its logs, both at once when a source is missing, with the reason on the screen; a path
  with spaces, apostrophes and quotes (a user's folder) reaches its node whole.
- drive.launch records under a relative bag_prefix in such a folder, and ends at once, with the
  reason, when it cannot record there (rosbag record alone only logs an error and exits).
- `platoon` takes the paper's figure numbers (fig1 ... fig8) as well as the figures' names, and
  an unknown figure gets a message that lists them.
- `calibrate --report DIR` gives the fit as a picture: a figure per run, the traces as CSV, and
  report.md opening with the package's headline.
- `--starts 0` is refused by calibrate and campaign (not "every start diverged"), and diagnose
  refuses a report folder it cannot create before it reads the runs.
- `make demo`'s live line shows "-" where the identifier publishes NaN (not determined).

Each roslaunch gets a master of its own on a free port, in its own process group, ended by its id.
Usage: test_launch_sources.py [--junit FILE]   (with the workspace's devel/setup.bash sourced)
"""
import csv
import importlib.util
import json
import os
import pathlib
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import types
import unittest

import junit_main
import rosbag

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]
# An OpenACC excerpt shipped in the repository (JRC OpenACC, CC BY 4.0: see its ATTRIBUTION.md).
OPENACC_EXCERPT = REPOSITORY / "test/data/openacc/zalazone_dynamic_part26_excerpt.csv"
# A canonical run shipped in the repository (Casale part 4, JRC OpenACC, CC BY 4.0: see the folder's ATTRIBUTION.md).
CASALE_RUN = REPOSITORY / "test/data/runs/casale_part4.csv"
# A bag of raw sentences of both receivers (made by test/data/end_to_end/make_dropout_bag.sh).
SENTENCE_BAG = REPOSITORY / "test/data/end_to_end/leader_dropout_5s.bag"
LAUNCH_TIMEOUT_S = 90


# A folder of the user's whose name holds a space, an apostrophe and quotes: roslaunch splits a
# node's arguments and launch prefix as a shell would, so a launch file must not pass a user's
# path through them unquoted, nor quoted (a quote in the path ends the quoting).
USER_FOLDER = "O'Brien's \"field day\""


def free_port():
    with socket.socket() as probe:
        probe.bind(("localhost", 0))
        return probe.getsockname()[1]


class UserCommands(unittest.TestCase):
    def setUp(self):
        self.directory = pathlib.Path(tempfile.mkdtemp(prefix="acc_launch_sources_"))
        self.environment = dict(os.environ)
        self.environment.update({
            "ROS_MASTER_URI": "http://localhost:%d" % free_port(),
            "ROS_HOME": str(self.directory / "ros_home"),
            "ROS_LOG_DIR": str(self.directory / "ros_home/log"),
            # What a shell sets: the directory the user typed the command in.
            "PWD": str(self.directory),
        })
        self.environment.setdefault("ROS_HOSTNAME", "localhost")

    def tearDown(self):
        shutil.rmtree(self.directory, ignore_errors=True)

    def run_command(self, arguments, timeout_s=60):
        return subprocess.run(arguments, cwd=self.directory, env=self.environment, capture_output=True,
                              text=True, timeout=timeout_s)

    def roslaunch(self, arguments):
        """Runs roslaunch ARGUMENTS in the user's directory; (ended on its own, its output)."""
        process = subprocess.Popen(["roslaunch", "acc_identification"] + arguments, cwd=self.directory,
                                   env=self.environment, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                   text=True, start_new_session=True)
        try:
            output, _ = process.communicate(timeout=LAUNCH_TIMEOUT_S)
            return True, output
        except subprocess.TimeoutExpired:
            # Ours only: the process group this test started, by its id.
            os.killpg(process.pid, signal.SIGINT)
            try:
                output, _ = process.communicate(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                output, _ = process.communicate()
            return False, output

    def make_logs(self):
        """Two logs in a folder whose name holds a space, as a user's folders may."""
        (self.directory / USER_FOLDER).mkdir(exist_ok=True)
        converted = self.run_command(["rosrun", "acc_identification", "openacc_to_nmea", str(OPENACC_EXCERPT),
                                      USER_FOLDER + "/L.nmea", USER_FOLDER + "/F.nmea"])
        self.assertEqual(converted.returncode, 0, converted.stdout + converted.stderr)
        self.assertTrue((self.directory / USER_FOLDER / "L.nmea").stat().st_size > 0)
        return USER_FOLDER + "/L.nmea", USER_FOLDER + "/F.nmea"

    def test_replay_nmea_takes_relative_logs_and_ends_after_them(self):
        logs = self.make_logs()
        ended, output = self.roslaunch(["replay_nmea.launch", "leader_log:=" + logs[0], "follower_log:=" + logs[1],
                                        "rate:=10", "end_wait_s:=2"])
        self.assertTrue(ended, "replay_nmea.launch did not end after its logs:\n" + output[-3000:])
        self.assertNotIn("FATAL", output, output[-3000:])
        for log in logs:
            self.assertIn("gps_driver: end of file://%s/%s" % (self.directory, log), output, output[-3000:])

    def test_replay_nmea_ends_when_a_log_is_missing(self):
        leader, _ = self.make_logs()
        ended, output = self.roslaunch(["replay_nmea.launch", "leader_log:=" + leader, "follower_log:=missing.nmea",
                                        "rate:=10"])
        self.assertTrue(ended, "replay_nmea.launch stayed up without its follower log:\n" + output[-3000:])
        self.assertIn("cannot open %s/missing.nmea" % self.directory, output, output[-3000:])

    def test_replay_takes_a_relative_bag_whose_path_holds_spaces_and_quotes(self):
        (self.directory / USER_FOLDER).mkdir()
        shutil.copy(SENTENCE_BAG, self.directory / USER_FOLDER / "drive 1.bag")
        ended, output = self.roslaunch(["replay.launch", "bag:=%s/drive 1.bag" % USER_FOLDER, "rate:=20",
                                        "required:=true"])
        self.assertTrue(ended, "replay.launch did not end after its bag:\n" + output[-3000:])
        self.assertNotIn("rosbag play failed", output, output[-3000:])
        self.assertNotIn("[FATAL]", output, output[-3000:])
        # The bag's sentences went through the drivers and relative_state to the identifier,
        # which names each window it solved by its times.
        self.assertRegex(output, r"identifier: window [0-9.]+-[0-9.]+ s", output[-3000:])

    def test_replay_ends_when_the_bag_is_missing(self):
        ended, output = self.roslaunch(["replay.launch", "bag:=%s/missing.bag" % USER_FOLDER, "rate:=20"])
        self.assertTrue(ended, "replay.launch stayed up without its bag:\n" + output[-3000:])
        self.assertIn("rosbag play failed on %s/%s/missing.bag" % (self.directory, USER_FOLDER), output,
                      output[-3000:])

    def test_drive_records_under_a_relative_prefix_whose_path_holds_quotes(self):
        leader, follower = self.make_logs()
        ended, output = self.roslaunch(["drive.launch", "leader_source:=file://%s/%s?rate=4" % (self.directory, leader),
                                        "follower_source:=file://%s/%s?rate=4" % (self.directory, follower),
                                        "bag_prefix:=%s/drive" % USER_FOLDER, "antenna_offset_m:=5.60"])
        self.assertTrue(ended, "drive.launch did not end after its logs:\n" + output[-3000:])
        self.assertNotIn("cannot record", output, output[-3000:])
        bags = sorted((self.directory / USER_FOLDER).glob("drive_*.bag*"))
        self.assertEqual(len(bags), 1, "%s\n%s" % (bags, output[-3000:]))
        with rosbag.Bag(str(bags[0])) as bag:
            topics = bag.get_type_and_topic_info().topics
        self.assertGreater(topics["/leader/nmea_sentence"].message_count, 0, sorted(topics))
        self.assertGreater(topics["/follower/nmea_sentence"].message_count, 0, sorted(topics))

    def test_drive_ends_when_it_cannot_record(self):
        # Receivers that never end (nothing sends to these ports): only the recorder can end it.
        ended, output = self.roslaunch(["drive.launch", "leader_source:=udp://:%d" % free_port(),
                                        "follower_source:=udp://:%d" % free_port(),
                                        "bag_prefix:=%s/missing/drive" % USER_FOLDER, "antenna_offset_m:=5.60"])
        self.assertTrue(ended, "drive.launch went on unrecorded:\n" + output[-3000:])
        self.assertIn("drive.launch: cannot record in %s/%s/missing" % (self.directory, USER_FOLDER), output,
                      output[-3000:])

    def test_drive_needs_the_antenna_offset(self):
        # A drive of one's own cars never takes the replays' default (5.60 m, the Casale cars).
        ended, output = self.roslaunch(["drive.launch", "leader_source:=udp://:%d" % free_port(),
                                        "follower_source:=udp://:%d" % free_port(),
                                        "bag_prefix:=%s/drive" % USER_FOLDER])
        self.assertTrue(ended, "drive.launch started without the antenna offset:\n" + output[-3000:])
        self.assertIn("antenna_offset_m", output, output[-3000:])
        self.assertEqual(sorted((self.directory / USER_FOLDER).glob("drive_*.bag*")), [], output[-3000:])

    def test_platoon_takes_the_papers_figure_numbers(self):
        for figure in ("fig6", "fig7"):
            result = self.run_command(["rosrun", "acc_identification", "platoon", figure, "--csv", figure + ".csv"])
            self.assertEqual(result.returncode, 0, figure + ": " + result.stdout + result.stderr)
            self.assertTrue((self.directory / (figure + ".csv")).stat().st_size > 0)
        unknown = self.run_command(["rosrun", "acc_identification", "platoon", "fig9", "--csv", "fig9.csv"])
        self.assertNotEqual(unknown.returncode, 0)
        for figure in ["fig%d" % number for number in range(1, 9)] + ["sinusoid", "lead-profile"]:
            self.assertIn(figure, unknown.stderr, unknown.stderr)

    def test_calibrate_and_campaign_refuse_zero_starts(self):
        for tool, data in (("calibrate", OPENACC_EXCERPT), ("campaign", OPENACC_EXCERPT)):
            result = self.run_command(["rosrun", "acc_identification", tool, "--starts", "0", str(data)])
            self.assertNotEqual(result.returncode, 0, tool + ": " + result.stdout + result.stderr)
            self.assertIn("--starts", result.stderr, tool + ": " + result.stderr)
            self.assertNotIn("diverged", result.stdout + result.stderr)

    def test_campaign_refuses_an_unknown_platoon_candidate_before_the_work(self):
        result = self.run_command(["rosrun", "acc_identification", "campaign", "--platoon-effects",
                                   "speed_dependent_gains", str(OPENACC_EXCERPT)])
        self.assertEqual(result.returncode, 2, result.stdout + result.stderr)
        self.assertIn("speed_dependent_gains is not among the platoon diagnosis's candidates", result.stderr)
        # The candidates as the option is written, so that one can be copied from the message.
        self.assertIn("quadratic_closing_response,reaction_delay", result.stderr)
        self.assertIn("reaction_delay@speed_and_gap", result.stderr)
        self.assertNotIn("group(s)", result.stderr)  # stopped before reading the runs

    def test_diagnose_refuses_an_unwritable_report_before_the_work(self):
        result = self.run_command(["rosrun", "acc_identification", "diagnose", "--no-plots", "--report",
                                   "/proc/no_such_report_folder", str(OPENACC_EXCERPT)])
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("cannot create /proc/no_such_report_folder", result.stderr)
        self.assertNotIn("pair read", result.stdout + result.stderr)  # stopped before reading the runs

    def test_nmea_to_csv_needs_the_antennas_and_says_when_nothing_pairs(self):
        leader, follower = self.make_logs()
        tool = ["rosrun", "acc_identification", "nmea_to_csv"]
        unplaced = self.run_command(tool + [leader, follower, "run.csv"])
        self.assertEqual(unplaced.returncode, 2, unplaced.stdout + unplaced.stderr)
        self.assertIn("say where the antennas are", unplaced.stderr)
        self.assertFalse((self.directory / "run.csv").exists())
        paired = self.run_command(tool + ["--antenna-offset-m", "4.5", "--json", "pairs.json", leader, follower,
                                          "run.csv"])
        self.assertEqual(paired.returncode, 0, paired.stdout + paired.stderr)
        with open(self.directory / "run.csv", newline="") as rows:
            read = list(csv.DictReader(rows))
        self.assertEqual(len(read), json.loads((self.directory / "pairs.json").read_text())["states"])
        self.assertTrue(read and all(row["valid"] in ("0", "1") for row in read))
        # The follower's log an hour later than the leader's: no epoch pairs, and it is said.
        shifted = self.run_command(["rosrun", "acc_identification", "openacc_to_nmea", "--time-shift-s", "3600",
                                    str(OPENACC_EXCERPT), "L_late.nmea", "F_late.nmea"])
        self.assertEqual(shifted.returncode, 0, shifted.stdout + shifted.stderr)
        apart = self.run_command(tool + ["--antenna-offset-m", "4.5", leader, "F_late.nmea", "apart.csv"])
        self.assertEqual(apart.returncode, 2, apart.stdout + apart.stderr)
        self.assertIn("no follower epoch could be paired", apart.stderr)
        self.assertIn(": nothing written", apart.stdout)  # not "-> apart.csv": no file is made
        self.assertNotIn("-> apart.csv", apart.stdout)
        self.assertFalse((self.directory / "apart.csv").exists())

    def test_calibrate_report_has_the_headline_traces_and_a_figure_per_run(self):
        result = self.run_command(["rosrun", "acc_identification", "calibrate", "--quiet", "--split", "half",
                                   "--report", "fit", str(CASALE_RUN)])
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        report = (self.directory / "fit/report.md").read_text().splitlines()
        self.assertEqual(report[0], "# ACC calibration")
        self.assertTrue(report[2].startswith("**Verdict:** "), report[2])
        self.assertIn("· **Model:** ", report[2])
        # What the file gave, counted (the JSON's inputs_read): a canonical CSV read whole.
        self.assertIn("## Data read", report)
        data_row = next(line for line in report if line.startswith(f"| `{CASALE_RUN}`"))
        self.assertIn("| csv | - | 1151 | 1151 | 1 | none |", data_row)
        with open(self.directory / "fit/fit_traces.csv") as traces:
            rows = list(csv.DictReader(traces))
        self.assertEqual({row["part"] for row in rows}, {"train", "held_out"})
        residual = float(rows[5]["measured_speed_mps"]) - float(rows[5]["simulated_speed_mps"])
        self.assertAlmostEqual(float(rows[5]["speed_residual_mps"]), residual, places=9)
        self.assertTrue((self.directory / "fit/fit_1.png").stat().st_size > 10000)
        self.assertTrue((self.directory / "fit/calibration.json").exists())

    def test_demo_line_says_dash_where_the_message_holds_nan(self):
        # make demo's live line: a quantity the data do not determine is NaN in AccParameters and
        # "-" on the screen; a determined one keeps its number.
        # Loaded from its file: a script of the package, not a module on the path.
        spec = importlib.util.spec_from_file_location("demo_listener", REPOSITORY / "scripts/demo_listener.py")
        demo_listener = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(demo_listener)

        class Stamp(float):
            def to_sec(self):
                return float(self)

            def __sub__(self, other):
                return Stamp(float(self) - float(other))

        nan = float("nan")
        message = types.SimpleNamespace(
            header=types.SimpleNamespace(stamp=Stamp(1000.0)), window_start=Stamp(900.0), window_end=Stamp(930.0),
            drive_start=Stamp(880.0), samples=301, k1_per_s2=nan, k2_per_s=0.2547, tau_e_s=nan, eta_m=nan,
            equilibrium_speed_mps=15.8, equilibrium_gap_m=nan, stability_margin=nan, stability_margin_std_error=nan,
            drive_stability_margin=-1.57, drive_stability_margin_std_error=0.32, stability_verdict="undecided",
            stability_p_value=nan, identifiable=False, identifiability_note="k1 = 0.0094 +- 0.024")
        line = demo_listener.line(message)
        self.assertNotIn("nan", line.lower().replace("not determined", ""), line)
        self.assertIn("k1      - k2 0.2547 tau_e     - eta     - gap               - margin - |", line)
        self.assertIn("drive     50s margin -1.57+-0.32", line)
        # The summary's online/batch table: "-" where a side has no value, and no difference then.
        self.assertEqual(demo_listener.compared("tau_e [s]", nan, 0.0).split(), ["tau_e", "[s]", "-", "0.0000", "-"])


def main():
    junit_main.run(UserCommands)


if __name__ == "__main__":
    main()
