#!/usr/bin/env python3
"""The demo's eyes on the identifier.

  demo_listener.py live                    one compact line per acc_parameters message
  demo_listener.py last BAG OUT_JSON       the last acc_parameters in a recorded bag, as JSON
  demo_listener.py compare ONLINE BATCH    online (JSON from 'last') next to calibrate --json
  demo_listener.py advance SECONDS         after the bag: let /clock run on so the identifier's
                                           period timer fires once more over every sample
"""
import datetime
import json
import math
import sys


def fmt(x, spec="7.4f"):
    """x in its column; "-" where the message holds NaN (the data do not determine it)."""
    width = spec.split(".")[0].lstrip("+")
    return ("{:" + spec + "}").format(x) if x == x else "-".rjust(int(width) if width else 0)


def pm(value, error, spec="+.2f"):
    """value +- error, or "-" when the data do not determine it."""
    if value != value:
        return "-"
    return ("{:" + spec + "}+-{:.2f}").format(value, error)


def gap(m):
    """The equilibrium gap at the drive's typical speed, "gap 21.7m@15.8m/s"; "gap -" without one."""
    if m.equilibrium_gap_m != m.equilibrium_gap_m:
        return "gap {:>15}".format("-")
    return "gap {:5.1f}m@{:4.1f}m/s".format(m.equilibrium_gap_m, m.equilibrium_speed_mps)


def line(m):
    """One update: the window (each quantity "-" where not determined), the drive so far, the verdict."""
    utc = datetime.datetime.utcfromtimestamp(m.header.stamp.to_sec()).strftime("%H:%M:%S")
    span = (m.window_end - m.window_start).to_sec()
    drive_s = (m.window_end - m.drive_start).to_sec() if m.drive_start.to_sec() > 0 else 0.0
    verdict = m.stability_verdict.upper()
    if m.stability_p_value == m.stability_p_value:
        # The sequential verdict: its anytime-valid p-value and the two e-values (decides at 1/alpha).
        verdict += " p={:.3f} E_unstable {:.3g} E_stable {:.3g} ({} samples)".format(
            m.stability_p_value, m.stability_e_value_unstable, m.stability_e_value_stable, m.stability_samples)
    note = "all determined" if m.identifiable else "not determined: " + (m.identifiability_note[:90] or "-")
    return ("{} win {:5.0f}s n={:5d} k1 {} k2 {} tau_e {} eta {} {} margin {} | "
            "drive {:6.0f}s margin {} | verdict {} | {}".format(
                utc, span, m.samples, fmt(m.k1_per_s2, "6.4f"), fmt(m.k2_per_s, "6.4f"), fmt(m.tau_e_s, "5.3f"),
                fmt(m.eta_m, "5.2f"), gap(m), pm(m.stability_margin, m.stability_margin_std_error), drive_s,
                pm(m.drive_stability_margin, m.drive_stability_margin_std_error), verdict, note))


def live():
    import rospy
    from acc_identification.msg import AccParameters
    rospy.init_node("demo_listener", anonymous=True)
    rospy.Subscriber("acc_parameters", AccParameters, lambda m: print(line(m), flush=True), queue_size=100)
    rospy.spin()


def advance(seconds):
    import time
    import rospy
    from rosgraph_msgs.msg import Clock
    rospy.init_node("demo_clock", anonymous=True)
    publisher = rospy.Publisher("/clock", Clock, queue_size=10)
    time.sleep(0.5)
    now = rospy.Time.now()
    for _ in range(int(float(seconds) / 0.1)):
        now += rospy.Duration(0.1)
        publisher.publish(Clock(clock=now))
        time.sleep(0.02)
    return 0


def last(bag_path, out_path):
    import rosbag
    message = None
    count = identifiable = decided = 0
    first_decided = None
    with rosbag.Bag(bag_path) as bag:
        for _, m, _ in bag.read_messages(topics=["/acc_parameters"]):
            message, count = m, count + 1
            identifiable += 1 if m.identifiable else 0
            if m.stability_verdict in ("stable", "unstable"):
                decided += 1
                if first_decided is None:
                    first_decided = (m.window_end - m.drive_start).to_sec()
    if message is None:
        print("no acc_parameters in " + bag_path, file=sys.stderr)
        return 1
    keys = ["samples", "segments", "k1_per_s2", "k2_per_s", "tau_e_s", "eta_m", "lambda2", "string_stable",
            "rmse_speed_mps", "rmse_gap_m", "identifiable", "identifiability_note", "drive_samples",
            "stability_verdict", "stability_p_value", "stability_margin_low", "stability_margin_high",
            "stability_samples", "stability_reason", "stability_margin", "stability_margin_std_error",
            "model_adequate", "model_adequacy_reasons"]
    out = {k: getattr(message, k) for k in keys}
    out["window_start_s"] = message.window_start.to_sec()
    out["window_end_s"] = message.window_end.to_sec()
    out["messages"] = count
    out["identifiable_messages"] = identifiable
    out["decided_messages"] = decided
    out["first_decided_after_s"] = first_decided
    with open(out_path, "w") as f:
        json.dump(out, f, indent=1, default=lambda v: None)
    print("{:.3f} {:.3f}".format(out["window_start_s"], out["window_end_s"]))
    return 0


def batch_value(batch, key):
    """A parameter or lambda2 from calibrate's JSON."""
    section = batch.get("stability", {}) if key == "lambda2" else batch.get("parameters", {})
    return section.get(key)


def number(value):
    """A JSON number as a float, NaN for null."""
    return float("nan") if value is None else float(value)


def compared(label, online, batch):
    """One row of the online/batch table; "-" where a side has no value (not determined)."""
    difference = online - batch
    return "{:12s} {:>10s} {:>10s} {:>10s}".format(label, fmt(online, "10.4f"), fmt(batch, "10.4f"),
                                                  fmt(difference, "+10.4f"))


def compare(online_path, batch_path):
    online = json.load(open(online_path))
    batch = json.load(open(batch_path))
    rows = [("k1 [1/s^2]", "k1_per_s2"), ("k2 [1/s]", "k2_per_s"), ("tau_e [s]", "tau_e_s"), ("eta [m]", "eta_m"),
            ("lambda2", "lambda2")]
    print("{:12s} {:>10s} {:>10s} {:>10s}".format("", "online", "batch", "difference"))
    worst = 0.0
    for label, key in rows:
        o, b = number(online.get(key)), number(batch_value(batch, key))
        print(compared(label, o, b))
        if key != "lambda2" and o == o and b == b:
            worst = max(worst, abs(o - b) / max(abs(b), 1e-9))
    train = batch.get("summary", {}).get("train", {})
    for label, key in (("rmse v [m/s]", "rmse_speed_mps"), ("rmse s [m]", "rmse_gap_m")):
        print(compared(label, number(online.get(key)), number(train.get(key))))
    print("samples: online {}, batch {}  window {:.1f}-{:.1f} s (UTC {})".format(
        online["samples"], train.get("samples"), 0.0, online["window_end_s"] - online["window_start_s"],
        datetime.datetime.utcfromtimestamp(online["window_start_s"]).strftime("%Y-%m-%d %H:%M:%S")))
    print("identifiable: online {}, batch {}; {} of {} online updates were identifiable".format(
        online["identifiable"], batch.get("identifiable"), online["identifiable_messages"], online["messages"]))
    test = batch.get("stability_test") or {}
    print("string stability, live sequential verdict (anytime-valid, {} samples looked at): {} p={}; batch "
          "calibrate's fixed-sample test (one look, {} held-out samples): {} p={}".format(
              online.get("stability_samples"), online.get("stability_verdict"),
              fmt(number(online.get("stability_p_value")), ".3f"), test.get("held_out_samples"), test.get("verdict"),
              fmt(number(test.get("p_value")), ".3f")))
    if online.get("first_decided_after_s") is not None:
        print("the live verdict was decided {:.0f} s into the drive; {} of {} updates carried a decided verdict".format(
            online["first_decided_after_s"], online["decided_messages"], online["messages"]))
    else:
        print("no update carried a decided verdict: the data do not decide string stability (undecided, not hidden)")
    if online["identifiable_messages"] == 0:
        print("No window of this drive determined all four parameters (on real drives tau_e and eta often "
              "trade off); each one is NaN in the message (- above) where not determined, the others are published.")
    if not online["identifiable"]:
        print("What the last window does not determine: " + online["identifiability_note"])
        print("batch calibrate: " + str(batch.get("identifiability_note")))
        print("The fits themselves (RMSE above) are compared instead; the batch parameters are printed "
              "as found, not as results.")
    else:
        print("largest relative difference of k1, k2, tau_e, eta: {:.2%}".format(worst))
    return 0


if __name__ == "__main__":
    if len(sys.argv) >= 2 and sys.argv[1] == "live":
        sys.exit(live())
    if len(sys.argv) == 3 and sys.argv[1] == "advance":
        sys.exit(advance(sys.argv[2]))
    if len(sys.argv) == 4 and sys.argv[1] == "last":
        sys.exit(last(sys.argv[2], sys.argv[3]))
    if len(sys.argv) == 4 and sys.argv[1] == "compare":
        sys.exit(compare(sys.argv[2], sys.argv[3]))
    print(__doc__, file=sys.stderr)
    sys.exit(2)
