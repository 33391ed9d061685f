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
import hashlib
import json
import math
import numbers
import os
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
    print them. attrs: path, openacc_pairs (the pair(s) read), segment_names, segment_pairs (each
    segment's OpenACC pair, None for other formats), input_account (the
    reader's format and counts, which calibrate and diagnose put in their JSON's inputs_read), and
    what tells whether the rows are still those read (a frame changed after reading is judged row
    by row again, with this max_gap_s)."""
    import pandas

    _check("max_gap_s", max_gap_s)
    _check("acc_engaged_timeout_s", acc_engaged_timeout_s)
    if os.path.isdir(str(path)):
        raise ValueError("%s is a folder: read_run reads one run file (campaign takes folders)" % (path,))
    read = _core.read_run(str(path), "" if follower is None else str(follower), all_pairs, max_gap_s, topic,
                          acc_engaged_topic, require_acc_engaged, acc_engaged_timeout_s, acc_setting or "")
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
                   "segment_names": [run["name"] for run in read["runs"]],
                   "segment_pairs": [run["pair"] for run in read["runs"]], "input_account": account,
                   "max_gap_s": max_gap_s, "rows_as_read": _fingerprint(frame)}
    return frame


def _check(name, value, rule=None):
    """A keyword argument checked by the tool's own rule for the same option (rule: the rule's name
    where it is not the argument's; None: not given)."""
    if value is not None:
        if isinstance(value, bool):
            raise ValueError("%s: a number, not %r" % (name, value))
        _core.check_option(name, rule or name, repr(value) if isinstance(value, float) else str(value))
    return value


def _fingerprint(frame):
    """What tells the rows read_run returned from rows changed after (cut, filtered, edited)."""
    import pandas

    columns = [name for name in ("segment",) + COLUMNS if name in frame.columns]
    rows = pandas.util.hash_pandas_object(frame[columns], index=False)  # any dtype, row by row
    return hashlib.sha1(rows.to_numpy().tobytes()).hexdigest()


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
    """A DataFrame, a path, or a list of either: a list of DataFrames. Anything else (an array, a
    dict) is a TypeError naming what was given, not a file name made of its values."""
    if not isinstance(runs, (list, tuple)):
        runs = [runs]
    for run in runs:
        if not hasattr(run, "columns") and not isinstance(run, (str, os.PathLike)):
            raise TypeError("a run is a pandas DataFrame (as read_run returns) or a path to a run file, not %s: "
                            "make a DataFrame with the columns %s" % (type(run).__name__, ", ".join(COLUMNS)))
    return [run if hasattr(run, "columns") else read_run(run) for run in runs]


def _inputs(frames, first_number=1):
    """What the JSON's inputs name: each frame's path, or its place in the call."""
    return [frame.attrs.get("path", "DataFrame %d" % (number + first_number)) for number, frame in enumerate(frames)]


def _as_read(frame):
    """Whether a frame holds exactly the rows read_run returned (no row cut, added or changed)."""
    return bool(frame.attrs.get("input_account")) and frame.attrs.get("rows_as_read") == _fingerprint(frame)


def _account(frame, path, as_read):
    """What the JSON's inputs_read says of a frame: read_run's account while the frame keeps the rows
    it read (as_read); otherwise format "dataframe" without counts (they would not be this frame's)."""
    if as_read:
        return {**frame.attrs["input_account"], "path": path}
    return {"path": path, "format": "dataframe", "openacc_pairs": _pairs_held(frame), "counts": {}}


def _pairs_held(frame):
    """The OpenACC pairs of the segments a frame still holds, in read_run's order (a frame cut to one
    car's rows names that car's pair only); every pair read where a segment is not read_run's."""
    read = list(frame.attrs.get("openacc_pairs") or [])
    of_segment = frame.attrs.get("segment_pairs") or []
    if "segment" not in frame.columns or not read:
        return read
    held = set()
    for label in frame["segment"].dropna().unique():
        index = _read_run_index(label, len(of_segment))
        if index is None or of_segment[index] is None:
            return read
        held.add(of_segment[index])
    return [pair for pair in read if pair in held]


def _column(part, name, where):
    """One column as floats; a missing value (NaN, pandas' NA) stays NaN for the readers' rules."""
    import pandas
    dates = pandas.api.types.is_datetime64_any_dtype(part[name].dtype)
    if dates or pandas.api.types.is_timedelta64_dtype(part[name].dtype):
        # Read as numbers they are nanoseconds, which the readers would call a time not in seconds.
        raise ValueError("%s: column %s holds %s: give it in seconds, e.g. (frame.%s - frame.%s.iloc[0])"
                         ".dt.total_seconds()" % (where, name, "dates and times" if dates else "durations", name, name))
    try:
        return part[name].to_numpy(dtype=float, na_value=math.nan)
    except (TypeError, ValueError) as error:
        raise ValueError("%s: column %s is not numeric: %s" % (where, name, error)) from None


def _segments(frames, first_number=1, max_gap_s=None):
    """The C++ side's runs (one dict per segment, "input" the frame's number, "check" whether its
    rows are judged again by the readers' rules, at max_gap_s or read_run's) and each frame's account."""
    runs, inputs_read = [], []
    for number, (frame, path) in enumerate(zip(frames, _inputs(frames, first_number)), start=first_number):
        missing = [name for name in COLUMNS if name not in frame.columns]
        if missing:
            raise ValueError("a run needs the columns %s; missing: %s" % (", ".join(COLUMNS), ", ".join(missing)))
        twice = sorted({name for name in frame.columns[frame.columns.duplicated()] if name in COLUMNS + ("segment",)})
        if twice:
            raise ValueError("%s: column(s) %s named twice: which one holds the data is not said" % (path, ", ".join(twice)))
        as_read = _as_read(frame)
        where = path if path.startswith("DataFrame") else "%s (DataFrame row)" % path
        for label, part in _segment_parts(frame.reset_index(drop=True), path):  # index: the row's place
            name = _segment_name(frame, path, label)
            columns = {column: _column(part, column, path) for column in COLUMNS}
            runs.append({"name": name, "path": path, "input": number, "check": not as_read, "where": where,
                         "max_gap_s": max_gap_s or frame.attrs.get("max_gap_s", 0.5), "rows": part.index.tolist(),
                         **columns})
        inputs_read.append(_account(frame, path, as_read))
    return runs, inputs_read


def _segment_parts(frame, path):
    """(label, rows) of each segment in label order; a frame without the column is one segment. A
    row without a segment belongs to none: refused rather than dropped, as groupby would."""
    if "segment" not in frame.columns:
        return [(None, frame)]
    unlabelled = int(frame["segment"].isna().sum())
    if unlabelled:
        raise ValueError("%s: %d row(s) have no segment (NaN): give every row one, or drop the column to make "
                         "the frame one segment" % (path, unlabelled))
    return list(frame.groupby("segment", sort=True, observed=True))


def _segment_name(frame, path, label):
    """A segment's name: read_run's name of that segment (by its label, which is its number there),
    else the frame's path and the label."""
    names = frame.attrs.get("segment_names", [])
    if label is None:
        return names[0] if names else "%s #1" % path
    index = _read_run_index(label, len(names))
    return names[index] if index is not None else "%s #%s" % (path, label)


def _read_run_index(label, count):
    """The segment label as read_run numbers its count segments (0, 1, ...), or None for another label."""
    if isinstance(label, numbers.Real) and not isinstance(label, bool) and float(label).is_integer() \
            and 0 <= int(label) < count:
        return int(label)
    return None


def _given(name, value, default, rule=None):
    """A keyword argument checked by the tool's rule, or the tool's default when not given."""
    return default if _check(name, value, rule) is None else value


def _log(result):
    """The notes the tool would print, to stderr, as the tool prints them."""
    if result.get("log"):
        sys.stderr.write(result["log"])


def calibrate(runs, split="none", starts=None, alpha=None, seed=None, stability_test=True, verdict_every_s=None,
              grid=None, second_opinion=True, bootstrap=None, bootstrap_below_s=None, max_gap_s=None):
    """`calibrate` on runs (DataFrames from read_run, or paths): the dict `calibrate --json` writes.
    split "half": train on the first half of each run, test on the second (the paper).
    second_opinion=False: as --no-second-opinion, no diagnosis when the model misses the data.
    bootstrap, bootstrap_below_s: as --bootstrap and --bootstrap-below (0 replicates: none).
    max_gap_s: the hole that splits a DataFrame judged row by row (your own, or one changed after
    read_run; default: read_run's max_gap_s for the frame, else 0.5 s as the tools)."""
    if split not in ("none", "half"):
        raise ValueError("split must be 'none' or 'half', not %r" % (split,))
    defaults = _core.DEFAULTS["calibrate"]
    segments, inputs_read = _segments(_as_frames(runs), max_gap_s=_check("max_gap_s", max_gap_s))
    result = _core.calibrate(segments, inputs_read, split == "half", int(_given("starts", starts, defaults["starts"])),
                             _given("alpha", alpha, defaults["alpha"]), _whole(_check("seed", seed)), stability_test,
                             _given("verdict_every_s", verdict_every_s, 0.0), int(_given("grid", grid, 0)),
                             second_opinion, int(_given("bootstrap", bootstrap, defaults["bootstrap"])),
                             _given("bootstrap_below_s", bootstrap_below_s, defaults["bootstrap_below_s"]))
    _log(result)
    return json.loads(result["json"])


def _whole(value):
    """A whole number checked by its rule (5.0 included) as the int the C++ side takes."""
    return None if value is None else int(value)


def diagnose(runs, train_fraction=None, effects=None, threads=None, seed=None, forward_selection=True,
             held_out=None, bootstrap=None, bootstrap_below_s=None, max_gap_s=None):
    """`diagnose` on runs (DataFrames from read_run, or paths): the dict `diagnose --json` writes.
    held_out (runs as `runs`): as --held-out, the runs are fitted whole and these scored whole.
    bootstrap, bootstrap_below_s: as --bootstrap and --bootstrap-below (0 replicates: none).
    max_gap_s: as calibrate's."""
    defaults = _core.DEFAULTS["diagnose"]
    if isinstance(effects, str):
        effects = [effects]
    frames = _as_frames(runs)
    held_out_frames = _as_frames(held_out) if held_out is not None else []
    if held_out is not None and not held_out_frames:
        raise ValueError("held_out names no run")
    max_gap_s = _check("max_gap_s", max_gap_s)
    segments, inputs_read = _segments(frames, max_gap_s=max_gap_s)
    held_out_segments, held_out_inputs_read = _segments(held_out_frames, len(frames) + 1, max_gap_s)
    result = _core.diagnose(segments, inputs_read + held_out_inputs_read, _inputs(frames),
                            _given("train_fraction", train_fraction, defaults["train_fraction"]),
                            list(effects or []), int(_given("threads", threads, defaults["threads"])),
                            int(_given("seed", seed, defaults["seed"], rule="seed32")), forward_selection,
                            held_out_segments, _inputs(held_out_frames, len(frames) + 1),
                            int(_given("bootstrap", bootstrap, defaults["bootstrap"])),
                            _given("bootstrap_below_s", bootstrap_below_s, defaults["bootstrap_below_s"]))
    _log(result)
    return json.loads(result["json"])


def campaign(paths, starts=None, threads=None, alpha=None, seed=None, platoon_check=True, platoon_diagnosis=True,
             bootstrap=None, bootstrap_below_s=None):
    """`campaign` on OpenACC files or folders: the dict `campaign --json` writes.
    bootstrap, bootstrap_below_s: as --bootstrap and --bootstrap-below (0 replicates: none)."""
    defaults = _core.DEFAULTS["campaign"]
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    paths = [os.fspath(path) for path in paths]
    if not paths:
        raise ValueError("campaign: no file or folder given")
    result = _core.campaign(paths, int(_given("starts", starts, defaults["starts"])),
                            int(_given("threads", threads, defaults["threads"])),
                            _given("alpha", alpha, defaults["alpha"]), int(_given("seed", seed, defaults["seed"])),
                            platoon_check, platoon_diagnosis, int(_given("bootstrap", bootstrap, defaults["bootstrap"])),
                            _given("bootstrap_below_s", bootstrap_below_s, defaults["bootstrap_below_s"]))
    _log(result)
    return json.loads(result["json"])
