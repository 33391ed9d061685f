"""The Python API (python/acc_identification) against the command-line tools: every function's
dict must be the tool's --json on the same bundled file, to the last digit (solve times aside),
and bad input must raise the tools' messages. Run by `make test` (cmake/python.cmake) with the
workspace sourced; ACC_DATA_CASALE_DIR, ACC_DATA_TOYOTA_DIR and ACC_DATA_ZALAZONE_DIR (the dynamic
runs) name the unpacked bundled data."""
import json
import math
import os
import re
import subprocess
import threading
import time

import pandas
import pytest

import acc_identification as acc

CASALE = os.environ.get("ACC_DATA_CASALE_DIR", "")
TOYOTA = os.environ.get("ACC_DATA_TOYOTA_DIR", "")
ZALAZONE = os.environ.get("ACC_DATA_ZALAZONE_DIR", "")
TIMING_KEYS = {"solve_time_s", "wall_time_s", "threads"}


def without_timing(value):
    """The JSON with its wall-clock times (and thread counts) taken out: they differ between runs."""
    if isinstance(value, dict):
        return {key: without_timing(item) for key, item in value.items() if key not in TIMING_KEYS}
    if isinstance(value, list):
        return [without_timing(item) for item in value]
    return value


def tool_json(tmp_path, tool, *arguments):
    out = tmp_path / (tool + ".json")
    completed = subprocess.run(["rosrun", "acc_identification", tool, *arguments, "--json", str(out)],
                               capture_output=True, text=True)
    assert out.exists(), completed.stderr
    with open(out) as stream:
        return json.load(stream), completed.returncode


def test_read_run_gives_the_canonical_columns_and_what_was_read():
    run = acc.read_run(os.path.join(CASALE, "part5.csv"))
    assert list(run.columns) == ["segment"] + list(acc.COLUMNS)
    assert len(run) == 1051
    assert run.attrs["openacc_pairs"] == ["Hyundai behind Rexton, positions 2/1"]
    assert run.attrs["segment_names"] == ["part5 Hyundai"]
    assert run["follower_speed_mps"].between(27.0, 40.0).all()
    account = run.attrs["input_account"]
    assert account["format"] == "openacc"
    assert account["counts"]["samples_used"] == len(run)
    assert account["counts"]["data_rows"] == (len(run) + account["counts"]["rejected_rows"] +
                                              account["counts"]["acc_off_rows"] + account["counts"]["single_sample_rows"])


def test_a_frame_changed_after_reading_keeps_its_pairs_but_not_the_readers_counts():
    path = os.path.join(CASALE, "part5.csv")
    run = acc.read_run(path)
    whole = acc.diagnose(run, threads=2)["inputs_read"]
    assert whole[0]["format"] == "openacc" and whole[0]["counts"]["samples_used"] == len(run)
    cut = acc.diagnose(run.iloc[:800].copy(), threads=2)["inputs_read"]
    assert cut == [{"path": path, "format": "dataframe", "openacc_pairs": ["Hyundai behind Rexton, positions 2/1"],
                    "counts": {}}]


def test_a_frame_cut_to_some_pairs_names_those_pairs_only():
    path = os.path.join(ZALAZONE, "dynamic_part26.csv")
    every = acc.read_run(path, all_pairs=True)
    pairs = every.attrs["openacc_pairs"]
    assert len(pairs) > 2 and len(every.attrs["segment_pairs"]) == every["segment"].nunique()
    second = pairs[1]
    kept = [label for label, pair in enumerate(every.attrs["segment_pairs"]) if pair == second]
    one_car = every[every["segment"].isin(kept)].copy()
    read = acc.calibrate(one_car)["inputs_read"]
    assert read == [{"path": path, "format": "dataframe", "openacc_pairs": [second], "counts": {}}]
    relabelled = one_car.assign(segment=one_car["segment"] + 1000)  # labels read_run never gave: every pair read
    assert acc.calibrate(relabelled)["inputs_read"][0]["openacc_pairs"] == pairs


def test_calibrate_equals_the_tool_to_the_last_digit(tmp_path):
    path = os.path.join(CASALE, "part5.csv")
    expected, status = tool_json(tmp_path, "calibrate", "--quiet", "--split", "half", path)
    assert status == 0
    got = acc.calibrate([acc.read_run(path)], split="half")
    assert without_timing(got) == without_timing(expected)
    assert got["parameters"]["k1_per_s2"] == expected["parameters"]["k1_per_s2"]  # exact, not approximate


def test_calibrate_takes_paths_and_says_when_valid_data_cannot_be_fitted(tmp_path):
    steady = tmp_path / "steady.csv"
    steady.write_text("time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n" +
                      "".join("%.1f,30,20,20\n" % (0.1 * k) for k in range(300)))
    expected, status = tool_json(tmp_path, "calibrate", "--quiet", str(steady))
    assert status == 3
    got = acc.calibrate(str(steady))
    assert got["fitted"] is False
    assert without_timing(got) == without_timing(expected)


def test_diagnose_equals_the_tool(tmp_path):
    path = os.path.join(CASALE, "part5.csv")
    expected, status = tool_json(tmp_path, "diagnose", "--threads", "2", path)
    assert status == 0
    got = acc.diagnose([acc.read_run(path)], threads=2)
    assert without_timing(got) == without_timing(expected)


def test_a_diagnosis_report_of_an_openacc_file_carries_its_attribution_whatever_its_name(tmp_path):
    renamed = tmp_path / "run.csv"
    renamed.write_bytes(open(os.path.join(CASALE, "part5.csv"), "rb").read())
    completed = subprocess.run(["rosrun", "acc_identification", "diagnose", "--threads", "2", "--report",
                                str(tmp_path / "report"), "run.csv"], cwd=tmp_path, capture_output=True, text=True)
    assert completed.returncode == 0, completed.stderr
    report = (tmp_path / "report" / "report.md").read_text()
    assert "## Attribution" in report and "CC BY 4.0" in report
    assert "| `run.csv` | openacc | Hyundai behind Rexton, positions 2/1 | 1051 | 1051 | 1 | none |" in report


def test_diagnose_with_runs_kept_aside_equals_the_tool(tmp_path):
    fitted, kept_aside = os.path.join(CASALE, "part5.csv"), os.path.join(CASALE, "part4.csv")
    expected, status = tool_json(tmp_path, "diagnose", "--threads", "2", fitted, "--held-out", kept_aside)
    assert status == 0
    got = acc.diagnose(fitted, threads=2, held_out=[acc.read_run(kept_aside)])
    assert without_timing(got) == without_timing(expected)
    assert got["held_out"] == "whole runs kept aside" and got["held_out_inputs"] == [kept_aside]
    assert [run.get("test") for run in got["runs"]] == [None, "part4 Hyundai[held out]"]


def test_campaign_equals_the_tool(tmp_path):
    expected, status = tool_json(tmp_path, "campaign", "--quiet", "--threads", "2", "--no-platoon-diagnosis", TOYOTA)
    assert status == 0
    got = acc.campaign([TOYOTA], threads=2, platoon_diagnosis=False)
    assert without_timing(got) == without_timing(expected)


def nmea_logs(tmp_path, name, *arguments):
    """Casale part 5 as the two receivers would have logged it (openacc_to_nmea)."""
    leader, follower = tmp_path / (name + "_leader.nmea"), tmp_path / (name + "_follower.nmea")
    subprocess.run(["rosrun", "acc_identification", "openacc_to_nmea", *arguments, os.path.join(CASALE, "part5.csv"),
                    str(leader), str(follower)], check=True, capture_output=True)
    return leader, follower


def test_pair_nmea_logs_writes_and_reads_what_the_tool_writes(tmp_path):
    leader, follower = nmea_logs(tmp_path, "part5")
    tool_csv = tmp_path / "tool.csv"
    expected, status = tool_json(tmp_path, "nmea_to_csv", "--antenna-offset-m", "5.60", str(leader), str(follower),
                                 str(tool_csv))
    assert status == 0
    run = acc.pair_nmea_logs(leader, follower, tmp_path / "api.csv", antenna_offset_m=5.60)
    assert (tmp_path / "api.csv").read_bytes() == tool_csv.read_bytes()
    assert run.attrs["pairing"] == expected
    assert expected["pairing"]["exact_pairs"] == expected["states"] > 1000
    assert run.attrs["input_account"]["counts"]["samples_used"] == len(run) == expected["valid_states"]
    calibrated, status = tool_json(tmp_path, "calibrate", "--quiet", str(tmp_path / "api.csv"))
    assert status == 0
    assert without_timing(acc.calibrate(run)) == without_timing(calibrated)
    # relative_state_node's own parameter file places the Casale antennas: the same pairs.
    config = os.path.join(os.path.dirname(__file__), "..", "..", "..", "config", "relative_state.yaml")
    acc.pair_nmea_logs(leader, follower, tmp_path / "params.csv", params=config)
    assert (tmp_path / "params.csv").read_bytes() == tool_csv.read_bytes()
    # The two offsets place the same antennas: the same gaps.
    split = acc.pair_nmea_logs(leader, follower, tmp_path / "split.csv", leader_antenna_to_rear_bumper_m=2.0,
                               follower_antenna_to_front_bumper_m=3.6)
    assert split["space_gap_m"].sub(run["space_gap_m"]).abs().max() <= 0.0011  # written to the millimetre


def test_pair_nmea_logs_refuses_to_guess_and_says_when_nothing_pairs(tmp_path):
    leader, follower = nmea_logs(tmp_path, "part5")
    out = tmp_path / "pairs.csv"
    with pytest.raises(ValueError, match="say where the antennas are.*the arguments: antenna_offset_m=M"):
        acc.pair_nmea_logs(leader, follower, out)
    with pytest.raises(ValueError, match="not both"):
        acc.pair_nmea_logs(leader, follower, out, antenna_offset_m=5.6, leader_antenna_to_rear_bumper_m=2.0)
    with pytest.raises(ValueError, match="go together"):
        acc.pair_nmea_logs(leader, follower, out, leader_antenna_to_rear_bumper_m=2.0)
    with pytest.raises(ValueError, match="'chord' is neither"):
        acc.pair_nmea_logs(leader, follower, out, antenna_offset_m=5.6, gap_mode="chord")
    with pytest.raises(ValueError, match="a setting is NaN"):  # NaN would be taken for "not given"
        acc.pair_nmea_logs(leader, follower, out, antenna_offset_m=5.6, dropout_gap_s=float("nan"))
    with pytest.raises(ValueError, match="not between -1000 and 1000"):
        acc.pair_nmea_logs(leader, follower, out, antenna_offset_m=5600.0)
    with pytest.raises(RuntimeError, match="nope.nmea"):
        acc.pair_nmea_logs(tmp_path / "nope.nmea", follower, out, antenna_offset_m=5.6)
    later_leader, _ = nmea_logs(tmp_path, "an_hour_later", "--time-shift-s", "3600")
    with pytest.raises(ValueError, match="no follower epoch could be paired"):
        acc.pair_nmea_logs(later_leader, follower, out, antenna_offset_m=5.6)


def test_bad_input_raises_the_tools_messages():
    with pytest.raises(Exception, match="nope.csv"):
        acc.read_run("/nonexistent/nope.csv")
    run = acc.read_run(os.path.join(CASALE, "part5.csv"))
    with pytest.raises(ValueError, match="missing: space_gap_m"):
        acc.calibrate(run.drop(columns=["space_gap_m"]))
    with pytest.raises(ValueError, match="unknown effect 'teleportation'"):
        acc.diagnose(run, effects=["teleportation"])
    with pytest.raises(ValueError, match="held_out names no run"):
        acc.diagnose(run, held_out=[])
    with pytest.raises(ValueError, match="split"):
        acc.calibrate(run, split="thirds")
    # What is not a frame or a path is a TypeError naming it, not a file name made of its values.
    for given in (run.to_numpy(), run.to_dict()):
        with pytest.raises(TypeError, match="a run is a pandas DataFrame .* not (ndarray|dict)"):
            acc.calibrate(given)
    # Times as dates, or as durations, would be read as nanoseconds: said, with the conversion.
    dated = run.assign(time_s=pandas.to_datetime(run.time_s, unit="s"))
    with pytest.raises(ValueError, match="column time_s holds dates and times: give it in seconds"):
        acc.calibrate(dated)
    with pytest.raises(ValueError, match="column time_s holds durations"):
        acc.calibrate(run.assign(time_s=pandas.to_timedelta(run.time_s, unit="s")))


def test_the_same_recording_given_twice_is_refused_as_the_tools_refuse_it():
    path = os.path.join(CASALE, "part5.csv")
    run = acc.read_run(path)
    with pytest.raises(ValueError, match="repeats " + re.escape(path) + "'s run part5 Hyundai .* give each recording"):
        acc.calibrate([run, acc.read_run(path)])
    # An excerpt kept aside from the run it is cut from is not held out.
    with pytest.raises(ValueError, match=re.escape(path) + r": its run part5 Hyundai \(from t = 56277.0 s\) repeats"):
        acc.diagnose(run, held_out=[run.iloc[200:900]])
    # A copy whose speeds were changed is another drive as far as the data can tell.
    other = run.copy()
    other["follower_speed_mps"] += 1e-9
    assert acc.calibrate([run, other], stability_test=False, second_opinion=False)["parameters"]


def test_the_solves_release_the_gil():
    # While another thread calibrates (400 starts: about half a second here), this one must keep
    # running: had the solve kept the GIL, this thread would stand still for all of it.
    run = acc.read_run(os.path.join(CASALE, "part6.csv"))
    done = []
    worker = threading.Thread(target=lambda: done.append(acc.calibrate(run, split="half", starts=400,
                                                                       second_opinion=False)))
    started = time.perf_counter()
    worker.start()
    ticks = [started]
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    duration = time.perf_counter() - started
    longest_stall = max(later - earlier for earlier, later in zip(ticks, ticks[1:]))
    assert done and done[0]["fitted"] is True
    assert duration > 0.1, "the solve was too short to tell"
    assert longest_stall < 0.5 * duration, (longest_stall, duration)


def test_a_frame_of_your_own_is_judged_row_by_row_as_the_tool_judges_the_same_file(tmp_path, capsys):
    # A NaN, a gap glitch, a negative speed and a hole of 10 s: the tool rejects those rows and
    # splits the run there; the same rows as a DataFrame must give the same runs and numbers.
    run = acc.read_run(os.path.join(CASALE, "part5.csv"))[list(acc.COLUMNS)]
    run.loc[100, "leader_speed_mps"] = math.nan
    run.loc[300, "space_gap_m"] = 1500.0
    run.loc[500, "follower_speed_mps"] = -30.0
    run = run.drop(index=range(700, 800))
    path = tmp_path / "glitches.csv"
    run.to_csv(path, index=False, float_format="%.17g")
    expected, _ = tool_json(tmp_path, "calibrate", "--quiet", "--no-stability-test", "--no-second-opinion", str(path))
    capsys.readouterr()
    got = acc.calibrate(pandas.read_csv(path, float_precision="round_trip"), stability_test=False,
                        second_opinion=False)
    assert len(got["runs"]) == len(expected["runs"]) == 5
    assert got["parameters"] == expected["parameters"]
    err = capsys.readouterr().err
    assert "DataFrame 1:100: leader speed is not a finite number" in err
    assert "space_gap_m 1500 outside" in err and "hole of" in err


def test_frames_put_together_are_split_where_their_times_part(capsys):
    four, five = (acc.read_run(os.path.join(CASALE, name)) for name in ("part4.csv", "part5.csv"))
    apart = acc.calibrate([four, five], stability_test=False, second_opinion=False)
    together = acc.calibrate(pandas.concat([four, five], ignore_index=True), stability_test=False,
                             second_opinion=False)
    assert together["parameters"] == apart["parameters"]
    assert "hole of" in capsys.readouterr().err


def test_segments_keep_their_names_and_a_row_without_one_is_refused():
    run = acc.read_run(os.path.join(CASALE, "part5.csv"))
    two = run.copy()
    two.loc[600:, "segment"] = 1
    two.attrs["segment_names"] = ["first half", "second half"]
    kept = two[two["segment"] == 1]
    assert [r["name"] for r in acc.calibrate(kept, stability_test=False, second_opinion=False)["runs"]] == \
        ["second half"]
    # Segments labelled by text are segments too, named by their label.
    texts = two.assign(segment=two["segment"].map({0: "a", 1: "b"}))
    assert [r["name"] for r in acc.calibrate(texts, stability_test=False, second_opinion=False)["runs"]] == \
        [texts.attrs["path"] + " #a", texts.attrs["path"] + " #b"]
    unlabelled = two.copy()
    unlabelled["segment"] = unlabelled["segment"].astype(float)
    unlabelled.loc[10:20, "segment"] = math.nan
    with pytest.raises(ValueError, match="11 row\\(s\\) have no segment"):
        acc.calibrate(unlabelled)


def test_options_are_checked_by_the_tools_rules():
    run = acc.read_run(os.path.join(CASALE, "part5.csv"))
    refused = [(acc.calibrate, {"alpha": 1.5}, "alpha: must be above 0 and below 1, not 1.5"),
               (acc.calibrate, {"alpha": math.nan}, "alpha: not a finite number"),
               (acc.calibrate, {"starts": 0}, "starts: must be a whole number from 1 to 100000, not 0"),
               (acc.calibrate, {"grid": 1}, "grid: must be a whole number from 2 to 1000"),
               (acc.calibrate, {"bootstrap": 5}, "bootstrap: must be 0 \\(none\\) or a whole number"),
               (acc.calibrate, {"verdict_every_s": 0.001}, "verdict_every_s: must be 1 or more"),
               (acc.calibrate, {"seed": -1}, "seed: must be a whole number 0 or more"),
               (acc.calibrate, {"bootstrap_below_s": -1.0}, "bootstrap_below_s: must be 0 or more"),
               (acc.calibrate, {"max_gap_s": 0}, "max_gap_s: must be above 0"),
               (acc.diagnose, {"seed": 2 ** 32}, "seed: must be a whole number from 0 to 4294967295"),
               (acc.diagnose, {"train_fraction": 0.99}, "train_fraction: must be from 0.05 to 0.95"),
               (acc.diagnose, {"threads": -1}, "threads: must be a whole number 0 or more"),
               (acc.campaign, {"alpha": math.nan}, "alpha: not a finite number")]
    for function, arguments, message in refused:
        with pytest.raises(ValueError, match=message):
            function(run if function is not acc.campaign else [CASALE], **arguments)
    with pytest.raises(ValueError, match="follower and all_pairs exclude each other"):
        acc.read_run(os.path.join(CASALE, "part5.csv"), follower="Hyundai", all_pairs=True)
    with pytest.raises(ValueError, match="acc_engaged_timeout_s: must be 0 or more"):
        acc.read_run(os.path.join(CASALE, "part5.csv"), acc_engaged_timeout_s=-1)
    with pytest.raises(ValueError, match="is a folder"):
        acc.read_run(CASALE)
    with pytest.raises(ValueError, match="no file or folder given"):
        acc.campaign([])
    # Within the option's range, but days of work on this run: refused before the fit, as the tool refuses it.
    with pytest.raises(ValueError, match="--grid 1000 on 1051 training samples would simulate .* give --grid 575 or less"):
        acc.calibrate(run, grid=1000)
    # A whole number written as a float is the number, as the tools read "5.0".
    assert acc.calibrate(run, seed=7.0, starts=5.0, stability_test=False, second_opinion=False)["fitted"]


def test_pair_nmea_logs_never_writes_over_its_inputs(tmp_path):
    leader, follower = str(tmp_path / "L.nmea"), str(tmp_path / "F.nmea")
    subprocess.run(["rosrun", "acc_identification", "openacc_to_nmea", os.path.join(CASALE, "part5.csv"), leader,
                    follower], check=True, capture_output=True)
    before = open(leader).read()
    with pytest.raises(ValueError, match="overwrite"):
        acc.pair_nmea_logs(leader, follower, leader, antenna_offset_m=5.6)
    assert open(leader).read() == before


def test_the_tools_notes_reach_stderr(tmp_path, capsys):
    run = acc.read_run(os.path.join(CASALE, "part5.csv"))
    short = pandas.concat([run, run.iloc[:3].assign(segment=1, time_s=run["time_s"].iloc[-1] + [10.0, 10.1, 10.2])],
                          ignore_index=True)
    capsys.readouterr()
    acc.calibrate(short, split="half", stability_test=False, second_opinion=False)
    assert "too few to split" in capsys.readouterr().err
    folder = tmp_path / "runs"
    folder.mkdir()
    (folder / "notes.csv").write_text("not,an,openacc,file\n")
    os.symlink(os.path.join(TOYOTA, "dynamic_part5.csv"), folder / "dynamic_part5.csv")
    acc.campaign(folder, platoon_check=False)
    assert "notes.csv: not an OpenACC file" in capsys.readouterr().err
