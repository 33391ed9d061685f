#!/usr/bin/python3
"""Draws the figures of a `calibrate --report DIR` run and writes DIR/report.md.

Reads what calibrate wrote into DIR (calibration.json, fit_traces.csv: every run as measured and
as the fitted model simulates it from its own start) and draws, per run, the measured and the
simulated speed and gap over time with their residuals (fit_<n>.png), then a Markdown report that
starts with the headline every report of the package has (report_headline.py).
Usage: /usr/bin/python3 plot_calibration.py DIR
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_headline import adequacy_words, fmt, headline, inputs_read_lines, verdict_words  # noqa: E402

PARTS = {"fit": ("fitted", "tab:orange"), "train": ("fitted (train)", "tab:orange"),
         "held_out": ("held out", "tab:red")}


def read_traces(path):
    """{run: [(part, columns)]} in file order."""
    runs = {}
    with open(path) as stream:
        for row in csv.DictReader(stream):
            parts = runs.setdefault(row["run"], [])
            if not parts or parts[-1][0] != row["part"]:
                parts.append((row["part"], {key: [] for key in row if key not in ("run", "part")}))
            for key, columns in parts[-1][1].items():
                columns.append(float(row[key]))
    return runs


def plot_run(report_dir, number, name, parts):
    figure, axes = plt.subplots(3, 1, figsize=(10, 8), sharex=True)
    for part, columns in parts:
        label, colour = PARTS.get(part, (part, "tab:orange"))
        t = columns["time_s"]
        axes[0].plot(t, columns["measured_speed_mps"], color="black", linewidth=0.8)
        axes[0].plot(t, columns["simulated_speed_mps"], color=colour, linewidth=0.9, label=label)
        axes[1].plot(t, columns["measured_gap_m"], color="black", linewidth=0.8)
        axes[1].plot(t, columns["simulated_gap_m"], color=colour, linewidth=0.9)
        axes[2].plot(t, columns["speed_residual_mps"], color=colour, linewidth=0.7)
    axes[0].plot([], [], color="black", label="measured")
    axes[0].set_ylabel("follower speed [m/s]")
    axes[1].set_ylabel("space gap [m]")
    axes[2].set_ylabel("speed residual [m/s]\n(measured - model)")
    axes[2].axhline(0.0, color="grey", linewidth=0.5)
    axes[2].set_xlabel("time [s]")
    axes[0].legend(loc="best", fontsize=8)
    axes[0].set_title(name + ": measured and simulated from each part's own start")
    figure.tight_layout()
    file = f"fit_{number}.png"
    figure.savefig(os.path.join(report_dir, file), dpi=90)
    plt.close(figure)
    return file


def rms(values):
    finite = [v for v in values if math.isfinite(v)]
    return math.sqrt(sum(v * v for v in finite) / len(finite)) if finite else float("nan")


QUANTITY_OF = {"k1_per_s2": "k1", "k2_per_s": "k2", "tau_e_s": "tau_e", "eta_m": "eta"}


def interval_words(entry):
    """An interval_95 of the JSON ([low, high] or null) in words."""
    interval = (entry or {}).get("interval_95")
    return f"[{fmt(interval[0], 4)}, {fmt(interval[1], 4)}]" if interval else "none"


def parameter_lines(fit):
    """The parameters with their standard errors and 95 % intervals; on short data also the refitting
    bootstrap's, which hold where value +- t se runs short (docs/RESULTS.md)."""
    p, se = fit["parameters"], fit.get("standard_errors") or {}
    quantities = (fit.get("identifiable_quantities") or {}).get("quantities") or {}
    bootstrap = (fit.get("refit_bootstrap") or {}).get("quantities")
    header = "| parameter | value | standard error | 95 % interval |" + (" 95 % interval, refitting bootstrap |"
                                                                          if bootstrap else "")
    lines = [header, "|---|---|---|---|" + ("---|" if bootstrap else "")]
    for key, name in QUANTITY_OF.items():
        row = f"| {key} | {fmt(p.get(key), 4)} | {fmt(se.get(key), 2)} | {interval_words(quantities.get(name))} |"
        if bootstrap:
            row += f" {interval_words(bootstrap.get(name))} |"
        lines.append(row)
    caution = (fit.get("refit_bootstrap") or {}).get("caution")
    if caution:
        lines += ["", f"Refitting bootstrap: {caution}."]
    return lines


def run_lines(runs):
    lines = ["| run | part | samples | speed RMSE [m/s] | gap RMSE [m] |", "|---|---|---|---|---|"]
    for name, parts in runs.items():
        for part, columns in parts:
            lines.append(f"| {name} | {PARTS.get(part, (part,))[0]} | {len(columns['time_s'])} | "
                         f"{fmt(rms(columns['speed_residual_mps']))} | {fmt(rms(columns['gap_residual_m']))} |")
    return lines


def data_words(runs):
    samples = sum(len(columns["time_s"]) for parts in runs.values() for _, columns in parts)
    seconds = sum(columns["time_s"][-1] - columns["time_s"][0] for parts in runs.values() for _, columns in parts
                  if columns["time_s"])
    return f"{len(runs)} run(s), {samples} samples, {seconds / 60:.1f} min"


def write_report(report_dir, fit, runs, figures):
    stability = fit.get("stability") or {}
    lines = headline("ACC calibration", verdict_words(fit.get("stability_test")), fit.get("model_adequacy"),
                     data_words(runs))
    lines += ["The model `dv/dt = k1 (s - eta - tau_e v) + k2 (v_leader - v)` fitted by the speed RMSE of its "
              "Euler simulation, as the paper does. The verdict is the string-stability test's on held-out "
              "halves (not the point estimate's lambda2); the model line says whether the fit describes the data "
              "at all: read it before the verdict.", "", "## Parameters", ""]
    lines += parameter_lines(fit)
    lines += ["", f"lambda2 of the point estimate: {fmt(stability.get('lambda2'))}; peak gain "
              f"{fmt(stability.get('peak_gain_db'))} dB at {fmt(stability.get('peak_frequency_rad_s'))} rad/s.", "",
              "## Runs", ""]
    lines += run_lines(runs)
    for (name, _), figure in zip(runs.items(), figures):
        lines += ["", f"### {name}", "", f"![{name}]({figure})"]
    lines += [""] + inputs_read_lines(fit.get("inputs_read"))
    if fit.get("openacc_pairs"):
        lines += ["", "## Attribution", "", "Data: JRC OpenACC database (Makridis, Mattas, Anesiadou, Ciuffo, "
                  "Transportation Research Part C 125 (2021) 103047), (c) European Union, CC BY 4.0. Changes: "
                  "calibrated with the ACC model; simulated speeds, gaps and residuals derived."]
    with open(os.path.join(report_dir, "report.md"), "w") as stream:
        stream.write("\n".join(lines) + "\n")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_calibration.py DIR")
    report_dir = sys.argv[1]
    with open(os.path.join(report_dir, "calibration.json")) as stream:
        fit = json.load(stream)
    if not fit.get("fitted"):
        # Valid data without a fit (steady speed, too short): the reason, and what the data decide.
        lines = headline("ACC calibration", "not tested", fit.get("model_adequacy"), "no fit: " + fit.get("reason", ""))
        lines += ["What the data do decide is in `calibration.json` (`data`).", ""]
        with open(os.path.join(report_dir, "report.md"), "w") as stream:
            stream.write("\n".join(lines))
        return
    runs = read_traces(os.path.join(report_dir, "fit_traces.csv"))
    figures = [plot_run(report_dir, number + 1, name, parts) for number, (name, parts) in enumerate(runs.items())]
    write_report(report_dir, fit, runs, figures)


if __name__ == "__main__":
    main()
