#!/usr/bin/env python3
"""Field operation across two computers, over a lossy radio link, in two network namespaces:
the two ways to split the chain, each over the same impaired link.

The lead car's computer is namespace "lead", the follower's computer namespace "follower". Between
them the only link is scripts/tun_link_emulator.py: a TUN device in each namespace and, between
the two, seeded delay, jitter (hence reordering), loss and a 10 s outage applied to every IP
packet in both directions (this machine's kernel has no netem qdisc). The two setups:
  udp: the lead sends its receiver's NMEA over UDP (as `socat -u /dev/ttyACM0,raw
       UDP-SENDTO:follower:10110` does in the field); the follower runs drive.launch with
       leader_source:=udp://:10110, its own receiver, the chain and the recorder. No ROS crosses.
  ros: ROS multi-machine: one master (roscore) on the follower; the leader's driver on the lead
       (launch/lead_car.launch, its receiver on the lead's loopback as udp://:10110), publishing
       /leader/... over TCPROS through the link to drive.launch leader_driver:=false.
The two computers' clocks are not shared: pairing is by GNSS time.

Per link level and setup, SECONDS_OF_DATA of the bundled Casale part 3 drive at real time.
Measured: leader sentences sent, arrived, recorded; follower epochs paired; how late leader fixes
arrive (bag receive time minus the time the lead sent the epoch); recovery after the outage;
nodes that died, errors logged. Checked, for both setups (they must hold however the link treats
a setup):
  - no stale or mispaired sample: each valid relative_state's leader speed equals the leader log's
    speed at that GNSS time, to 0.02 m/s plus 1.5 m/s^2 times the pair's epoch skew;
  - the recording holds only sentences the lead sent, none twice (and for ros in the lead's order);
  - the follower's chain and recorder run to the end.
For the chosen setup (CHOSEN, udp) the field requirements besides: every leader sentence that
arrived is recorded (recorded == datagrams the link delivered), a floor on the share of follower
epochs paired, valid samples from the first to the last seconds, and recovery after the outage.
For the other setup those are measured and reported, not asserted.
Writes RESULTS/lossy_link.xml (JUnit, one case per setup and level) and RESULTS/lossy_link.txt.
Everything it creates (namespaces, TUN devices, processes) is removed at the end, also on failure.

The link is perfect until the data start (both computers start while the cars stand side by side)
and impaired from then on; with --impaired-start it is impaired from the first packet, so that
ROS's set-up (the lead's registration and parameter calls to the master, the subscribers'
connections) crosses the bad link too.

Usage: lossy_link_test.py WORKSPACE RESULTS_DIR [--impaired-start]
       (run as root by scripts/test_hooks/lossy_link.sh)
"""
import bisect
import collections
import glob
import json
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
import xml.sax.saxutils
import xmlrpc.client

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SECONDS_OF_DATA = 45.0
DRAIN_S = 5.0  # after the last sentence is sent: late leader data may still arrive and pair
MARK_AHEAD_S = 0.5  # the link's data start mark before the first sentence
CONNECT_TIMEOUT_S = 60.0  # ros: the follower's subscribers connected to the lead's publishers
# Jitter is +- (netem's `delay D J`): it reorders a GGA and the RMC sent right after it. Without
# the leader driver's reorder wait the epoch then completes without its RMC (no speed: an invalid
# sample): udp paired 95.6-96.9, 66.2-68.7, 41.1-44.7 % over five runs; with a 0.5 s wait
# 95.6, 80.2, 48.0 %. The floors sit below the latter and above the former at 10 % loss, so a
# driver that splits reordered epochs again fails here.
LEVELS = [
    {"name": "delay_50ms_loss_5pct", "delay_s": 0.05, "jitter_s": 0.02, "loss": 0.05, "min_paired": 0.88},
    {"name": "delay_200ms_loss_10pct", "delay_s": 0.2, "jitter_s": 0.1, "loss": 0.10, "min_paired": 0.72},
    {"name": "delay_500ms_loss_20pct_outage_10s", "delay_s": 0.5, "jitter_s": 0.2, "loss": 0.20,
     "outage_start_s": 20.0, "outage_s": 10.0, "min_paired": 0.35},
]
SETUPS = ["udp", "ros"]
CHOSEN = "udp"
# The link is perfect until the data start (the computers start while the cars stand side by side):
# what is compared is the drive. --impaired-start impairs it from the first packet on, set-up too.
IMPAIRED_START = False
LEADER_PORT, FOLLOWER_PORT = 10110, 10111
# ros: the follower's subscriptions that must be connected across the link before data flow
ROS_CONNECTIONS = [("/relative_state", "/leader/fix"), ("/record", "/leader/fix"),
                   ("/record", "/leader/nmea_sentence")]


class Namespaces:
    """Two network namespaces, removed on exit (also when setting up fails). The link between them
    is the emulator's pair of TUN devices, which go with the emulator.

    Commands enter a namespace with nsenter --net (util-linux), which switches the network
    namespace only: `ip netns exec` and `ip -n` also remount / and /sys, which fails where / is not
    a mount point (a chroot, as the bare-root CI runs in)."""

    def __init__(self, tag):
        self.tag = tag
        self.lead, self.follower = "accl" + tag, "accf" + tag
        self.lead_ip, self.follower_ip = "10.213.78.1", "10.213.78.2"
        self.made = []

    def __enter__(self):
        try:
            for ns in (self.lead, self.follower):
                subprocess.run(["ip", "netns", "add", ns], check=True)
                self.made.append(ns)
                subprocess.run(self.command(ns, ["ip", "link", "set", "lo", "up"]), check=True)
        except BaseException:
            self.__exit__()
            raise
        return self

    def __exit__(self, *exc):
        for ns in self.made:
            subprocess.run(["ip", "netns", "del", ns], stderr=subprocess.DEVNULL)
        # `ip netns add` made /run/netns a mount point; let it go when no namespace is left in it
        # (it is made again when needed), so that nothing of this test stays mounted.
        listing = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True).stdout.strip()
        if not listing:
            subprocess.run(["umount", "/run/netns"], stderr=subprocess.DEVNULL)

    def command(self, ns, args):
        return ["nsenter", "--net=/run/netns/" + ns] + args

    def path(self, ns):
        return "/run/netns/" + ns


def process_stat(pid):
    """(parent id, start time) of a process, or None when it is gone."""
    try:
        stat = open("/proc/%d/stat" % pid).read()
    except OSError:
        return None
    fields = stat[stat.rindex(")") + 2:].split()
    return int(fields[1]), fields[19]


def descendants(pid):
    """(id, start time) of pid's descendants now: the start time tells a reused id apart."""
    children = collections.defaultdict(list)
    for entry in os.listdir("/proc"):
        stat = process_stat(int(entry)) if entry.isdigit() else None
        if stat:
            children[stat[0]].append((int(entry), stat[1]))
    out, todo = [], [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            out.append(child)
            todo.append(child[0])
    return out


class Processes:
    """Processes this test started, and theirs, ended by their own ids only."""

    def __init__(self):
        self.started = []

    def start(self, args, log, env):
        process = subprocess.Popen(args, stdout=open(log, "w"), stderr=subprocess.STDOUT, env=env,
                                   start_new_session=True)
        self.started.append(process)
        return process

    def stop(self, processes, sig=signal.SIGINT, wait_s=15.0):
        """Signals all of them first, then waits, so that slow shutdowns overlap. roslaunch starts
        each node in a session of its own and gives up on a node whose shutdown hangs (the lead's
        driver unregistering from a master behind a dead link): what is left of the descendants
        known before the signal is killed by id."""
        running = [p for p in processes if p.poll() is None]
        offspring = [child for p in running for child in descendants(p.pid)]
        for process in running:
            os.killpg(process.pid, sig)
        deadline = time.time() + wait_s
        for process in running:
            try:
                process.wait(max(0.1, deadline - time.time()))
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
        for child, start_time in offspring:
            stat = process_stat(child)
            if stat and stat[1] == start_time:
                try:
                    os.kill(child, signal.SIGKILL)
                except ProcessLookupError:
                    pass

    def stop_all(self):
        self.stop(list(reversed(self.started)), signal.SIGINT, 10.0)


def wait_until(predicate, timeout_s, step_s=0.2):
    deadline = time.time() + timeout_s
    while time.time() < deadline:
        if predicate():
            return True
        time.sleep(step_s)
    return False


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


NMEA_TIME = re.compile(r"^\$..(?:GGA|RMC),(\d{2})(\d{2})(\d{2}\.\d+),")
NMEA_RMC = re.compile(r"^\$..RMC,(\d{2})(\d{2})(\d{2}\.\d+),A,[^,]*,[NS],[^,]*,[EW],([\d.]+),")


def time_of_day_s(line):
    match = NMEA_TIME.match(line)
    return None if not match else int(match.group(1)) * 3600 + int(match.group(2)) * 60 + float(match.group(3))


def log_speeds(path, day_start_s):
    """(GNSS time, speed m/s) of each RMC of a log."""
    out = []
    for line in open(path, newline="").read().splitlines():
        match = NMEA_RMC.match(line)
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


def percentile(values, share):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(share * len(ordered)))] if ordered else float("nan")


def diagnostic_values(message, name_part):
    """The key-values of the /diagnostics status whose name contains name_part, or None."""
    for status in message.status:
        if name_part in status.name:
            return {kv.key: kv.value for kv in status.values}
    return None


def analyse(bag_path, leader_log, timing, level):
    """Counts, latencies and the stale/mispaired check from the follower's bag.

    timing: start_wall (when the lead sent the log's first sentence) and first_tod_s (that
    sentence's GNSS time of day): the lead sends the epoch at GNSS time of day T at
    start_wall + T - first_tod_s, so a fix's lateness is its receive time minus that."""
    import rosbag
    counts = {"leader_sentences": 0, "leader_fixes": 0, "follower_fixes": 0, "relative_state": 0, "valid": 0,
              "acc_parameters": 0}
    valid_times, valid_arrivals, leader_arrivals, recorded_sentences = [], [], [], []
    worst_speed_error, speeds = 0.0, None
    last_relative_state_diagnostics, lead_driver_lines = {}, 0
    with rosbag.Bag(bag_path) as bag:
        for topic, message, received in bag.read_messages():
            if topic == "/leader/nmea_sentence":
                counts["leader_sentences"] += 1
                recorded_sentences.append(message.sentence)
            elif topic == "/leader/fix":
                counts["leader_fixes"] += 1
                gnss = message.header.stamp.to_sec()
                sent = timing["start_wall"] + (gnss % 86400.0 - timing["first_tod_s"]) % 86400.0
                leader_arrivals.append((received.to_sec(), received.to_sec() - sent))
            elif topic == "/follower/fix":
                counts["follower_fixes"] += 1
            elif topic == "/acc_parameters":
                counts["acc_parameters"] += 1
            elif topic == "/diagnostics":
                values = diagnostic_values(message, "Relative state")
                if values:
                    last_relative_state_diagnostics = values
                values = diagnostic_values(message, "leader_gps")
                if values and "lines" in values:
                    lead_driver_lines = max(lead_driver_lines, int(values["lines"]))
            elif topic == "/relative_state":
                counts["relative_state"] += 1
                if not message.valid:
                    continue
                counts["valid"] += 1
                t = message.header.stamp.to_sec()
                valid_times.append(t)
                valid_arrivals.append(received.to_sec())
                if speeds is None:
                    speeds = log_speeds(leader_log, int(t // 86400) * 86400.0)
                truth = interpolate(speeds, t)
                if truth is not None:
                    # An exact pair must carry the leader's own speed at its epoch; an interpolated one
                    # (a leader epoch lost) may differ by what the car can change in its skew (1.5 m/s^2
                    # x skew: half of a hard acceleration); a stale or mispaired leader is further off.
                    allowed = 0.02 + 1.5 * abs(message.epoch_skew_s)
                    worst_speed_error = max(worst_speed_error, abs(message.leader_speed_mps - truth) / allowed)
    counts["paired_share"] = counts["valid"] / max(1, counts["follower_fixes"])
    counts["worst_leader_speed_error_ratio"] = worst_speed_error
    counts["lead_driver_lines"] = lead_driver_lines
    for key in ("leader_dropouts", "follower_unpaired", "leader_too_late", "leader_out_of_order",
                "interpolated_pairs"):
        counts[key] = int(last_relative_state_diagnostics.get(key, -1))
    lateness = [late for _, late in leader_arrivals]
    counts["leader_fix_late_median_s"] = statistics.median(lateness) if lateness else float("nan")
    counts["leader_fix_late_p99_s"] = percentile(lateness, 0.99)
    counts["leader_fix_late_max_s"] = max(lateness) if lateness else float("nan")
    counts["leader_fixes_later_than_2s"] = sum(1 for late in lateness if late > 2.0)
    # The recording holds only what the lead sent, nothing twice.
    log_lines = [line for line in open(leader_log, newline="").read().splitlines() if line.strip()]
    unknown = collections.Counter(recorded_sentences) - collections.Counter(log_lines)
    counts["recorded_not_sent"] = sum(unknown.values())
    position, out_of_order = {line: i for i, line in enumerate(log_lines)}, 0
    for before, after in zip(recorded_sentences, recorded_sentences[1:]):
        out_of_order += position.get(after, -1) < position.get(before, -1)
    counts["recorded_out_of_log_order"] = out_of_order
    if valid_times:
        counts["valid_span_s"] = max(valid_times) - min(valid_times)
    if "outage_s" in level:
        # Wall time: the emulator's outage counts from the data start mark.
        back = timing["mark_wall"] + level["outage_start_s"] + level["outage_s"]
        after = [(arrived, late) for arrived, late in leader_arrivals if arrived >= back]
        counts["first_leader_fix_after_outage_s"] = after[0][0] - back if after else None
        # For ros each subscriber has its own TCPROS connection, stalled and resumed on its own:
        # the recorder's (leader fixes in the bag) and relative_state's (its valid samples).
        valid_after = [arrived for arrived in valid_arrivals if arrived >= back]
        counts["first_valid_after_outage_s"] = min(valid_after) - back if valid_after else None
        if valid_times:
            gnss_back = min(valid_times) + level["outage_start_s"] + level["outage_s"]
            counts["valid_after_outage"] = sum(1 for t in valid_times if t > gnss_back + 2.0)
        else:
            counts["valid_after_outage"] = 0
    return counts


def problems_of(counts, setup, level, link, sent):
    """What fails: the checks every setup must pass, and for the chosen one the field requirements."""
    problems = []
    if counts["worst_leader_speed_error_ratio"] > 1.0:
        problems.append("a valid sample's leader speed is %.2f times further off the leader log at its GNSS time "
                        "than its epoch skew allows (stale or mispaired)" % counts["worst_leader_speed_error_ratio"])
    if counts["recorded_not_sent"]:
        problems.append("%d recorded leader sentences were never sent, or recorded twice" % counts["recorded_not_sent"])
    if setup == "ros" and counts["recorded_out_of_log_order"]:
        problems.append("%d leader sentences recorded out of order over TCPROS" % counts["recorded_out_of_log_order"])
    if counts["leader_sentences"] > sent:
        problems.append("recorded %d leader sentences, the lead sent %d" % (counts["leader_sentences"], sent))
    if counts["follower_fixes"] < 0.95 * SECONDS_OF_DATA * 10:
        problems.append("the follower's own chain stalled: %d follower fixes recorded" % counts["follower_fixes"])
    for name in ("follower", "lead"):
        if counts.get(name + "_deaths"):
            problems.append("%d process(es) died on the %s (see %s_launch.log)" % (counts[name + "_deaths"], name, name))
    if setup != CHOSEN:
        return problems
    delivered = link["a_to_b"]["forwarded_udp_by_dst_port"].get(str(LEADER_PORT), 0)
    if counts["leader_sentences"] != delivered:
        problems.append("recorded %d leader sentences, the link delivered %d" % (counts["leader_sentences"], delivered))
    if counts["paired_share"] < level["min_paired"]:
        problems.append("only %.1f %% of follower epochs paired (floor %.0f %%)" % (
            100 * counts["paired_share"], 100 * level["min_paired"]))
    if counts["valid"] == 0:
        problems.append("no valid relative_state at all")
    elif counts["valid_span_s"] < SECONDS_OF_DATA - 5.0:
        problems.append("valid samples span only %.1f s of %.0f" % (counts["valid_span_s"], SECONDS_OF_DATA))
    after_outage_s = SECONDS_OF_DATA - level.get("outage_start_s", 0.0) - level.get("outage_s", 0.0) - 2.0
    if "outage_s" in level and counts["valid_after_outage"] < 3.0 * after_outage_s:  # 30 % of 10 Hz
        problems.append("no recovery after the outage (%d valid samples after it)" % counts["valid_after_outage"])
    return problems


def ros_connected(master_uri, pairs):
    """True when each (node, topic) subscriber has a connected inbound link (roscpp's getBusInfo)."""
    caller = "/lossy_link_test"
    master = xmlrpc.client.ServerProxy(master_uri)
    for node, topic in pairs:
        code, _, uri = master.lookupNode(caller, node)
        if code != 1:
            return False
        code, _, links = xmlrpc.client.ServerProxy(uri).getBusInfo(caller)
        # each: [connection id, publisher, direction, transport, topic, connected, ...]
        if code != 1 or not any(link[2] == "i" and link[4] == topic and link[5] for link in links):
            return False
    return True


def deaths_in(log):
    return sum(1 for line in open(log, errors="replace") if "process has died" in line)


def errors_in(log):
    """Lines a node or roslaunch logged as errors (master calls that failed, connections lost)."""
    return sum(1 for line in open(log, errors="replace") if "[ERROR]" in line or "Traceback" in line)


def ros_env(env, master_uri, **names):
    out = {k: v for k, v in env.items() if k not in ("ROS_IP", "ROS_HOSTNAME", "ROS_MASTER_URI")}
    out["ROS_MASTER_URI"] = master_uri
    out.update(names)
    return out


def run_one(setup, level, namespaces, logs, work, env, processes):
    """One setup at one link level: the link, both computers, the drive, the analysis."""
    leader_log, follower_log = logs
    index = LEVELS.index(level)
    directory = os.path.join(work, level["name"], setup)
    os.makedirs(directory)
    in_follower = lambda args: namespaces.command(namespaces.follower, args)
    in_lead = lambda args: namespaces.command(namespaces.lead, args)
    port = 11700 + 2 * index + SETUPS.index(setup)
    counts = {}

    # The link first: for ros, the master's and TCPROS's own set-up crosses it too.
    link_stats, link_ready = os.path.join(directory, "link.json"), os.path.join(directory, "link.ready")
    link_args = ["python3", os.path.join(REPO, "scripts/tun_link_emulator.py"),
                 "--netns-a", namespaces.path(namespaces.lead), "--ip-a", namespaces.lead_ip,
                 "--netns-b", namespaces.path(namespaces.follower), "--ip-b", namespaces.follower_ip,
                 "--name-a", "tunl" + namespaces.tag, "--name-b", "tunf" + namespaces.tag,
                 "--delay-s", str(level["delay_s"]), "--jitter-s", str(level["jitter_s"]), "--loss", str(level["loss"]),
                 "--seed", str(7 + index), "--duration-s", str(SECONDS_OF_DATA + CONNECT_TIMEOUT_S + 120),
                 "--stats", link_stats, "--ready", link_ready]
    if not IMPAIRED_START:
        link_args.append("--clean-until-mark")
    if "outage_s" in level:
        link_args += ["--outage-start-s", str(level["outage_start_s"]), "--outage-s", str(level["outage_s"])]
    link = processes.start(link_args, os.path.join(directory, "link.log"), env)
    if not wait_until(lambda: os.path.exists(link_ready) or link.poll() is not None, 10.0) or link.poll() is not None:
        raise RuntimeError("the link emulator did not come up (see %s)" % os.path.join(directory, "link.log"))

    if setup == "udp":
        # Everything ROS stays on the follower; only the NMEA datagrams cross the link.
        follower_env = ros_env(env, "http://localhost:%d" % port, ROS_HOSTNAME="localhost")
        lead_env = env
        # As the field command of docs/FIELD_OPERATION.md: the leader's epochs wait for sentences the link reorders.
        leader_args = ["leader_source:=udp://:%d" % LEADER_PORT, "leader_epoch_reorder_wait_s:=0.5"]
        lead_target = namespaces.follower_ip
    else:
        master_uri = "http://%s:%d" % (namespaces.follower_ip, port)
        follower_env = ros_env(env, master_uri, ROS_IP=namespaces.follower_ip)
        lead_env = ros_env(env, master_uri, ROS_IP=namespaces.lead_ip)
        leader_args = ["leader_driver:=false"]
        lead_target = "127.0.0.1"  # the lead's receiver, read by its own driver
    roscore = processes.start(in_follower(["roscore", "-p", str(port)]), os.path.join(directory, "roscore.log"),
                              follower_env)
    wait_until(lambda: subprocess.run(in_follower(["rostopic", "list"]), env=follower_env, stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL).returncode == 0, 20.0, 0.1)
    follower_log_path = os.path.join(directory, "follower_launch.log")
    follower = processes.start(in_follower(
        ["roslaunch", "acc_identification", "drive.launch", "follower_source:=udp://:%d" % FOLLOWER_PORT,
         "bag_prefix:=" + os.path.join(directory, "drive"), "window_s:=300", "period_s:=5",
         "antenna_offset_m:=5.60"] + leader_args),
        follower_log_path, follower_env)
    launches = [follower]
    lead_log_path = os.path.join(directory, "lead_launch.log")
    set_up_start = time.time()
    if setup == "ros":
        lead = processes.start(in_lead(["roslaunch", "acc_identification", "lead_car.launch",
                                        "leader_source:=udp://:%d" % LEADER_PORT]), lead_log_path, lead_env)
        launches.append(lead)
        check = in_follower(["python3", os.path.abspath(__file__), "--connected", master_uri] +
                            ["%s=%s" % pair for pair in ROS_CONNECTIONS])
        connected = wait_until(lambda: subprocess.run(check, env=follower_env, stdout=subprocess.DEVNULL,
                                                      stderr=subprocess.DEVNULL).returncode == 0,
                               CONNECT_TIMEOUT_S, 0.5)
        counts["ros_connected_after_s"] = time.time() - set_up_start if connected else None
    else:
        wait_until(lambda: "/leader/nmea_sentence" in subprocess.run(
            in_follower(["rostopic", "list"]), env=follower_env, capture_output=True, text=True).stdout, 20.0)
    wait_until(lambda: glob.glob(os.path.join(directory, "drive*.bag.active")), 20.0)
    time.sleep(1.0)

    start_wall = time.time() + 1.5
    sender = os.path.join(REPO, "scripts/nmea_udp_sender.py")
    sent_stats = os.path.join(directory, "lead_sender.json")
    lead_sender = processes.start(in_lead(["python3", sender, leader_log, lead_target, str(LEADER_PORT),
                                           "--start-at", "%.3f" % start_wall, "--stats", sent_stats]),
                                  os.path.join(directory, "lead_sender.log"), env)
    own_sender = processes.start(in_follower(["python3", sender, follower_log, "127.0.0.1", str(FOLLOWER_PORT),
                                              "--start-at", "%.3f" % start_wall]),
                                 os.path.join(directory, "own_sender.log"), env)
    # The data start mark, a little before the first sentence so that none crosses the link
    # before it is impaired; the outage counts from the mark.
    time.sleep(max(0.0, start_wall - MARK_AHEAD_S - time.time()))
    os.kill(link.pid, signal.SIGUSR1)
    mark_wall = time.time()
    lead_sender.wait(SECONDS_OF_DATA + 30)
    own_sender.wait(SECONDS_OF_DATA + 30)
    time.sleep(DRAIN_S)
    counts["launches_alive_at_end"] = all(p.poll() is None for p in launches)
    processes.stop(launches)
    processes.stop([roscore])
    processes.stop([link], signal.SIGTERM)
    counts["follower_deaths"] = deaths_in(follower_log_path)
    counts["follower_errors"] = errors_in(follower_log_path)
    if setup == "ros":
        counts["lead_deaths"] = deaths_in(lead_log_path)
        counts["lead_errors"] = errors_in(lead_log_path)
    bags = glob.glob(os.path.join(directory, "drive*.bag"))
    if not bags:
        return counts, ["the recorder left no bag (see %s)" % follower_log_path]
    link_counts = json.load(open(link_stats))
    sent = json.load(open(sent_stats))["sent"]
    first_tod = next(t for t in map(time_of_day_s, open(leader_log, newline="").read().splitlines()) if t is not None)
    counts.update(analyse(bags[0], leader_log, {"start_wall": start_wall, "first_tod_s": first_tod,
                                                 "mark_wall": mark_wall}, level))
    counts["leader_sentences_sent"] = sent
    counts["link"] = link_counts
    problems = problems_of(counts, setup, level, link_counts, sent)
    if setup == "ros" and counts.get("ros_connected_after_s") is None:
        problems.append("the follower's subscribers never connected to the lead's driver in %.0f s" % CONNECT_TIMEOUT_S)
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


TABLE_HEADER = ("setup | level | ROS connected after s | link lead->follower packets: received / lost / outage / forwarded / reordered | "
                "leader sentences sent / recorded | follower epochs | paired (share) | leader fix late median / p99 / "
                "max s (> 2 s) | dropouts / too late | after outage: valid samples, first leader fix / valid sample after s | "
                "worst speed error / allowed | problems")


def table_row(setup, level, counts, problems):
    link = counts.get("link", {}).get("a_to_b", {})
    number = lambda key, form: form % counts[key] if isinstance(counts.get(key), (int, float)) else "-"
    return " | ".join([
        setup, level["name"], number("ros_connected_after_s", "%.1f"),
        "%s / %s / %s / %s / %s" % tuple(link.get(k, "-") for k in ("received", "lost", "outage", "forwarded",
                                                                     "reordered")),
        "%s / %s" % (counts.get("leader_sentences_sent", "-"), counts.get("leader_sentences", "-")),
        str(counts.get("follower_fixes", "-")),
        "%s (%s)" % (counts.get("valid", "-"), number("paired_share", "%.3f")),
        "%s / %s / %s (%s)" % (number("leader_fix_late_median_s", "%.2f"), number("leader_fix_late_p99_s", "%.2f"),
                               number("leader_fix_late_max_s", "%.2f"), counts.get("leader_fixes_later_than_2s", "-")),
        "%s / %s" % (counts.get("leader_dropouts", "-"), counts.get("leader_too_late", "-")),
        "%s, %s / %s" % (counts.get("valid_after_outage", "-"), number("first_leader_fix_after_outage_s", "%.1f"),
                         number("first_valid_after_outage_s", "%.1f")) if "outage_s" in level else "-",
        number("worst_leader_speed_error_ratio", "%.2f"),
        "; ".join(problems) or "none"])


def run_all(namespaces, logs, work, env, processes, cases, table):
    for level in LEVELS:
        for setup in SETUPS:
            start = time.time()
            try:
                counts, problems = run_one(setup, level, namespaces, logs, work, env, processes)
            except Exception as error:  # a run that cannot complete is a failure, not a crash
                counts, problems = {}, ["%s: %s" % (type(error).__name__, error)]
            finally:
                processes.stop_all()
            row = table_row(setup, level, counts, problems)
            table.append(row)
            print("lossy_link: " + row, flush=True)
            cases.append(("%s/%s" % (setup, level["name"]), time.time() - start, problems,
                          json.dumps(counts, indent=1, sort_keys=True)))


def main():
    if len(sys.argv) > 2 and sys.argv[1] == "--connected":  # run inside the follower's namespace
        pairs = [tuple(arg.split("=", 1)) for arg in sys.argv[3:]]
        try:
            return 0 if ros_connected(sys.argv[2], pairs) else 1
        except (OSError, xmlrpc.client.Error):
            return 1
    global IMPAIRED_START
    workspace, results = sys.argv[1], sys.argv[2]
    IMPAIRED_START = "--impaired-start" in sys.argv[3:]
    os.makedirs(results, exist_ok=True)
    work = tempfile.mkdtemp(prefix="acc_lossy_link_")
    env = dict(os.environ)
    env["ROS_LOG_DIR"] = os.path.join(work, "ros_log")
    processes = Processes()
    cases, table = [], [TABLE_HEADER]
    began = time.time()
    try:
        logs = nmea_logs(workspace, work)
        namespaces = Namespaces(str(os.getpid() % 100000))
        namespaces.__enter__()  # removes what it made if it fails half way
        try:
            run_all(namespaces, logs, work, env, processes, cases, table)
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
    table.append("total %.0f s" % (time.time() - began))
    open(os.path.join(results, "lossy_link.txt"), "w").write("\n".join(table) + "\n")
    open(os.path.join(results, "lossy_link.json"), "w").write(json.dumps(
        [{"case": name, "seconds": round(seconds, 1), "problems": problems, "counts": json.loads(detail or "{}")}
         for name, seconds, problems, detail in cases], indent=1) + "\n")
    junit(os.path.join(results, "lossy_link.xml"), cases)
    return 1 if any(c[2] for c in cases) else 0


if __name__ == "__main__":
    sys.exit(main())
