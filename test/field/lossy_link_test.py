#!/usr/bin/env python3
"""Field operation across two computers, over a lossy radio link, in two network namespaces.

The lead car's computer (namespace "lead") sends its receiver's NMEA over UDP, as
`socat -u /dev/ttyACM0,raw UDP-SENDTO:follower:10110` does in the field; the follower's computer
(namespace "follower") runs drive.launch with leader_source:=udp://:10110 and its own receiver,
the whole chain and the recorder. Between them a veth pair and, inside the follower's namespace, a
userspace relay that delays, jitters (reorders), drops and cuts the link for 10 s
(scripts/lossy_udp_relay.py; this machine's kernel has no netem qdisc). The two computers' clocks
are not shared: pairing is by GNSS time.

Per link level, 60 s of the bundled Casale part 3 drive at real time; the checks:
  - the chain keeps running and publishes relative_state from the first to the last minute;
  - every leader sentence that arrived is in the recording (recorded == forwarded by the relay);
  - no stale or mispaired sample: each valid relative_state's leader speed equals the leader
    log's speed at that GNSS time, to 0.02 m/s plus 1.5 m/s^2 times the pair's epoch skew (an
    interpolated pair, where a leader epoch was lost);
  - after the 10 s outage the chain recovers (valid samples after it);
  - the share of follower epochs paired is reported per level (and must exceed a floor).
Writes RESULTS/lossy_link.xml (JUnit, one case per level) and RESULTS/lossy_link.txt (the table).
Everything it creates (namespaces, veth, processes) is removed at the end, also on failure.

Usage: lossy_link_test.py WORKSPACE RESULTS_DIR   (run as root by scripts/test_hooks/lossy_link.sh)
"""
import bisect
import glob
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import xml.sax.saxutils

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SECONDS_OF_DATA = 60.0
LEVELS = [
    {"name": "delay_50ms_loss_5pct", "delay_s": 0.05, "jitter_s": 0.02, "loss": 0.05, "min_paired": 0.88},
    {"name": "delay_200ms_loss_10pct", "delay_s": 0.2, "jitter_s": 0.1, "loss": 0.10, "min_paired": 0.75},
    {"name": "delay_500ms_loss_20pct_outage_10s", "delay_s": 0.5, "jitter_s": 0.2, "loss": 0.20,
     "outage_start_s": 25.0, "outage_s": 10.0, "min_paired": 0.45},
]


class Namespaces:
    """Two network namespaces joined by a veth pair, removed on exit (also when setting up fails).

    Commands enter a namespace with nsenter --net (util-linux), which switches the network
    namespace only: `ip netns exec` and `ip -n` also remount / and /sys, which fails where / is not
    a mount point (a chroot, as the bare-root CI runs in)."""

    def __init__(self, tag):
        self.lead, self.follower = "accl" + tag, "accf" + tag
        self.lead_if, self.follower_if = "avl" + tag, "avf" + tag
        self.lead_ip, self.follower_ip = "10.213.77.1", "10.213.77.2"
        self.made = []

    def __enter__(self):
        try:
            self.setUp()
        except BaseException:
            self.__exit__()
            raise
        return self

    def setUp(self):
        run = lambda args: subprocess.run(args, check=True)
        for ns in (self.lead, self.follower):
            run(["ip", "netns", "add", ns])
            self.made.append(ns)
        run(["ip", "link", "add", self.lead_if, "type", "veth", "peer", "name", self.follower_if])
        run(["ip", "link", "set", self.lead_if, "netns", self.lead])
        run(["ip", "link", "set", self.follower_if, "netns", self.follower])
        for ns, interface, ip in ((self.lead, self.lead_if, self.lead_ip),
                                  (self.follower, self.follower_if, self.follower_ip)):
            run(self.command(ns, ["ip", "addr", "add", ip + "/30", "dev", interface]))
            run(self.command(ns, ["ip", "link", "set", interface, "up"]))
            run(self.command(ns, ["ip", "link", "set", "lo", "up"]))

    def __exit__(self, *exc):
        for ns in self.made:
            subprocess.run(["ip", "netns", "del", ns], stderr=subprocess.DEVNULL)
        # The veth pair, if it was made but not moved, lives in this namespace: remove it too.
        subprocess.run(["ip", "link", "del", self.lead_if], stderr=subprocess.DEVNULL)
        # `ip netns add` made /run/netns a mount point; let it go when no namespace is left in it
        # (it is made again when needed), so that nothing of this test stays mounted.
        listing = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True).stdout.strip()
        if not listing:
            subprocess.run(["umount", "/run/netns"], stderr=subprocess.DEVNULL)

    def command(self, ns, args):
        return ["nsenter", "--net=/run/netns/" + ns] + args


class Processes:
    """Processes this test started, ended by their own ids only."""

    def __init__(self):
        self.started = []

    def start(self, args, log, env):
        process = subprocess.Popen(args, stdout=open(log, "w"), stderr=subprocess.STDOUT, env=env,
                                   start_new_session=True)
        self.started.append(process)
        return process

    def stop(self, process, sig=signal.SIGINT, wait_s=15.0):
        if process.poll() is None:
            os.killpg(process.pid, sig)
            try:
                process.wait(wait_s)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()

    def stop_all(self):
        for process in reversed(self.started):
            self.stop(process, signal.SIGINT, 10.0)


def nmea_logs(workspace, work):
    """The leader's and the follower's logs of Casale part 3, first SECONDS_OF_DATA seconds."""
    tool = os.path.join(workspace, "devel/lib/acc_identification/openacc_to_nmea")
    csv = os.path.join(workspace, "build/acc_identification/data/openacc/casale/part3.csv")
    leader, follower = os.path.join(work, "leader_full.nmea"), os.path.join(work, "follower_full.nmea")
    subprocess.run([tool, csv, leader, follower], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    cut = []
    for path in (leader, follower):
        lines = open(path, newline="").read().splitlines()
        keep = 2 * int(SECONDS_OF_DATA * 10)  # GGA + RMC per epoch at 10 Hz
        out = path.replace("_full", "")
        open(out, "w", newline="").write("\r\n".join(lines[:keep]) + "\r\n")
        cut.append(out)
    return cut


NMEA_TIME = re.compile(r"^\$..RMC,(\d{2})(\d{2})(\d{2}\.\d+),A,[^,]*,[NS],[^,]*,[EW],([\d.]+),")


def log_speeds(path, day_start_s):
    """(GNSS time, speed m/s) of each RMC of a log."""
    out = []
    for line in open(path, newline="").read().splitlines():
        match = NMEA_TIME.match(line)
        if match:
            h, m, s, knots = match.groups()
            out.append((day_start_s + int(h) * 3600 + int(m) * 60 + float(s), float(knots) * 1852.0 / 3600.0))
    return out


def interpolate(series, t):
    times = [p[0] for p in series]
    i = bisect.bisect_left(times, t)
    if i < len(times) and abs(times[i] - t) < 1e-6:
        return series[i][1]
    if i == 0 or i == len(times):
        return None
    (t0, v0), (t1, v1) = series[i - 1], series[i]
    return v0 + (v1 - v0) * (t - t0) / (t1 - t0)


def analyse(bag_path, leader_log, relay_stats, level):
    import rosbag
    counts = {"leader_sentences": 0, "leader_fixes": 0, "follower_fixes": 0, "relative_state": 0, "valid": 0,
              "acc_parameters": 0}
    valid_times, worst_speed_error = [], 0.0
    speeds = None
    with rosbag.Bag(bag_path) as bag:
        for topic, message, _ in bag.read_messages():
            if topic == "/leader/nmea_sentence":
                counts["leader_sentences"] += 1
            elif topic == "/leader/fix":
                counts["leader_fixes"] += 1
            elif topic == "/follower/fix":
                counts["follower_fixes"] += 1
            elif topic == "/acc_parameters":
                counts["acc_parameters"] += 1
            elif topic == "/relative_state":
                counts["relative_state"] += 1
                if not message.valid:
                    continue
                counts["valid"] += 1
                t = message.header.stamp.to_sec()
                valid_times.append(t)
                if speeds is None:
                    day_start = int(t // 86400) * 86400.0
                    speeds = log_speeds(leader_log, day_start)
                truth = interpolate(speeds, t)
                if truth is not None:
                    # An exact pair must carry the leader's own speed at its epoch; an interpolated one
                    # (a leader epoch lost) may differ by what the car can change in its skew (1.5 m/s^2
                    # x skew: half of a hard acceleration); a stale or mispaired leader is further off.
                    allowed = 0.02 + 1.5 * abs(message.epoch_skew_s)
                    worst_speed_error = max(worst_speed_error, abs(message.leader_speed_mps - truth) / allowed)
    counts["paired_share"] = counts["valid"] / max(1, counts["follower_fixes"])
    counts["worst_leader_speed_error_ratio"] = worst_speed_error
    problems = []
    if counts["leader_sentences"] != relay_stats["forwarded"]:
        problems.append("recorded %d leader sentences, the link delivered %d" % (
            counts["leader_sentences"], relay_stats["forwarded"]))
    if worst_speed_error > 1.0:
        problems.append("a valid sample's leader speed is %.2f times further off the leader log at its GNSS time "
                        "than its epoch skew allows (stale or mispaired)" % worst_speed_error)
    if counts["paired_share"] < level["min_paired"]:
        problems.append("only %.1f %% of follower epochs paired (floor %.0f %%)" % (
            100 * counts["paired_share"], 100 * level["min_paired"]))
    if valid_times:
        first, last = min(valid_times), max(valid_times)
        if last - first < SECONDS_OF_DATA - 5.0:
            problems.append("valid samples span only %.1f s of %.0f" % (last - first, SECONDS_OF_DATA))
        if "outage_s" in level:
            end = first + level["outage_start_s"] + level["outage_s"]
            after = [t for t in valid_times if t > end + 2.0]
            counts["valid_after_outage"] = len(after)
            if len(after) < 100:
                problems.append("no recovery after the outage (%d valid samples after it)" % len(after))
    else:
        problems.append("no valid relative_state at all")
    return counts, problems


def run_level(level, namespaces, logs, work, env, processes):
    leader_log, follower_log = logs
    port = 11700 + LEVELS.index(level)
    env = dict(env, ROS_MASTER_URI="http://localhost:%d" % port, ROS_HOSTNAME="localhost")
    directory = os.path.join(work, level["name"])
    os.makedirs(directory)
    in_follower = lambda args: namespaces.command(namespaces.follower, args)
    in_lead = lambda args: namespaces.command(namespaces.lead, args)
    roscore = processes.start(in_follower(["roscore", "-p", str(port)]), os.path.join(directory, "roscore.log"), env)
    for _ in range(100):
        if subprocess.run(in_follower(["rostopic", "list"]), env=env, stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL).returncode == 0:
            break
        time.sleep(0.1)
    relay_stats = os.path.join(directory, "relay.json")
    relay_args = ["python3", os.path.join(REPO, "scripts/lossy_udp_relay.py"), namespaces.follower_ip, "6001",
                  "127.0.0.1", "10110", "--delay-s", str(level["delay_s"]), "--jitter-s", str(level["jitter_s"]),
                  "--loss", str(level["loss"]), "--seed", str(7 + LEVELS.index(level)), "--idle-s", "4",
                  "--stats", relay_stats]
    if "outage_s" in level:
        relay_args += ["--outage-start-s", str(level["outage_start_s"]), "--outage-s", str(level["outage_s"])]
    relay = processes.start(in_follower(relay_args), os.path.join(directory, "relay.log"), env)
    launch = processes.start(in_follower([
        "roslaunch", "acc_identification", "drive.launch", "leader_source:=udp://:10110",
        "follower_source:=udp://:10111", "bag_prefix:=" + os.path.join(directory, "drive"), "window_s:=300",
        "period_s:=5"]), os.path.join(directory, "launch.log"), env)
    for _ in range(200):  # the drivers, the chain and the recorder up
        topics = subprocess.run(in_follower(["rostopic", "list"]), env=env, capture_output=True, text=True).stdout
        if "/relative_state" in topics and "/leader/nmea_sentence" in topics and glob.glob(
                os.path.join(directory, "drive*.bag.active")):
            break
        time.sleep(0.1)
    time.sleep(1.0)
    start_at = "%.3f" % (time.time() + 1.5)
    sender = os.path.join(REPO, "scripts/nmea_udp_sender.py")
    lead = processes.start(in_lead(["python3", sender, leader_log, namespaces.follower_ip, "6001",
                                    "--start-at", start_at]), os.path.join(directory, "lead_sender.log"), env)
    own = processes.start(in_follower(["python3", sender, follower_log, "127.0.0.1", "10111",
                                       "--start-at", start_at]), os.path.join(directory, "own_sender.log"), env)
    lead.wait(SECONDS_OF_DATA + 30)
    own.wait(SECONDS_OF_DATA + 30)
    relay.wait(30)
    time.sleep(3.0)  # the last epochs complete and pair
    processes.stop(launch)
    processes.stop(roscore)
    bags = glob.glob(os.path.join(directory, "drive*.bag"))
    if not bags:
        return {}, ["the recorder left no bag (see %s)" % os.path.join(directory, "launch.log")]
    stats = json.load(open(relay_stats))
    counts, problems = analyse(bags[0], leader_log, stats, level)
    counts["link"] = stats
    return counts, problems


def junit(path, cases):
    out = ['<?xml version="1.0" encoding="utf-8"?>',
           '<testsuite name="lossy_link" tests="%d" failures="%d" errors="0">' % (
               len(cases), sum(1 for c in cases if c[2]))]
    for name, seconds, problems, detail in cases:
        out.append('  <testcase classname="lossy_link" name="%s" time="%.1f">' % (name, seconds))
        if problems:
            out.append('    <failure message=%s><![CDATA[%s]]></failure>' % (
                xml.sax.saxutils.quoteattr("; ".join(problems)), detail.replace("]]>", "]] >")))
        out.append("  </testcase>")
    out.append("</testsuite>")
    open(path, "w").write("\n".join(out) + "\n")


def run_levels(namespaces, logs, work, env, processes, cases, table):
    for level in LEVELS:
        start = time.time()
        try:
            counts, problems = run_level(level, namespaces, logs, work, env, processes)
        except Exception as error:  # a level that cannot run is a failure, not a crash
            counts, problems = {}, ["%s: %s" % (type(error).__name__, error)]
        finally:
            processes.stop_all()
        link = counts.get("link", {})
        row = "%s | %s / %s / %s / %s / %s | %s | %s | %.1f %% | %.4f | %s" % (
            level["name"], link.get("received"), link.get("lost"), link.get("outage"), link.get("forwarded"),
            link.get("reordered"), counts.get("follower_fixes"), counts.get("valid"),
            100 * counts.get("paired_share", 0.0), counts.get("worst_leader_speed_error_ratio", float("nan")),
            "; ".join(problems) or "none")
        table.append(row)
        print("lossy_link: " + row, flush=True)
        cases.append((level["name"], time.time() - start, problems, json.dumps(counts, indent=1)))


def main():
    workspace, results = sys.argv[1], sys.argv[2]
    os.makedirs(results, exist_ok=True)
    work = tempfile.mkdtemp(prefix="acc_lossy_link_")
    env = dict(os.environ)
    env["ROS_LOG_DIR"] = os.path.join(work, "ros_log")
    processes = Processes()
    cases, table = [], ["level | link: received / lost / outage / forwarded / reordered | follower epochs | "
                        "paired | share | worst leader speed error / allowed | problems"]
    try:
        logs = nmea_logs(workspace, work)
        namespaces = Namespaces(str(os.getpid() % 100000))
        namespaces.__enter__()  # removes what it made if it fails half way
        try:
            run_levels(namespaces, logs, work, env, processes, cases, table)
        finally:
            processes.stop_all()
            namespaces.__exit__()
    except Exception as error:  # whatever went wrong is a failed test case, never a missing result
        cases.append(("setup", 0.0, ["%s: %s" % (type(error).__name__, error)], ""))
        print("lossy_link: setup failed: %s" % error, flush=True)
    finally:
        processes.stop_all()
        if not os.environ.get("ACC_KEEP_LOSSY_LINK"):
            shutil.rmtree(work, ignore_errors=True)
    open(os.path.join(results, "lossy_link.txt"), "w").write("\n".join(table) + "\n")
    junit(os.path.join(results, "lossy_link.xml"), cases)
    return 1 if any(c[2] for c in cases) else 0


if __name__ == "__main__":
    sys.exit(main())
