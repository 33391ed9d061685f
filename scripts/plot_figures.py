#!/usr/bin/python3
"""Plots the figures of Gunter et al. from the CSV and JSON files written by the `platoon` tool.

usage: plot_figures.py DATA_DIR OUT_DIR [FIGURE ...]
DATA_DIR holds <figure>.csv and <figure>.json as scripts/reproduce_figures.sh names them
(fig1, fig2, fig3, fig5, fig6, fig7, fig8); each figure whose files are there is drawn to
OUT_DIR/<figure>.png. The plots show the numbers the tool measured; they compute nothing new.
Run with Debian's python3 (python3-matplotlib, python3-numpy).
"""
import csv
import io
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402  (python3-pil, a dependency of python3-matplotlib)

OPENACC_CREDIT = ("Data: JRC OpenACC, Casale campaign (Makridis et al. 2021), CC BY 4.0, (c) European Union; "
                  "read as published (Time, IVS1, Speed2, Speed1); steady-sample selection, fits and simulations added.")
PAPER = {"min": {"band": 0.358, "peak_db": 1.25, "peak_w": 0.204},
         "max": {"band": 0.118, "peak_db": 0.386, "peak_w": 0.062}}


def read_table(path):
    """CSV -> (header, dict of column name -> list of strings)."""
    with open(path, newline="") as handle:
        reader = csv.reader(handle)
        header = next(reader)
        columns = {name: [] for name in header}
        for row in reader:
            for name, value in zip(header, row):
                columns[name].append(value)
    return header, columns


def floats(values):
    return np.array([float(v) for v in values])


def by_setting(columns):
    """Row indices of each setting, in order of appearance."""
    groups = {}
    for index, name in enumerate(columns["setting"]):
        groups.setdefault(name, []).append(index)
    return groups


def load(data_dir, name):
    csv_path = os.path.join(data_dir, name + ".csv")
    json_path = os.path.join(data_dir, name + ".json")
    if not (os.path.exists(csv_path) and os.path.exists(json_path)):
        return None
    with open(json_path) as handle:
        summary = json.load(handle)
    return read_table(csv_path), summary


def save(fig, out_dir, name):
    path = os.path.join(out_dir, name + ".png")
    buffer = io.BytesIO()
    fig.savefig(buffer, dpi=100)
    # An adaptive 256-colour palette keeps the line plots readable at a fraction of the size.
    buffer.seek(0)
    Image.open(buffer).convert("RGB").quantize(colors=256).save(path, optimize=True)
    plt.close(fig)
    print("wrote %s (%d kB)" % (path, os.path.getsize(path) // 1024))


def platoon_speeds(columns, rows, stride=1):
    """time [s] and speeds [vehicle][sample] of one setting's platoon, every stride-th sample."""
    rows = rows[::stride]
    time = floats([columns["time_s"][i] for i in rows])
    vehicles = sorted((name for name in columns if name.startswith("v") and name.endswith("_mps")),
                      key=lambda name: int(name[1:-4]))
    return time, [floats([columns[name][i] for i in rows]) for name in vehicles]


def draw_platoon(ax, time, speeds, title, followers=None):
    followers = len(speeds) - 1 if followers is None else followers
    colours = plt.cm.viridis(np.linspace(0.0, 0.9, max(followers, 1)))
    for i in range(1, followers + 1):
        ax.plot(time, speeds[i], color=colours[i - 1], lw=0.8)
    ax.plot(time, speeds[0], color="red", lw=1.4, label="lead")
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("speed [m/s]")
    ax.grid(alpha=0.3)


def fig1(data_dir, out_dir):
    loaded = load(data_dir, "fig1")
    if not loaded:
        return
    (_, c), summary = loaded
    tau, k1, k2, lam = (floats(c[n]) for n in ("tau_e_s", "k1_per_s2", "k2_per_s", "lambda2"))
    taus = sorted(set(tau))
    fig, axes = plt.subplots(1, len(taus), figsize=(2.6 * len(taus) + 1.0, 3.4), sharey=True, constrained_layout=True)
    norm = matplotlib.colors.LogNorm(vmin=1e-3, vmax=max(1e3, lam.max()))
    for ax, t in zip(np.atleast_1d(axes), taus):
        sel = tau == t
        a, b, l = k1[sel], k2[sel], lam[sel]
        n1, n2 = len(set(a)), len(set(b))
        grid = l.reshape(n1, n2).T  # rows k2, columns k1
        extent = (a.min(), a.max(), b.min(), b.max())
        unstable = np.ma.masked_where(grid <= 0.0, grid)
        image = ax.imshow(unstable, origin="lower", extent=extent, aspect="auto", cmap="magma_r", norm=norm)
        stable = np.ma.masked_where(grid > 0.0, np.ones_like(grid))
        ax.imshow(stable, origin="lower", extent=extent, aspect="auto", cmap="Greys", vmin=0, vmax=2.5)
        k1_line = np.linspace(a.min(), a.max(), 200)
        ax.plot(k1_line, (2.0 - k1_line * t * t) / (2.0 * t), "k--", lw=1)
        ax.set_ylim(b.min(), b.max())
        ax.set_title("tau_e = %g s: %.0f %% stable" % (t, 100 * summary["stable_fraction"][min(
            summary["stable_fraction"], key=lambda key: abs(float(key) - t))]), fontsize=9)
        ax.set_xlabel("k1 [1/s^2]")
    np.atleast_1d(axes)[0].set_ylabel("k2 [1/s]")
    fig.colorbar(image, ax=axes, label="lambda2 (unstable, > 0)", shrink=0.85)
    fig.suptitle("Fig. 1: lambda2 over (k1, k2); grey = string stable (lambda2 < 0); dashed: k1 tau_e^2 + 2 k2 tau_e = 2",
                 fontsize=10)
    save(fig, out_dir, "fig1_lambda2_map")


def fig2(data_dir, out_dir):
    loaded = load(data_dir, "fig2")
    if not loaded:
        return
    (_, c), summary = loaded
    groups = by_setting(c)
    fig, axes = plt.subplots(1, len(groups), figsize=(10, 3.6), sharey=True)
    for ax, entry, (name, rows) in zip(np.atleast_1d(axes), summary["settings"], groups.items()):
        p = entry["parameters"]
        time, speeds = platoon_speeds(c, rows, stride=2)
        keep = time <= 150.0
        time, speeds = time[keep], [v[keep] for v in speeds]
        draw_platoon(ax, time, speeds, "%s: tau_e = %g s (%s)\nlast follower: min %.2f, max %.2f m/s" % (
            name, p["tau_e_s"], "stable" if p["string_stable"] else "unstable",
            entry["response"]["per_vehicle"][-1]["minimum_speed_mps"],
            entry["response"]["per_vehicle"][-1]["maximum_speed_mps"]))
    fig.suptitle("Fig. 2: %d ACC followers (k1 = k2 = 0.5, eta = 8) behind a lead speed step down and up" %
                 summary["vehicles"], fontsize=10)
    fig.tight_layout()
    save(fig, out_dir, "fig2_step")


def fig3(data_dir, out_dir):
    loaded = load(data_dir, "fig3")
    if not loaded:
        return
    (_, c), summary = loaded
    fig, axes = plt.subplots(2, 1, figsize=(10, 5.6), sharex=True)
    for entry, (name, rows) in zip(summary["settings"], by_setting(c).items()):
        time = floats([c["time_s"][i] for i in rows])
        time = time - time[0]
        if name == list(by_setting(c))[0]:
            axes[0].plot(time, floats([c["measured_speed_mps"][i] for i in rows]), "k", lw=1, label="measured follower")
            axes[0].plot(time, floats([c["leader_speed_mps"][i] for i in rows]), color="red", lw=0.6, alpha=0.6,
                         label="measured leader")
            axes[1].plot(time, floats([c["measured_gap_m"][i] for i in rows]), "k", lw=1, label="measured")
            axes[0].axvline(entry["split_time_s"] - float(c["time_s"][rows[0]]), color="grey", ls=":")
            axes[1].axvline(entry["split_time_s"] - float(c["time_s"][rows[0]]), color="grey", ls=":")
        label = "%s (train/test RMSE %.2f/%.2f m/s, %.2f/%.2f m)" % (
            name, entry["train_speed_rmse_mps"], entry["test_speed_rmse_mps"], entry["train_gap_rmse_m"],
            entry["test_gap_rmse_m"])
        axes[0].plot(time, floats([c["simulated_speed_mps"][i] for i in rows]), lw=1, label=label)
        axes[1].plot(time, floats([c["simulated_gap_m"][i] for i in rows]), lw=1, label=name)
    axes[0].set_ylabel("speed [m/s]")
    axes[1].set_ylabel("space gap [m]")
    axes[1].set_xlabel("time since start of run [s] (dotted: end of training part)")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower left")
    fig.suptitle("Figs. 3/4: measured and simulated follower, %s" % os.path.basename(summary["run"]), fontsize=10)
    fig.text(0.01, 0.005, OPENACC_CREDIT, fontsize=6)
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    save(fig, out_dir, "fig3_timeseries")


def fig5(data_dir, out_dir):
    loaded = load(data_dir, "fig5")
    if not loaded:
        return
    (_, c), summary = loaded
    speed, gap, steady = floats(c["follower_speed_mps"]), floats(c["space_gap_m"]), floats(c["steady"]) > 0
    fig, ax = plt.subplots(figsize=(8, 5))
    ax.plot(speed[~steady][::5], gap[~steady][::5], ".", color="0.75", ms=2, label="all samples (every 5th)")
    ax.plot(speed[steady], gap[steady], ".", color="tab:blue", ms=2, label="steady following")
    v = np.linspace(0.0, max(speed.max(), 1.0) * 1.05, 50)
    for entry in summary["settings"]:
        p = entry["parameters"]
        ax.plot(v, p["eta_m"] + p["tau_e_s"] * v, lw=1.5,
                label="%s: %.2f m + %.3f s * v" % (p["name"], p["eta_m"], p["tau_e_s"]))
    pooled = summary.get("pooled", {})
    if "fit" in pooled:
        fit = pooled["fit"]
        ax.plot(v, fit["eta_m"] + fit["tau_e_s"] * v, "k--", lw=1.5,
                label="least squares through all %d steady samples: %.2f m + %.3f s * v" % (
                    pooled["steady_samples"], fit["eta_m"], fit["tau_e_s"]))
    ax.set_xlabel("follower speed [m/s]")
    ax.set_ylabel("space gap [m]")
    ax.set_ylim(0, max(gap.max(), 10) * 1.1)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title("Fig. 5: space gap against speed with equilibrium lines eta + tau_e v", fontsize=10)
    fig.text(0.01, 0.005, OPENACC_CREDIT, fontsize=6)
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    save(fig, out_dir, "fig5_equilibrium")


def fig6(data_dir, out_dir):
    loaded = load(data_dir, "fig6")
    if not loaded:
        return
    (_, c), summary = loaded
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for entry, (name, rows) in zip(summary["settings"], by_setting(c).items()):
        p = entry["parameters"]
        w = floats([c["frequency_rad_s"][i] for i in rows])
        line, = ax.semilogx(w, floats([c["gain_db"][i] for i in rows]), lw=1.5,
                            label="%s: > 0 dB below %.4f rad/s, peak %.3f dB at %.4f rad/s" % (
                                name, p["amplified_band_upper_rad_s"], float(p["peak_gain_db"]), p["peak_frequency_rad_s"]))
        ax.semilogx(w, floats([c["euler_gain_db"][i] for i in rows]), ls=":", color=line.get_color(), lw=1)
        ax.plot(p["peak_frequency_rad_s"], float(p["peak_gain_db"]), "o", color=line.get_color())  # "inf": not drawn
        if name in PAPER:
            ax.plot(PAPER[name]["peak_w"], PAPER[name]["peak_db"], "x", color=line.get_color(), ms=8, mew=2,
                    label="%s, paper: peak %.3g dB at %.3g rad/s, band %.3g rad/s" % (
                        name, PAPER[name]["peak_db"], PAPER[name]["peak_w"], PAPER[name]["band"]))
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_ylim(-20, 3)
    ax.set_xlabel("frequency [rad/s]")
    ax.set_ylabel("|Gamma(jw)| [dB]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="lower left")
    ax.set_title("Fig. 6: speed-to-speed gain (dotted: Euler recursion at h = %g s)" % summary["time_step_s"],
                 fontsize=10)
    fig.tight_layout()
    save(fig, out_dir, "fig6_bode")


def fig7(data_dir, out_dir):
    loaded = load(data_dir, "fig7")
    if not loaded:
        return
    (_, c), summary = loaded
    groups = by_setting(c)
    fig, axes = plt.subplots(1, len(groups) + 1, figsize=(11, 3.5))
    for ax, entry, (name, rows) in zip(axes, summary["settings"], groups.items()):
        time, speeds = platoon_speeds(c, rows, stride=5)
        keep = time <= 200.0
        draw_platoon(ax, time[keep], [s[keep] for s in speeds],
                     "%s: follower %d / lead = %.3f" % (name, summary["vehicles"], entry["last_follower_to_lead"]))
    ax = axes[-1]
    for entry in summary["settings"]:
        amplitude = entry["amplitude_mps"]
        index = np.arange(len(amplitude))
        line, = ax.semilogy(index, amplitude, "o", ms=4, label="%s simulated" % entry["parameters"]["name"])
        ax.semilogy(index, entry["model_gain"] ** index, "-", color=line.get_color(), lw=1,
                    label="|Gamma|^i = %.4f^i" % entry["model_gain"])
    ax.set_xlabel("vehicle (0 = lead)")
    ax.set_ylabel("speed amplitude [m/s]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    ax.set_title("amplitude over the last 5 periods", fontsize=9)
    fig.suptitle("Fig. 7: %d followers behind a 1 m/s lead sinusoid at %.3f rad/s" % (
        summary["vehicles"], summary["frequency_rad_s"]), fontsize=10)
    fig.tight_layout()
    save(fig, out_dir, "fig7_sinusoid")


def fig8(data_dir, out_dir):
    loaded = load(data_dir, "fig8")
    if not loaded:
        return
    (_, c), summary = loaded
    groups = by_setting(c)
    short = summary["short_platoon"]
    count = len(groups)
    fig = plt.figure(figsize=(5.5 * max(count, 2), 7))
    grid = fig.add_gridspec(2, 2 * count)
    top = [fig.add_subplot(grid[0, 2 * i:2 * i + 2]) for i in range(count)]
    long_ax = fig.add_subplot(grid[1, :count])
    ax = fig.add_subplot(grid[1, count:])
    for panel, entry, (name, rows) in zip(top, summary["settings"], groups.items()):
        time, speeds = platoon_speeds(c, rows, stride=10)
        keep = time <= summary["profile_duration_s"] + 3.0 * short
        d = entry["short"]["per_vehicle"]
        draw_platoon(panel, time[keep], [s[keep] for s in speeds], "%s, %d followers: drop below cruise %.1f -> %.1f m/s" % (
            name, short, d[0]["drop_below_reference_mps"], d[-1]["drop_below_reference_mps"]), followers=short)
    # The long platoon of the setting that decays first is the interesting one (the paper's "max").
    long_entry = next((e for e in summary["settings"] if e["long"]["growth_by_drop"]["decays_at_first"]),
                      summary["settings"][-1])
    long_name = long_entry["parameters"]["name"]
    time, speeds = platoon_speeds(c, groups[long_name], stride=20)
    every_other = [speeds[0]] + speeds[2::2]  # every 2nd follower keeps the file small
    draw_platoon(long_ax, time, every_other, "%s, %d followers (every 2nd drawn)" % (long_name, summary["vehicles"]))
    lo = min(min(s) for s in speeds)
    long_ax.set_ylim(max(lo, -5.0) - 1.0, None)
    for entry in summary["settings"]:
        per_vehicle = entry["long"]["per_vehicle"]
        index = np.arange(len(per_vehicle))
        drop = [d["drop_below_reference_mps"] for d in per_vehicle]
        p2p = [d["peak_to_peak_mps"] for d in per_vehicle]
        line, = ax.semilogy(index, drop, "-", lw=1.5, label="%s: drop below cruise" % entry["parameters"]["name"])
        ax.semilogy(index, p2p, ":", color=line.get_color(), lw=1.5, label="%s: peak-to-peak" % entry["parameters"]["name"])
        onset = entry["long"]["growth_by_drop"]
        if onset["decays_at_first"] and onset["growth_starts_at"] is not None:
            i = onset["growth_starts_at"]
            ax.plot(i, drop[i], "v", color=line.get_color(), ms=8, label="smallest drop: follower %d" % i)
        if onset["exceeds_lead_at"] is not None and onset["exceeds_lead_at"] > 1:
            i = onset["exceeds_lead_at"]
            ax.plot(i, drop[i], "^", color=line.get_color(), ms=8, label="exceeds the lead's drop: follower %d" % i)
        negative = entry["long"]["first_negative_speed_vehicle"]
        if negative is not None:
            ax.axvline(negative, color=line.get_color(), ls="--", lw=0.8,
                       label="%s: speeds < 0 from follower %d" % (entry["parameters"]["name"], negative))
    ax.axvline(short, color="grey", lw=0.8)
    ax.set_ylim(1.0, 1e3)
    ax.set_xlabel("vehicle (0 = lead)")
    ax.set_ylabel("speed disturbance [m/s]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=6.5, loc="upper left")
    ax.set_title("disturbance along the platoon (grey line: %d followers)" % short, fontsize=9)
    fig.suptitle("Fig. 8: platoons behind lead profile I rebuilt from its description (recorded test I not available)",
                 fontsize=10)
    fig.tight_layout()
    save(fig, out_dir, "fig8_profile_i")


FIGURES = {"fig1": fig1, "fig2": fig2, "fig3": fig3, "fig5": fig5, "fig6": fig6, "fig7": fig7, "fig8": fig8}


def main(argv):
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2
    data_dir, out_dir = argv[1], argv[2]
    wanted = argv[3:] or sorted(FIGURES)
    unknown = [name for name in wanted if name not in FIGURES]
    if unknown:
        print("unknown figure(s): %s; known: %s" % (", ".join(unknown), ", ".join(sorted(FIGURES))), file=sys.stderr)
        return 2
    os.makedirs(out_dir, exist_ok=True)
    for name in wanted:
        if not all(os.path.exists(os.path.join(data_dir, name + ext)) for ext in (".csv", ".json")):
            print("skipped %s: no %s.csv and %s.json in %s" % (name, name, name, data_dir), file=sys.stderr)
            continue
        FIGURES[name](data_dir, out_dir)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
