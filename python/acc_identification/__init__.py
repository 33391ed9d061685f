"""acc_identification from Python: read runs into pandas, calibrate, diagnose and run campaigns
with the package's own C++ code (the same calls as the command-line tools, so the same numbers;
docs/PYTHON.md).

    import acc_identification as acc
    run = acc.read_run("part9.csv")              # pandas.DataFrame, canonical columns
    run = acc.pair_nmea_logs("L.nmea", "F.nmea", "pairs.csv", antenna_offset_m=5.6)  # two receivers' logs
    fit = acc.calibrate([run], split="half")     # dict: what `calibrate --json` writes
    diag = acc.diagnose([run]); camp = acc.campaign(["dir/"])

Errors raise the tools' messages (ValueError for bad input, RuntimeError otherwise); the solves
release the GIL, so threads can run several at once. The generated ROS messages stay where catkin
puts them: acc_identification.msg.
"""
import json
import math
import sys

from acc_identification import _core

COLUMNS = ("time_s", "space_gap_m", "follower_speed_mps", "leader_speed_mps")
__all__ = ["COLUMNS", "read_run", "pair_nmea_logs", "calibrate", "diagnose", "campaign"]


def read_run(path, follower=None, all_pairs=False, max_gap_s=0.5, topic="relative_state",
             acc_engaged_topic="acc_engaged", require_acc_engaged=False, acc_engaged_timeout_s=0.0,
             acc_setting=None):
    """A run file as the tools read it (canonical CSV, OpenACC CSV of any layout, or a bag of
    RelativeState), as one pandas.DataFrame with the canonical columns and a `segment` column (the
    reader splits a run at holes, at rows it rejects, and in a bag where the ACC's engagement
    reports say it was off: calibrate's --acc-engaged-topic, --require-acc-engaged and
    --acc-engaged-timeout; and where the ACC's setting changes: acc_setting keeps one setting's
    samples, as --acc-setting). The reader's notes go to stderr, as the tools
    print them. attrs: path, openacc_pairs (the pair(s) read), segment_names, input_account (the
    reader's format and counts, which calibrate and diagnose put in their JSON's inputs_read)."""
    import pandas

    read = _core.read_run(str(path), follower or "", all_pairs, max_gap_s, topic, acc_engaged_topic,
                          require_acc_engaged, acc_engaged_timeout_s, acc_setting or "")
    if read["log"]:
        sys.stderr.write(read["log"])
    frames = []
    for index, run in enumerate(read["runs"]):
        frame = pandas.DataFrame({name: run[name] for name in COLUMNS})
        frame.insert(0, "segment", index)
        frames.append(frame)
    frame = pandas.concat(frames, ignore_index=True)
    account = read["account"]
    frame.attrs = {"path": str(path), "openacc_pairs": list(account["openacc_pairs"]),
                   "segment_names": [run["name"] for run in read["runs"]], "input_account": account}
    return frame


def pair_nmea_logs(leader_log, follower_log, out_csv, antenna_offset_m=None, leader_antenna_to_rear_bumper_m=None,
                   follower_antenna_to_front_bumper_m=None, gap_mode=None, dropout_gap_s=None, params=None):
    """nmea_to_csv: the two receivers' NMEA logs paired by GNSS time with relative_state_node's own
    code, every paired epoch (valid or not, with its reason) written to out_csv, which is then read
    as read_run reads it (invalid rows are split points). Settings: the node's defaults, then
    params (the node's parameter file, as nmea_to_csv --params), then these arguments. The
    antennas' place is required, here or in params: the combined offset, or the two
    antenna-to-bumper offsets [m]. attrs["pairing"]: the counts `nmea_to_csv --json` writes. The
    file's unread keys and the stream events (dropouts, time resets) go to stderr, as the tool
    prints them; logs that pair no epoch raise ValueError with the tool's message."""
    def given(value):  # None is "not given", NaN to the library; a NaN given would read as None
        if value is not None and math.isnan(value):
            raise ValueError("pair_nmea_logs: a setting is NaN; leave it out (None) to not give it")
        return float("nan") if value is None else value
    paired = _core.pair_nmea_logs(
        str(leader_log), str(follower_log), str(out_csv), "" if params is None else str(params), given(antenna_offset_m),
        given(leader_antenna_to_rear_bumper_m), given(follower_antenna_to_front_bumper_m), gap_mode or "",
        given(dropout_gap_s))
    if paired["log"]:
        sys.stderr.write(paired["log"])
    run = read_run(out_csv)
    run.attrs["pairing"] = json.loads(paired["json"])
    return run


def _as_frames(runs):
    """A DataFrame, a path, or a list of either: a list of DataFrames."""
    if not isinstance(runs, (list, tuple)):
        runs = [runs]
    return [run if hasattr(run, "columns") else read_run(run) for run in runs]


def _inputs(frames, first_number=1):
    """What the JSON's inputs name: each frame's path, or its place in the call."""
    return [frame.attrs.get("path", "DataFrame %d" % (number + first_number)) for number, frame in enumerate(frames)]


def _account(frame, path):
    """What the JSON's inputs_read says of a frame: read_run's account while the frame keeps the rows
    it read; otherwise format "dataframe" without counts (they would not be this frame's)."""
    account = frame.attrs.get("input_account")
    pairs = list(frame.attrs.get("openacc_pairs") or [])
    if account and account["counts"].get("samples_used") == len(frame):
        return {**account, "path": path}
    return {"path": path, "format": "dataframe", "openacc_pairs": pairs, "counts": {}}


def _segments(frames, first_number=1):
    """The C++ side's runs (one dict per segment, "input" the frame's number) and each frame's account."""
    runs, inputs_read = [], []
    for number, (frame, path) in enumerate(zip(frames, _inputs(frames, first_number)), start=first_number):
        missing = [name for name in COLUMNS if name not in frame.columns]
        if missing:
            raise ValueError("a run needs the columns %s; missing: %s" % (", ".join(COLUMNS), ", ".join(missing)))
        names = frame.attrs.get("segment_names", [])
        groups = frame.groupby("segment", sort=True) if "segment" in frame.columns else [(0, frame)]
        for index, (_, part) in enumerate(groups):
            name = names[index] if index < len(names) else "%s #%d" % (path, index + 1)
            columns = {column: part[column].to_numpy(dtype=float) for column in COLUMNS}
            runs.append({"name": name, "path": path, "input": number, **columns})
        inputs_read.append(_account(frame, path))
    return runs, inputs_read


def calibrate(runs, split="none", starts=None, alpha=None, seed=None, stability_test=True, verdict_every_s=None,
              grid=None, second_opinion=True, bootstrap=None, bootstrap_below_s=None):
    """`calibrate` on runs (DataFrames from read_run, or paths): the dict `calibrate --json` writes.
    split "half": train on the first half of each run, test on the second (the paper).
    second_opinion=False: as --no-second-opinion, no diagnosis when the model misses the data.
    bootstrap, bootstrap_below_s: as --bootstrap and --bootstrap-below (0 replicates: none)."""
    if split not in ("none", "half"):
        raise ValueError("split must be 'none' or 'half', not %r" % (split,))
    defaults = _core.DEFAULTS["calibrate"]
    segments, inputs_read = _segments(_as_frames(runs))
    result = _core.calibrate(segments, inputs_read, split == "half", defaults["starts"] if starts is None else starts,
                             defaults["alpha"] if alpha is None else alpha, seed, stability_test,
                             verdict_every_s or 0.0, grid or 0, second_opinion,
                             defaults["bootstrap"] if bootstrap is None else bootstrap,
                             defaults["bootstrap_below_s"] if bootstrap_below_s is None else bootstrap_below_s)
    return json.loads(result["json"])


def diagnose(runs, train_fraction=None, effects=None, threads=None, seed=None, forward_selection=True,
             held_out=None, bootstrap=None, bootstrap_below_s=None):
    """`diagnose` on runs (DataFrames from read_run, or paths): the dict `diagnose --json` writes.
    held_out (runs as `runs`): as --held-out, the runs are fitted whole and these scored whole.
    bootstrap, bootstrap_below_s: as --bootstrap and --bootstrap-below (0 replicates: none)."""
    defaults = _core.DEFAULTS["diagnose"]
    frames = _as_frames(runs)
    held_out_frames = _as_frames(held_out) if held_out is not None else []
    if held_out is not None and not held_out_frames:
        raise ValueError("held_out names no run")
    segments, inputs_read = _segments(frames)
    held_out_segments, held_out_inputs_read = _segments(held_out_frames, len(frames) + 1)
    return json.loads(_core.diagnose(segments, inputs_read + held_out_inputs_read, _inputs(frames),
                                     defaults["train_fraction"] if train_fraction is None else train_fraction,
                                     list(effects or []), defaults["threads"] if threads is None else threads,
                                     defaults["seed"] if seed is None else seed, forward_selection,
                                     held_out_segments, _inputs(held_out_frames, len(frames) + 1),
                                     defaults["bootstrap"] if bootstrap is None else bootstrap,
                                     defaults["bootstrap_below_s"] if bootstrap_below_s is None else bootstrap_below_s))


def campaign(paths, starts=None, threads=None, alpha=None, seed=None, platoon_check=True, platoon_diagnosis=True,
             bootstrap=None, bootstrap_below_s=None):
    """`campaign` on OpenACC files or folders: the dict `campaign --json` writes.
    bootstrap, bootstrap_below_s: as --bootstrap and --bootstrap-below (0 replicates: none)."""
    defaults = _core.DEFAULTS["campaign"]
    if isinstance(paths, str):
        paths = [paths]
    return json.loads(_core.campaign([str(path) for path in paths],
                                     defaults["starts"] if starts is None else starts,
                                     defaults["threads"] if threads is None else threads,
                                     defaults["alpha"] if alpha is None else alpha,
                                     defaults["seed"] if seed is None else seed, platoon_check, platoon_diagnosis,
                                     defaults["bootstrap"] if bootstrap is None else bootstrap,
                                     defaults["bootstrap_below_s"] if bootstrap_below_s is None else bootstrap_below_s))
