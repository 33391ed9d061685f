#!/usr/bin/env python3
"""Runs SUMO headless on a straight one-lane road: a leader whose speed is imposed sample by
sample (TraCI, speed mode 0: no check of SUMO's may alter it) and one or more vehicles of the
given vTypes behind it, in order. Writes every vehicle's speed and bumper-to-bumper gap at each
step as CSV. Called by `sumo_replay` (src/sumo/sumo_replay.cpp) with a job file it wrote:

    sumo_traci_replay.py JOB.json

JOB.json: {"sumo": "sumo", "step_length_s": 0.1, "vtype_file": "...", "work_dir": "...",
           "leader": {"length_m": 4.5, "decel_mps2": 3.0, "speeds_mps": [...]},
           "followers": [{"vtype": "ID", "gap_m": 20.0, "speed_mps": 25.0}, ...],
           "output": "trace.csv"}
Exit status 0 on success; 1 with a one-line reason on stderr otherwise (no SUMO, TraCI missing,
a vType not in the file, a vehicle SUMO did not insert or lost).
"""
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

# Debian installs SUMO's data and tools under /usr/share/sumo; SUMO itself looks there through SUMO_HOME.
os.environ.setdefault("SUMO_HOME", "/usr/share/sumo")
SUMO_TOOLS = os.path.join(os.environ["SUMO_HOME"], "tools")
LEADER_TYPE = "acc_identification_replayed_leader"
# The lane's limit: above any car's speed, so that an ACC's desired speed is its vType's maxSpeed
# (or this, when it has none) and never caps a replayed leader.
LANE_SPEED_LIMIT_MPS = 70.0


def fail(message):
    print("sumo_traci_replay: " + message, file=sys.stderr)
    sys.exit(1)


def import_traci():
    sys.path.append(SUMO_TOOLS)
    try:
        import traci  # noqa: E402  (SUMO's own TraCI client, from Debian's sumo-tools)
    except ImportError:
        fail("cannot import traci from " + SUMO_TOOLS + " (Debian package sumo-tools)")
    return traci


def vtype_lengths(vtype_file):
    lengths = {}
    for element in ElementTree.parse(vtype_file).iter("vType"):
        lengths[element.get("id")] = float(element.get("length", "5.0"))
    return lengths


def write_network(work_dir, length_m, sumo_binary):
    nodes = os.path.join(work_dir, "road.nod.xml")
    edges = os.path.join(work_dir, "road.edg.xml")
    net = os.path.join(work_dir, "road.net.xml")
    with open(nodes, "w") as out:
        out.write('<nodes><node id="start" x="0" y="0"/><node id="end" x="%.1f" y="0"/></nodes>\n' % length_m)
    with open(edges, "w") as out:
        out.write('<edges><edge id="road" from="start" to="end" numLanes="1" speed="%.1f"/></edges>\n'
                  % LANE_SPEED_LIMIT_MPS)
    netconvert = os.path.join(os.path.dirname(sumo_binary), "netconvert") if os.path.dirname(sumo_binary) \
        else "netconvert"
    try:
        result = subprocess.run([netconvert, "--node-files", nodes, "--edge-files", edges, "-o", net,
                                 "--no-warnings", "true"], capture_output=True, text=True)
    except OSError as error:  # not installed, or not where the sumo binary is: the one-line reason
        fail("no SUMO: cannot run %s (%s); Debian's package sumo has it beside sumo" % (netconvert, error.strerror))
    if result.returncode != 0:
        fail("netconvert failed: " + result.stderr.strip().splitlines()[-1] if result.stderr else "netconvert failed")
    return net


def front_positions(job, lengths):
    """Front positions on the road: the last car at 20 m, each car ahead one gap and its own
    length further (a gap is from a car's front bumper to the rear bumper of the car ahead)."""
    followers = job["followers"]
    ahead_lengths = [job["leader"]["length_m"]] + [lengths[f["vtype"]] for f in followers[:-1]]
    fronts = [20.0]
    for follower, ahead_length in zip(reversed(followers), reversed(ahead_lengths)):
        fronts.append(fronts[-1] + follower["gap_m"] + ahead_length)
    fronts.reverse()
    return fronts[0], fronts[1:]


def write_routes(work_dir, job, lengths):
    leader = job["leader"]
    leader_front_m, positions = front_positions(job, lengths)
    routes = os.path.join(work_dir, "replay.rou.xml")
    with open(routes, "w") as out:
        out.write("<routes>\n")
        # The leader's decel is what SUMO's safe speed of the car behind assumes it may brake at:
        # what the real leader did, not more (speed mode 0 lets the imposed speeds through anyway).
        out.write('  <vType id="%s" length="%r" minGap="0" accel="%r" decel="%r" emergencyDecel="%r" '
                  'speedFactor="1" speedDev="0" maxSpeed="%r"/>\n'
                  % (LEADER_TYPE, leader["length_m"], leader["decel_mps2"], leader["decel_mps2"],
                     leader["decel_mps2"], LANE_SPEED_LIMIT_MPS))
        out.write('  <route id="straight" edges="road"/>\n')
        out.write('  <vehicle id="leader" type="%s" route="straight" depart="0" departPos="%r" departSpeed="%r" '
                  'insertionChecks="none"/>\n' % (LEADER_TYPE, leader_front_m, leader["speeds_mps"][0]))
        for index, (follower, position) in enumerate(zip(job["followers"], positions)):
            out.write('  <vehicle id="car%d" type="%s" route="straight" depart="0" departPos="%r" '
                      'departSpeed="%r" insertionChecks="none"/>\n'
                      % (index + 1, follower["vtype"], position, follower["speed_mps"]))
        out.write("</routes>\n")
    return routes


def road_length_m(job, lengths):
    step = job["step_length_s"]
    travelled = sum(max(0.0, speed) for speed in job["leader"]["speeds_mps"]) * step
    cars = sum(lengths[f["vtype"]] + f["gap_m"] for f in job["followers"])
    return travelled + cars + job["leader"]["length_m"] + 500.0


def check_job(job, lengths):
    for follower in job["followers"]:
        if follower["vtype"] not in lengths:
            fail("vType '%s' is not in %s (it has: %s)" % (follower["vtype"], job["vtype_file"],
                                                           ", ".join(sorted(lengths)) or "none"))
    if len(job["leader"]["speeds_mps"]) < 2:
        fail("the leader's speed needs at least two samples")


def record(traci, vehicles, lengths_by_vehicle):
    row = []
    for index, vehicle in enumerate(vehicles):
        row.append(traci.vehicle.getSpeed(vehicle))
        if index == 0:
            continue
        ahead = vehicles[index - 1]
        gap = traci.vehicle.getLanePosition(ahead) - lengths_by_vehicle[ahead] - traci.vehicle.getLanePosition(vehicle)
        row.append(gap)
    return row


def run(job):
    lengths = vtype_lengths(job["vtype_file"])
    check_job(job, lengths)
    work_dir = job["work_dir"]
    net = write_network(work_dir, road_length_m(job, lengths), job["sumo"])
    routes = write_routes(work_dir, job, lengths)
    traci = import_traci()
    command = [job["sumo"], "-n", net, "-r", routes, "--additional-files", job["vtype_file"],
               "--step-length", repr(job["step_length_s"]), "--step-method.ballistic", "false",
               "--time-to-teleport", "-1", "--collision.action", "warn", "--no-step-log", "true",
               "--seed", "0", "--log", os.path.join(work_dir, "sumo.log")]
    try:
        traci.start(command, numRetries=20)
    except Exception as error:  # SUMO refused the scenario: its log says why
        fail("SUMO did not start (%s): %s" % (error, first_error(os.path.join(work_dir, "sumo.log"))))
    vehicles = ["leader"] + ["car%d" % (i + 1) for i in range(len(job["followers"]))]
    lengths_by_vehicle = dict(zip(vehicles, [job["leader"]["length_m"]] +
                                  [lengths[f["vtype"]] for f in job["followers"]]))
    speeds = job["leader"]["speeds_mps"]
    rows = []
    try:
        traci.simulationStep()  # inserts every vehicle at its depart position and speed
        missing = [v for v in vehicles if v not in traci.vehicle.getIDList()]
        if missing:
            fail("SUMO did not insert " + ", ".join(missing) + ": " + first_error(os.path.join(work_dir, "sumo.log")))
        traci.vehicle.setSpeedMode("leader", 0)
        traci.vehicle.setLaneChangeMode("leader", 0)
        rows.append(record(traci, vehicles, lengths_by_vehicle))
        for speed in speeds[1:]:
            traci.vehicle.setSpeed("leader", max(0.0, speed))
            traci.simulationStep()
            present = traci.vehicle.getIDList()
            if any(v not in present for v in vehicles):
                fail("a vehicle left the simulation at %.1f s: %s" % (traci.simulation.getTime(),
                                                                      first_error(os.path.join(work_dir, "sumo.log"))))
            rows.append(record(traci, vehicles, lengths_by_vehicle))
    except (traci.exceptions.TraCIException, traci.exceptions.FatalTraCIError) as error:  # SUMO ended the run
        fail("SUMO stopped (%s): %s" % (error, first_error(os.path.join(work_dir, "sumo.log"))))
    finally:
        try:
            traci.close()
        except Exception:  # already closed by SUMO
            pass
    write_trace(job["output"], job["step_length_s"], len(job["followers"]), rows)


def first_error(log_path):
    """SUMO's first error line, else its first warning: said here, since the log goes with the
    temporary folder unless sumo_replay --keep DIR keeps it."""
    warning = None
    try:
        with open(log_path) as log:
            for line in log:
                if line.startswith("Error:"):
                    return line.strip()
                if warning is None and line.startswith("Warning:"):
                    warning = line.strip()
    except OSError:
        pass
    return warning or "SUMO's log says no more (sumo_replay --keep DIR keeps it)"


def write_trace(path, step_s, followers, rows):
    header = ["time_s", "leader_speed_mps"]
    for i in range(followers):
        header += ["speed_mps_%d" % (i + 1), "gap_m_%d" % (i + 1)]
    with open(path, "w") as out:
        out.write(",".join(header) + "\n")
        for k, row in enumerate(rows):
            out.write(",".join([repr(k * step_s)] + [repr(value) for value in row]) + "\n")


def main():
    if len(sys.argv) != 2:
        fail("usage: sumo_traci_replay.py JOB.json")
    with open(sys.argv[1]) as source:
        job = json.load(source)
    run(job)


if __name__ == "__main__":
    main()
