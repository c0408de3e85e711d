#!/usr/bin/python3
"""Figures of an ensemble (rockmass ensemble): the distribution of the stability factors, RQD
bands against the threshold, and the convergence of the means with the realizations.

Usage: /usr/bin/python3 scripts/figures/ensemble_figures.py OUTDIR

Reads OUTDIR/ensemble.json and the CSVs it lists (docs/ensemble.md); writes into OUTDIR:
- ensemble_factors.png: a histogram of each factor the realizations computed (K_s, critical
  SRF), the scene's target and the probability below it (with its standard error), and the
  rank correlation (Spearman) of the factor with each uncertain input, largest first;
- ensemble_rqd.png: for every RQD ball (its mean over directions) and every borehole, the
  median RQD of the realizations against the threshold with the 5-95 % band;
- ensemble_convergence.png: the running mean of each factor (and of P32 per set) with its 95 %
  confidence interval against the number of realizations.
A figure whose inputs the ensemble did not produce is skipped. Prints "figure: NAME" per PNG.
"""
import argparse
import json
import math
import os
import sys

import numpy as np

from figure_io import plt, read_rows, save

FACTORS = (("K_s", "overload factor K_s"), ("critical_srf", "critical SRF"))


def columns(path):
    """The realizations' CSV as {column: [float or nan]}."""
    rows = read_rows(path, ["realization"])
    out = {}
    for row in rows:
        for key, value in row.items():
            try:
                out.setdefault(key, []).append(float(value) if value != "" else math.nan)
            except ValueError:
                sys.exit(f"{path}: {key}: expected a number, got {value!r}")
    return out


def factors_figure(out, ensemble, data, scene):
    present = [(k, label) for k, label in FACTORS if k in data and
               any(math.isfinite(v) for v in data[k])]
    if not present:
        return None
    fig, axes = plt.subplots(2, len(present), figsize=(5.5 * len(present), 7.5), squeeze=False)
    facts = {"realizations": ensemble.get("complete"), "factors": {}}
    for column, (key, label) in enumerate(present):
        values = np.array([v for v in data[key] if math.isfinite(v)])
        info = ensemble.get("stability", {}).get(key, {})
        ax = axes[0][column]
        bins = max(5, min(30, int(math.sqrt(len(values))) + 1))
        ax.hist(values, bins=bins, color="#7a9cc6", edgecolor="white")
        ax.set_xlabel(label)
        ax.set_ylabel("realizations")
        stats = info.get("stats", {})
        title = f"{label}: mean {stats.get('mean', float('nan')):.3g}, n = {len(values)}"
        outside = len(data[key]) - len(values)
        if outside:
            title += f" ({outside} outside the factors tried)"
        fact = {"n": len(values), "mean": stats.get("mean")}
        if "target" in info:
            target = info["target"]
            ax.axvline(target, color="#c0392b", lw=1.5,
                       label=f"target {target:g}: P(below) = {info['probability_below']:.3f}"
                             f" ± {info['standard_error']:.3f}")
            ax.legend(fontsize=8)
            fact.update(target=target, probability_below=info["probability_below"])
        ax.set_title(title, fontsize=10)
        ax = axes[1][column]
        sens = [s for s in info.get("sensitivity", []) if s.get("spearman") is not None]
        if sens:
            names = [s["key"] for s in sens][::-1]
            rho = [s["spearman"] for s in sens][::-1]
            ax.barh(range(len(rho)), rho, color=["#c0392b" if r < 0 else "#2e86c1" for r in rho])
            ax.set_yticks(range(len(rho)), names, fontsize=8)
            ax.set_xlim(-1, 1)
            ax.axvline(0, color="black", lw=0.5)
            fact["most_influential"] = sens[0]["key"]
        else:
            ax.text(0.5, 0.5, "no uncertain input varies", ha="center", va="center",
                    transform=ax.transAxes)
        ax.set_xlabel(f"Spearman rank correlation with {label}")
        ax.set_title("sensitivity", fontsize=10)
        facts["factors"][key] = fact
    fig.suptitle(f"{ensemble.get('complete')} realizations ({ensemble.get('sampling')})")
    fig.tight_layout()
    path = os.path.join(out, "ensemble_factors.png")
    save(fig, path, facts, scene)
    return path


def rqd_figure(out, ensemble, data, scene):
    balls = {}
    for key in data:
        if key.startswith("rqd_ball:"):
            _, name, threshold = key.split(":")
            balls.setdefault(name, []).append((float(threshold), data[key]))
    holes = {}
    path = os.path.join(out, "ensemble_boreholes.csv")
    if os.path.exists(path):
        for row in read_rows(path, ["hole", "threshold", "p05", "p50", "p95"]):
            holes.setdefault(row["hole"], []).append(
                tuple(float(row[k]) for k in ("threshold", "p05", "p50", "p95")))
    if not balls and not holes:
        return None
    fig, ax = plt.subplots(figsize=(7.5, 5))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    drawn = []
    for i, (name, series) in enumerate(sorted(balls.items())):
        series.sort()
        t = [s[0] for s in series]
        band = [np.nanpercentile(s[1], [5, 50, 95]) for s in series]
        colour = colours[i % len(colours)]
        ax.fill_between(t, [b[0] for b in band], [b[2] for b in band], color=colour, alpha=0.2)
        ax.plot(t, [b[1] for b in band], "-o", color=colour, ms=3, label=f"ball {name}")
        drawn.append(f"ball {name}")
    for j, (name, series) in enumerate(sorted(holes.items())):
        series.sort()
        colour = colours[(len(balls) + j) % len(colours)]
        t = [s[0] for s in series]
        ax.fill_between(t, [s[1] for s in series], [s[3] for s in series], color=colour,
                        alpha=0.15, hatch="//")
        ax.plot(t, [s[2] for s in series], "--s", color=colour, ms=3, label=f"borehole {name}")
        drawn.append(f"borehole {name}")
    ax.set_xlabel("threshold t (m)")
    ax.set_ylabel("RQD (%)")
    ax.set_ylim(0, 100)
    ax.legend(fontsize=8)
    ax.set_title("median of the realizations, band 5-95 %", fontsize=10)
    fig.suptitle(f"RQD against threshold over {ensemble.get('complete')} realizations")
    fig.tight_layout()
    path = os.path.join(out, "ensemble_rqd.png")
    save(fig, path, {"series": drawn, "band": "5-95 %"}, scene)
    return path


def convergence_figure(out, ensemble, scene):
    path = os.path.join(out, "ensemble_convergence.csv")
    if not os.path.exists(path):
        return None
    series = {}
    for row in read_rows(path, ["measure", "n", "mean", "ci95"]):
        series.setdefault(row["measure"], []).append(
            (int(row["n"]), float(row["mean"]), float(row["ci95"])))
    def varies(key):
        means = [s[1] for s in series[key]]
        return max(means) - min(means) > 1e-9 * max(1.0, abs(means[0]))

    # A measure that does not vary (a fault's P32 in every realization) has nothing to show.
    wanted = [k for k, _ in FACTORS if k in series and varies(k)]
    wanted += sorted(k for k in series if k.startswith("p32:") and varies(k))[:4]
    if not wanted:
        return None
    fig, axes = plt.subplots(len(wanted), 1, figsize=(7, 2.4 * len(wanted)), sharex=True,
                             squeeze=False)
    for ax, key in zip(axes[:, 0], wanted):
        n = np.array([s[0] for s in series[key]])
        mean = np.array([s[1] for s in series[key]])
        ci = np.array([s[2] for s in series[key]])
        ax.fill_between(n, mean - ci, mean + ci, color="#7a9cc6", alpha=0.3)
        ax.plot(n, mean, "-", color="#1f4e79", lw=1.2)
        label = dict(FACTORS).get(key, key.replace("p32:", "P32 of ") + " (m²/m³)")
        ax.set_ylabel(label, fontsize=8)
        ax.set_title(f"{label}: running mean and 95 % interval", fontsize=9)
    axes[-1][0].set_xlabel("realizations")
    fig.suptitle("Convergence of the means")
    fig.tight_layout()
    out_path = os.path.join(out, "ensemble_convergence.png")
    save(fig, out_path, {"measures": wanted}, scene)
    return out_path


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("outdir", help="the ensemble's output folder")
    args = parser.parse_args(argv)
    try:
        with open(os.path.join(args.outdir, "ensemble.json")) as f:
            ensemble = json.load(f)
    except FileNotFoundError:
        sys.exit(f"{args.outdir}: no ensemble.json (run rockmass ensemble first)")
    data = columns(os.path.join(args.outdir, "ensemble_realizations.csv"))
    scene = ensemble.get("name", "")
    for path in (factors_figure(args.outdir, ensemble, data, scene),
                 rqd_figure(args.outdir, ensemble, data, scene),
                 convergence_figure(args.outdir, ensemble, scene)):
        if path:
            print("figure: " + os.path.basename(path))


if __name__ == "__main__":
    main()
