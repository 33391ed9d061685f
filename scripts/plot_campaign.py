#!/usr/bin/python3
"""Draws the figures of a `campaign --report DIR` run.

Reads DIR/campaign.json (written by the campaign tool) and writes into DIR:
  parameters.png    k1, k2, tau_e, eta +- standard error by car and distance setting
                    (only where the data determine them),
  margins.png       the stability margin m = k1 tau_e^2 + 2 k2 tau_e - 2 +- SE, coloured by the
                    verdict of the string-stability test on held-out halves,
  platoon_dips.png  measured against predicted speed-dip depth by platoon position, one panel per
                    run with a perturbation: the base models and, with the platoon diagnosis, the
                    diagnosed ones,
  link_gain.png     with the platoon diagnosis: each car's empirical |Gamma(jw)| (Welch, band where
                    the coherence makes it informative) against its base and diagnosed model's.
report.md (written by the tool) links them and carries the data's attribution.
Usage: /usr/bin/python3 plot_campaign.py DIR
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PARAMETERS = [("k1_per_s2", "k1 [1/s^2]"), ("k2_per_s", "k2 [1/s]"), ("tau_e_s", "tau_e [s]"), ("eta_m", "eta [m]")]
SETTING_COLOURS = {"S": "tab:blue", "M": "tab:orange", "L": "tab:green"}
VERDICT_COLOURS = {"stable": "tab:green", "unstable": "tab:red", "undecided": "tab:gray"}


def number(value):
    """None (JSON null: NaN) as NaN."""
    return float("nan") if value is None else float(value)


def footer(fig, attribution):
    fig.text(0.01, 0.005, attribution, fontsize=5, wrap=True, va="bottom")


def save_placeholder(path, text):
    """A figure that says why there is nothing to draw, so that the report's link never breaks."""
    fig, ax = plt.subplots(figsize=(6, 2))
    ax.text(0.5, 0.5, text, ha="center")
    ax.axis("off")
    fig.savefig(path, dpi=120)
    plt.close(fig)


def panel_grid(count, max_columns, panel_size):
    """A grid of at least `count` panels, at most max_columns wide, each panel_size inches."""
    columns = min(max_columns, count)
    rows = math.ceil(count / columns)
    return plt.subplots(rows, columns, figsize=(panel_size[0] * columns, panel_size[1] * rows), squeeze=False)


def save_panel_grid(fig, axes, used, path, attribution):
    """Blanks the grid's panels past the first `used`, adds the attribution and saves the figure."""
    for ax in list(axes.flat)[used:]:
        ax.axis("off")
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    footer(fig, attribution)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_parameters(vehicles, path, attribution):
    labels = [f"{v['name']}/{v['setting']}" for v in vehicles]
    fig, axes = plt.subplots(len(PARAMETERS), 1, figsize=(max(8, 0.45 * len(labels) + 2), 11), sharex=True)
    for ax, (key, title) in zip(axes, PARAMETERS):
        for i, v in enumerate(vehicles):
            value = number(v["parameters"][key])
            error = number(v["standard_errors"][key])
            colour = SETTING_COLOURS.get(v["setting"], "tab:purple")
            if math.isnan(value):
                ax.plot(i, 0, "x", color="lightgray")
                continue
            ax.errorbar(i, value, yerr=0 if math.isnan(error) else error, fmt="o", color=colour, capsize=3)
        ax.set_ylabel(title)
        ax.grid(alpha=0.3)
    axes[0].set_title("Parameters +- SE by car and setting (grey x: not determined by the data)")
    handles = [plt.Line2D([], [], marker="o", ls="", color=c, label=f"setting {s}") for s, c in SETTING_COLOURS.items()]
    axes[0].legend(handles=handles, fontsize=7, loc="upper right")
    axes[-1].set_xticks(range(len(labels)))
    axes[-1].set_xticklabels(labels, rotation=70, fontsize=7)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    footer(fig, attribution)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_margins(vehicles, path, attribution):
    labels = [f"{v['name']}/{v['setting']}" for v in vehicles]
    fig, ax = plt.subplots(figsize=(max(8, 0.45 * len(labels) + 2), 5))
    finite = [x for v in vehicles for x in [number(v["margin"]["value"])] +
              [number(e) for e in v["stability_test"]["margin_interval"]] if not math.isnan(x)]
    open_bottom, open_top = (min(finite) - 1.0, max(finite) + 1.0) if finite else (-3.0, 3.0)
    for i, v in enumerate(vehicles):
        verdict = v["stability_test"]["verdict"]
        colour = VERDICT_COLOURS.get(verdict, "black")
        value = number(v["margin"]["value"])
        error = number(v["margin"]["standard_error"])
        low, high = (number(x) for x in v["stability_test"]["margin_interval"])
        if v["stability_test"].get("tested") and not (math.isnan(low) and math.isnan(high)):
            # An end at infinity (null in the JSON: the data allow every margin that way) is drawn
            # to the plot's edge with an arrow, not dropped.
            bottom, top = (open_bottom if math.isnan(low) else low), (open_top if math.isnan(high) else high)
            ax.plot([i, i], [bottom, top], color=colour, alpha=0.3, lw=6)
            for end, marker in ((low, "v"), (high, "^")):
                if math.isnan(end):
                    ax.plot(i, bottom if marker == "v" else top, marker=marker, color=colour, alpha=0.5)
        if not math.isnan(value):
            ax.errorbar(i, value, yerr=0 if math.isnan(error) else error, fmt="o", color=colour, capsize=3)
        p = number(v["stability_test"]["p_value"])
        # The p-value named by the hypothesis it tests; none when the test did not run.
        hypothesis = v["stability_test"].get("p_value_hypothesis")
        label = f"{verdict}\np (H0 {hypothesis})={p:.3f}" if hypothesis else f"{verdict}\n(not run)"
        ax.annotate(label, (i, 0), fontsize=5, ha="center", va="bottom", rotation=90,
                    color=colour, xytext=(0, 4), textcoords="offset points")
    ax.axhline(0.0, color="black", lw=0.8)
    ax.set_ylabel("margin m = k1 tau_e^2 + 2 k2 tau_e - 2")
    ax.set_title("String-stability margin +- SE (dot), interval the held-out data allow (band; an arrow: open "
                 "that way), verdict (colour)", fontsize=9)
    handles = [plt.Line2D([], [], marker="o", ls="", color=c, label=k) for k, c in VERDICT_COLOURS.items()]
    ax.legend(handles=handles, fontsize=7)
    ax.set_xticks(range(len(labels)))
    ax.set_xticklabels(labels, rotation=70, fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    footer(fig, attribution)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_dips(platoons, path, attribution):
    panels = [(p["run"], p["setting"], i, q) for p in platoons for i, q in enumerate(p["perturbations"])]
    if not panels:
        save_placeholder(path, "no perturbation in any run")
        return
    fig, axes = panel_grid(len(panels), 3, (5, 3.6))
    for ax, (run, setting, index, perturbation) in zip(axes.flat, panels):
        positions = [r["position"] for r in perturbation["positions"]]
        measured = [number(r["measured_dip_mps"]) for r in perturbation["positions"]]
        predicted = [number(r["predicted_dip_mps"]) for r in perturbation["positions"]]
        ax.plot(positions, measured, "o-", color="black", label="measured")
        ax.plot(positions, predicted, "s--", color="tab:red", label="base model (leave-one-run-out)")
        diagnosed = [number(r.get("predicted_dip_mps_diagnosed")) for r in perturbation["positions"]]
        if any(not math.isnan(d) for d in diagnosed):
            ax.plot(positions, diagnosed, "^-", color="tab:blue", label="diagnosed model (leave-one-run-out)")
        # Behind a car it could not predict, the chain restarts from that car's measured speed.
        restarts = {r.get(k) for r in perturbation["positions"]
                    for k in ("predicted_from_position", "predicted_from_position_diagnosed")} - {None, 1}
        for origin in sorted(restarts):
            ax.axvline(origin, linestyle=":", color="grey")
            ax.annotate("chain restarts\nfrom this car", (origin, 0), xycoords=("data", "axes fraction"),
                        xytext=(2, 4), textcoords="offset points", fontsize=6, color="grey")
        growth = "data: growth" if perturbation["data_show_growth"] else "data: no growth"
        ax.set_title(f"{run} ({setting}), dip {index + 1} at {perturbation['onset_s']:.0f} s; {growth}", fontsize=8)
        ax.set_xlabel("position in the platoon")
        ax.set_ylabel("speed dip [m/s]")
        ax.set_xticks(positions)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6)
    save_panel_grid(fig, axes, len(panels), path, attribution)


def plot_link_gains(links, path, attribution):
    """Empirical |Gamma| (dots where informative, band) against the base and diagnosed model, per car."""
    panels = [e for e in links if e["frequency_response"]["segments_used"] > 0]
    if not panels:
        save_placeholder(path, "no car has a stretch long enough for a spectrum")
        return
    fig, axes = panel_grid(len(panels), 4, (4.2, 3.2))
    for ax, e in zip(axes.flat, panels):
        r = e["frequency_response"]
        keep = [i for i, w in enumerate(r["frequency_rad_s"]) if w <= 2.0]
        w = [r["frequency_rad_s"][i] for i in keep]
        gain = [number(r["gain"][i]) for i in keep]
        low = [number(r["gain_lower"][i]) for i in keep]
        high = [number(r["gain_upper"][i]) for i in keep]
        informative = [bool(r["informative"][i]) for i in keep]
        ax.fill_between(w, low, high, color="gray", alpha=0.25, lw=0, label="empirical band")
        ax.plot(w, gain, color="gray", lw=0.8)
        ax.plot([x for x, f in zip(w, informative) if f], [g for g, f in zip(gain, informative) if f], "o",
                color="black", ms=2.5, label="empirical (coherence >= 0.5)")
        ax.plot(w, [number(r["model_gain_base"][i]) for i in keep], "--", color="tab:red", label="base model")
        ax.plot(w, [number(r["model_gain_diagnosed"][i]) for i in keep], "-", color="tab:blue",
                label="diagnosed: " + e["diagnosed_model"]["name"])
        ax.axhline(1.0, color="black", lw=0.6)
        ax.set_xscale("log")
        ax.set_ylim(0, 2.0)
        ax.set_title(f"{e['vehicle']}/{e['setting']} ({r['segments_used']} segments)", fontsize=8)
        ax.set_xlabel("w [rad/s]", fontsize=7)
        ax.set_ylabel("|Gamma(jw)|", fontsize=7)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=5)
    save_panel_grid(fig, axes, len(panels), path, attribution)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    folder = sys.argv[1]
    with open(os.path.join(folder, "campaign.json"), encoding="utf-8") as f:
        campaign = json.load(f)
    attribution = campaign["attribution"]
    plot_parameters(campaign["vehicles"], os.path.join(folder, "parameters.png"), attribution)
    plot_margins(campaign["vehicles"], os.path.join(folder, "margins.png"), attribution)
    plot_dips(campaign["platoons"], os.path.join(folder, "platoon_dips.png"), attribution)
    if campaign.get("links"):
        plot_link_gains(campaign["links"], os.path.join(folder, "link_gain.png"), attribution)


if __name__ == "__main__":
    main()
