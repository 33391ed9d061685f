#!/usr/bin/python3
"""Draws the figures of a `diagnose --report DIR` run and writes DIR/report.md.

Reads what the diagnose tool wrote into DIR (diagnosis.json, residuals.csv, spectrum.csv,
gain.csv, train_fit.csv) and writes PNG figures plus a Markdown report that reads on its own.
Usage: /usr/bin/python3 plot_diagnosis.py DIR
"""
import csv
import json
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_headline import headline, inputs_read_lines, verdict_words  # noqa: E402

OPENACC_ATTRIBUTION = (
    "Data: JRC OpenACC database, Casale campaign (Makridis, Mattas, Anesiadou, Ciuffo, "
    "Transportation Research Part C 125 (2021) 103047), (c) European Union, licensed CC BY 4.0. "
    "Changes: split into fitting and held-out halves; simulated with calibrated models; residuals, "
    "spectra and statistics derived.")


def stability_test_lines(test):
    """The verdict of the chosen model, decided on held-out data (diagnosis/augmented_stability_verdict.h)."""
    if not test:
        return ["The string-stability test was not run.", ""]

    def side(name, fit):
        if not fit:
            return f"- best {name} model: none found in the search box"
        params = ", ".join(f"{k} {fmt(v)}" for k, v in fit["parameters"].items())
        effect = ", ".join(f"{k} {fmt(v)}" for k, v in fit["effect_parameters"].items())
        return (f"- best {name} model: {params}{'; ' + effect if effect else ''}; stability index "
                f"{fmt(fit['stability_index'])}, peak {fmt(fit['peak_gain_db'])} dB; speed RMSE train "
                f"{fmt(fit['train_rmse_speed'])}, held out {fmt(fit['test_rmse_speed'])} m/s")

    return [f"**Verdict for the `{test['effect']}` model: {test['verdict'].upper()}** "
            f"(p = {fmt(test['p_value'])}, alpha {test['alpha']}).", "",
            side("string-stable", test.get("best_stable")), side("string-unstable", test.get("best_unstable")), "",
            f"Why: {test['reason']}.", ""]


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def by_run(rows):
    runs = defaultdict(list)
    for row in rows:
        runs[row["run"]].append(row)
    return runs


def significant(value, digits=2):
    """A standard error to its significant digits: 0.0042, not 0.00."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "n/a"
    return f"{value:.{digits}g}"


def fmt(value, digits=3):
    if isinstance(value, str):  # "inf": an infinite gain or lambda2, which JSON cannot hold as a number
        return value
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "n/a"
    return f"{value:.{digits}g}" if abs(value) < 1e-3 and value != 0 else f"{value:.{digits}f}"


def plot_time_series(report_dir, residuals, diagnosis):
    runs = by_run(residuals)
    names = list(runs)
    fig, axes = plt.subplots(len(names), 2, figsize=(13, 2.8 * len(names)), squeeze=False)
    effect = diagnosis["dominant_effect"]
    worst = diagnosis["where"]["segments"][:5]
    for i, name in enumerate(names):
        rows = runs[name]
        t = [float(r["time_s"]) for r in rows]
        t0 = t[0]
        t = [x - t0 for x in t]
        for col, (measured, base, eff, unit) in enumerate(
                [("speed_mps", "base_speed_mps", "effect_speed_mps", "speed [m/s]"),
                 ("gap_m", "base_gap_m", "effect_gap_m", "gap [m]")]):
            ax = axes[i][col]
            ax.plot(t, [float(r[measured]) for r in rows], "k", lw=1.0, label="measured")
            ax.plot(t, [float(r[base]) for r in rows], "C0", lw=1.0, label="base model")
            if effect != "none":
                ax.plot(t, [float(r[eff]) for r in rows], "C3--", lw=1.0, label=f"with {effect}")
            for seg in worst:
                if seg["run"] == name:
                    ax.axvspan(seg["start_s"] - t0, seg["end_s"] - t0, color="orange", alpha=0.25)
            ax.set_ylabel(unit)
            ax.set_title(f"{name} (held out; orange: worst segments)", fontsize=9)
            ax.grid(alpha=0.3)
        axes[i][0].legend(fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("time from start of held-out part [s]")
    fig.tight_layout()
    fig.savefig(os.path.join(report_dir, "held_out_time_series.png"), dpi=110)
    plt.close(fig)


def plot_groups(report_dir, diagnosis):
    where = diagnosis["where"]
    fig, axes = plt.subplots(1, 2, figsize=(13, 4))
    for ax, key, title in [(axes[0], "regimes", "driving regime"), (axes[1], "speed_bands", "follower speed band")]:
        groups = where[key]
        x = range(len(groups))
        ax.bar([i - 0.2 for i in x], [g["share_of_time"] for g in groups], 0.4, label="share of time")
        ax.bar([i + 0.2 for i in x], [g["share_of_squared_speed_error"] for g in groups], 0.4,
               label="share of squared speed error")
        ax.set_xticks(list(x))
        ax.set_xticklabels([g["name"].replace("_", "\n") for g in groups], fontsize=7)
        ax.set_title(f"Held-out base-model residual by {title}")
        ax.grid(alpha=0.3, axis="y")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(report_dir, "residual_by_regime.png"), dpi=110)
    plt.close(fig)


def plot_spectrum(report_dir, spectrum, diagnosis):
    fig, ax = plt.subplots(figsize=(8, 4))
    effect = diagnosis["dominant_effect"]
    for i, (name, rows) in enumerate(by_run(spectrum).items()):
        f = [float(r["frequency_hz"]) for r in rows]
        ax.loglog(f, [max(float(r["power_before"]), 1e-12) for r in rows], color=f"C{i}", lw=0.7,
                  label=f"{name} base")
        if effect != "none":
            ax.loglog(f, [max(float(r["power_after"]), 1e-12) for r in rows], color=f"C{i}", lw=0.7, ls="--",
                      label=f"{name} with {effect}")
    for band in diagnosis["where"]["frequency_bands"]:
        if band["lower_hz"] > 0:
            ax.axvline(band["lower_hz"], color="grey", lw=0.5)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("periodogram of speed residual [(m/s)^2]")
    ax.set_title("Spectrum of the held-out speed residual (grey: band edges)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(report_dir, "residual_spectrum.png"), dpi=110)
    plt.close(fig)


def plot_effects(report_dir, diagnosis):
    effects = diagnosis["effects"]
    names = [e["name"] for e in effects]
    fig, ax = plt.subplots(figsize=(9, 4))
    # The bounds are of the MSE difference itself (resampled), not a share of the full-sample base
    # MSE: divided by it they reached past 100 %, a reduction larger than the error it reduces.
    means = [e["improvement"]["mean_mse_reduction"] or 0 for e in effects]
    lows = [e["improvement"]["lower_bound"] or 0 for e in effects]
    highs = [e["improvement"]["upper_bound"] or 0 for e in effects]
    colors = ["C2" if e["significant"] else "C7" for e in effects]
    ax.bar(range(len(names)), means, color=colors)
    ax.errorbar(range(len(names)), means, yerr=[[m - lo for m, lo in zip(means, lows)],
                                                [hi - m for m, hi in zip(means, highs)]], fmt="none", ecolor="k")
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xticks(range(len(names)))
    ax.set_xticklabels([n.replace("_", "\n") for n in names], fontsize=8)
    ax.set_ylabel("held-out speed MSE reduction [m^2/s^2]")
    ax.set_title("What each effect buys on held-out data (green: significant; bars: bootstrap bounds)")
    ax.grid(alpha=0.3, axis="y")
    fig.tight_layout()
    fig.savefig(os.path.join(report_dir, "effect_improvements.png"), dpi=110)
    plt.close(fig)


def plot_gain(report_dir, gain, diagnosis):
    fig, ax = plt.subplots(figsize=(8, 4))
    w = [float(r["frequency_rad_s"]) for r in gain]
    ax.semilogx(w, [float(r["base_db"]) for r in gain], "k", lw=1.5, label="base")
    for e in diagnosis["effects"]:
        key = e["name"] + "_db"
        style = "-" if e["name"] == diagnosis["dominant_effect"] else ":"
        ax.semilogx(w, [float(r[key]) for r in gain], style, lw=1.0, label=e["name"])
    ax.axhline(0, color="grey", lw=0.8)
    ax.set_xlabel("frequency [rad/s]")
    ax.set_ylabel("|Gamma(jw)| [dB]")
    ax.set_title("Speed-to-speed gain of the fitted models (> 0 dB: string unstable)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(report_dir, "string_stability_gain.png"), dpi=110)
    plt.close(fig)


def parameter_text(effect):
    parts = []
    for name, value in effect["parameters"].items():
        se = effect["standard_errors"].get(name)
        # No standard error: the fit's speeds do not move with it (a limit that never binds), or it diverged.
        parts.append(f"{name} = {fmt(value, 4)}" + (f" ± {significant(se)}" if se is not None
                                                    else " (± n/a: the fitted speeds do not move with it)"))
    return "; ".join(parts)


def combination_lines(d):
    """The forward selection's chain: one row per step, the model with every effect added so far."""
    chain = d.get("selected_effects")
    if chain is None:
        return []  # a diagnosis.json from before effects were tried in combination
    lines = ["## Effects in combination", ""]
    forward = d.get("forward_selection", {})
    if not chain:
        lines += [f"No effect was added (forward selection: {forward.get('stop_reason', 'not run')}).", ""]
        return lines
    lines.append("Starting from the dominant effect, every remaining effect is fitted on top of the current model "
                 "and compared with it by the same rule (the family-wise level over the remaining effects, the "
                 "practical threshold relative to the base model's held-out MSE); the best significant one is added.")
    lines += ["", "| step | effect added | held-out speed RMSE [m/s] | held-out gap RMSE [m] | "
              "MSE reduction vs previous step [% of base] (lower bound [m²/s²]) | string stability (test, p) | "
              "its size, by the training data | parameters (± std. error) |", "|---|---|---|---|---|---|---|---|"]
    base = d["baseline"]
    lines.append(f"| 0 | base | {fmt(base['test_rmse_speed'])} | {fmt(base['test_rmse_gap'])} | - | "
                 f"{point_estimate_stability(base)} | - | {parameter_text(base)} |")
    for i, step in enumerate(chain, 1):
        imp = step["improvement"]
        test = step.get("stability_test")
        verdict = f"{test['verdict']}, p = {fmt(test['p_value'])}" if test else "not tested"
        values = dict(step["parameters"], **step["effect_parameters"])
        params = parameter_text({"parameters": values, "standard_errors": step["standard_errors"]})
        lines.append(f"| {i} | {step['effect']} | {fmt(step['test_rmse_speed'])} | {fmt(step['test_rmse_gap'])} | "
                     f"{imp['relative'] * 100:.1f} ({fmt(imp['lower_bound'], 3)}) | "
                     f"{point_estimate_stability(step)} ({verdict}) | {added_size_text(step)} | {params} |")
    lines += ["", f"Stopped: {forward.get('stop_reason', '')}.", ""]
    return lines


def final_model_lines(d):
    """The model the diagnosis ends with: each parameter with its standard error and, on short training
    data, the refitting bootstrap's 95 % interval (which holds where value +- 1.96 se runs short)."""
    final = d.get("final_model")
    if not final:
        return []
    effects = " + ".join(final["effects"]) or "base model"
    bootstrap = final.get("refit_bootstrap") or {}
    quantities = bootstrap.get("quantities") or {}
    lines = [f"## The final model ({effects})", "",
             "| parameter | value | standard error |" + (" 95 % interval, refitting bootstrap |" if quantities else ""),
             "|---|---|---|" + ("---|" if quantities else "")]
    for name, value in final["parameters"].items():
        row = f"| {name} | {fmt(value, 4)} | {significant(final['standard_errors'].get(name))} |"
        if quantities:
            entry = quantities.get(name) or {}
            interval = entry.get("interval_95")
            row += (f" [{fmt(interval[0], 4)}, {fmt(interval[1], 4)}] |" if interval
                    else f" none: {entry.get('note', '')} |")
        lines.append(row)
    if quantities:
        lines += ["", f"Refitting bootstrap: {bootstrap['refitted']} of {bootstrap['replicates']} drives the model "
                  f"could have given refitted as the diagnosis fitted it (residual blocks of "
                  f"{fmt(bootstrap['block_length_s'], 3)} s)." + (f" Caution: {bootstrap['caution']}." if bootstrap.get("caution") else "")]
    elif bootstrap.get("note"):
        lines += ["", f"Refitting bootstrap not made: {bootstrap['note']}."]
    return lines + [""]


def added_size_text(step):
    """Whether the training data pin the added effect's size (z from none at the determined rule's threshold)."""
    size = step.get("added_effect_size")
    if size is None:
        return "-"  # a diagnosis.json from before the size was judged
    if size["z"] is None:
        return "not judged"
    bound = ", at a bound" if size["at_bound"] else ""
    return f"{'determined' if size['determined'] else '**not determined**'} ({size['z']:.1f} SE from none{bound})"


def point_estimate_stability(model):
    """The point estimate's string stability in words; null (parameters not finite) is not "unstable"."""
    stable = model["stability"]["string_stable"]
    return "undetermined" if stable is None else "stable" if stable else "unstable"


def adequacy_text(adequacy):
    """model_adequacy in words: ADEQUATE, NOT ADEQUATE (reasons) or not assessed (why)."""
    if adequacy is None or adequacy.get("adequate") is None:
        return "not assessed" + (f" ({'; '.join(adequacy['reasons'])})" if adequacy else "")
    return "ADEQUATE" if adequacy["adequate"] else "NOT ADEQUATE (" + "; ".join(adequacy["reasons"]) + ")"


def perturbation_window_lines(windows):
    """Each effect inside the leaders' perturbations, beside the whole-run table above it."""
    if not windows:
        return []
    lines = ["## Inside the leader's perturbations (held out)", "",
             f"{windows['perturbations']} perturbation(s) of the leaders in the held-out parts; base model's "
             f"window speed RMSE {fmt(windows['base_window_rmse_speed_mps'])} m/s. Rule: {windows['rule']}.", ""]
    if windows["reason"]:
        return lines + [f"Not judged: {windows['reason']}.", ""]
    lines += ["| model | window speed RMSE [m/s] | window MSE change [%] | p (over the effects) | p (alone) | named |",
              "|---|---|---|---|---|---|"]
    for e in windows["effects"]:
        change = -100 * e["relative_improvement"] if e["relative_improvement"] is not None else None
        lines.append(f"| {e['effect']} | {fmt(e['window_rmse_speed_mps'])} | "
                     f"{'-' if change is None else f'{change:+.1f}'} | {fmt(e.get('family_p_value'))} | "
                     f"{fmt(e['p_value'])} | {'yes' if e['significant'] else 'no'} |")
    return lines + ["", f"Named on the perturbation windows: `{windows['named']}`.", ""]


def write_report(report_dir, d):
    base = d["baseline"]
    dominant = d["dominant_effect"]
    chosen = next((e for e in d["effects"] if e["name"] == dominant), None)
    verdict = d.get("verdict") or {}
    lines = headline("Sim-to-real gap diagnosis",
                     verdict_words(verdict) + (f", of the {verdict['model']}" if verdict.get("model") else ""),
                     d["final_model"].get("model_adequacy"), ", ".join(f"`{p}`" for p in d.get("inputs", [])))
    lines.append("Inputs: " + ", ".join(f"`{p}`" for p in d.get("inputs", [])) + ". Each run is fitted on its "
                 "first part and scored on the rest (held-out).")
    lines += ["", "## Verdict", ""]
    if d.get("steady_training"):
        lines += [f"**The parts fitted on are too steady to fit** ({d['steady_training']}): the fits below leave "
                  "open what these data do not pin, and their peak gains are no model's stability.", ""]
    if dominant == "none":
        lines.append("**No candidate effect improves the held-out fit significantly.** The residual below is "
                     "not explained by any single effect of the catalogue.")
    else:
        plausible = ", ".join(d["plausible_effects"])
        lines.append(f"**Dominant effect: `{dominant}`.** Effects the data cannot tell apart from it: {plausible}.")
        lines.append("")
        lines.append(f"Held-out speed RMSE {fmt(base['test_rmse_speed'])} → {fmt(chosen['test_rmse_speed'])} m/s, "
                     f"gap RMSE {fmt(base['test_rmse_gap'])} → {fmt(chosen['test_rmse_gap'])} m. "
                     f"Parameters: {parameter_text(chosen)}.")
        verdict = "changes" if chosen["stability_verdict_changes"] else "does not change"
        lines.append("")
        lines.append(f"String stability: base peak gain {fmt(base['stability']['peak_gain_db'])} dB "
                     f"({point_estimate_stability(base)}), with the effect "
                     f"{fmt(chosen['stability']['peak_gain_db'])} dB "
                     f"({point_estimate_stability(chosen)}): the point estimate's stability {verdict}. "
                     f"({chosen['stability']['note']}.)")
    verdict = d.get("verdict")
    if verdict:
        lines += ["", f"Model adequacy of the base model: {adequacy_text(base.get('model_adequacy'))}.",
                  f"Model adequacy of the final model: {adequacy_text(d['final_model'].get('model_adequacy'))}.", "",
                  f"**The verdict** (string-stability test of the {verdict['model']}): "
                  f"{verdict['verdict'] or 'not tested'}, p (H0: stable) = {fmt(verdict['p_value_stable_rejected'])}, "
                  f"p (H0: unstable) = {fmt(verdict['p_value_unstable_rejected'])}. Why this model: {verdict['why']}."]
    lines += ["", "Selection rule: " + d["selection"]["rule"], "", "## Models", ""]
    lines.append("| model | train speed RMSE [m/s] | held-out speed RMSE [m/s] | held-out gap RMSE [m] | "
                 "MSE reduction [%] | its bounds [m^2/s^2] | significant | peak gain [dB] | "
                 "parameters (± std. error) |")
    lines.append("|---|---|---|---|---|---|---|---|---|")
    lines.append(f"| base | {fmt(base['train_rmse_speed'])} | {fmt(base['test_rmse_speed'])} | "
                 f"{fmt(base['test_rmse_gap'])} | - | - | - | {fmt(base['stability']['peak_gain_db'])} | "
                 f"{parameter_text(base)} |")
    for e in d["effects"]:
        imp = e["improvement"]
        lines.append(f"| {e['name']} | {fmt(e['train_rmse_speed'])} | {fmt(e['test_rmse_speed'])} | "
                     f"{fmt(e['test_rmse_gap'])} | {imp['relative'] * 100:.1f} | "
                     f"{fmt(imp['lower_bound'], 3)} to {fmt(imp['upper_bound'], 3)} | "
                     f"{'yes' if e['significant'] else 'no'} | {fmt(e['stability']['peak_gain_db'])} | "
                     f"{parameter_text(e)} |")
    lines += ["", "![improvements](effect_improvements.png)", ""]
    lines += perturbation_window_lines(d.get("perturbation_windows"))
    lines += determined_lines(d)
    lines += combination_lines(d)
    lines += final_model_lines(d)
    lines += ["## Where the residual lies (base model, held out)", ""]
    for key, title in [("regimes", "Driving regime"), ("speed_bands", "Speed band")]:
        lines.append(f"| {title} | share of time | share of squared speed error | speed RMSE before → after [m/s] | "
                     "gap RMSE before → after [m] |")
        lines.append("|---|---|---|---|---|")
        for g in d["where"][key]:
            lines.append(f"| {g['name']} | {g['share_of_time'] * 100:.1f}% | "
                         f"{g['share_of_squared_speed_error'] * 100:.1f}% | {fmt(g['rmse_speed_before'])} → "
                         f"{fmt(g['rmse_speed_after'])} | {fmt(g['rmse_gap_before'])} → {fmt(g['rmse_gap_after'])} |")
        lines.append("")
    lines.append("![regimes](residual_by_regime.png)")
    lines += ["", "| Frequency band | share of squared speed error, base | with the dominant effect |", "|---|---|---|"]
    for b in d["where"]["frequency_bands"]:
        lines.append(f"| {b['name']} | {b['share_of_squared_speed_error_before'] * 100:.1f}% | "
                     f"{b['share_of_squared_speed_error_after'] * 100:.1f}% |")
    lines += ["", "![spectrum](residual_spectrum.png)", "", "Worst 10 s segments:", "",
              "| run | start [s] | end [s] | share of squared speed error | speed RMSE before → after [m/s] | "
              "main regime |", "|---|---|---|---|---|---|"]
    for s in d["where"]["segments"]:
        lines.append(f"| {s['run']} | {s['start_s']:.1f} | {s['end_s']:.1f} | "
                     f"{s['share_of_squared_speed_error'] * 100:.1f}% | {fmt(s['rmse_speed_before'])} → "
                     f"{fmt(s['rmse_speed_after'])} | {s['main_regime']} |")
    lines += ["", "![time series](held_out_time_series.png)", "", "## String stability", ""]
    lines += stability_test_lines(d.get("stability_test"))
    lines += ["![gain](string_stability_gain.png)", ""]
    lines += inputs_read_lines(d.get("inputs_read"))
    if d["notes"]:
        lines += ["## Data not used", ""] + [f"- {n}" for n in d["notes"]] + [""]
    # Read as OpenACC, or named after it (a bag or canonical CSV made from the database, as the
    # package's own are): its attribution travels with what is made from it.
    if d.get("openacc_pairs") or any("openacc" in p.lower() or "casale" in p.lower() for p in d.get("inputs", [])):
        lines += ["## Attribution", "", OPENACC_ATTRIBUTION, ""]
    with open(os.path.join(report_dir, "report.md"), "w") as f:
        f.write("\n".join(lines))


def determined_lines(d):
    """What the training data pin away from none, named by the held-out rule or not, and the effects
    they cannot see at all (a lag whose fit sits at 0, asked at a typical size)."""
    lines = ["## What the training data determine", ""]
    for e in d.get("determined_effects", []):
        lines.append(f"- `{e['effect']}` {fmt(e['value'])} ± {fmt(e['standard_error'])} "
                     f"({e['z']:.1f} standard errors from none)")
    if not d.get("determined_effects"):
        lines.append("- no effect's size is pinned away from none")
    for e in d.get("unmeasured_effects", []):
        seen = "would be determined" if e["would_be_determined"] else "would not be seen"
        lines.append(f"- `{e['effect']}`: its fit sits at none, where it carries no information; held at "
                     f"{fmt(e['held_value'])} these data pin it to ± {fmt(e['standard_error'])} "
                     f"({fmt(e['z'], 1)} standard errors from none): an effect that size {seen}")
    return lines + [""]


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: plot_diagnosis.py DIR")
    report_dir = sys.argv[1]
    with open(os.path.join(report_dir, "diagnosis.json")) as f:
        diagnosis = json.load(f)
    plot_time_series(report_dir, read_csv(os.path.join(report_dir, "residuals.csv")), diagnosis)
    plot_groups(report_dir, diagnosis)
    plot_spectrum(report_dir, read_csv(os.path.join(report_dir, "spectrum.csv")), diagnosis)
    plot_effects(report_dir, diagnosis)
    plot_gain(report_dir, read_csv(os.path.join(report_dir, "gain.csv")), diagnosis)
    write_report(report_dir, diagnosis)


if __name__ == "__main__":
    main()
