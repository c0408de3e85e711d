#!/usr/bin/python3
"""RQD against the threshold, per RQD ball and per virtual borehole (Figure 6b of the paper).

Usage: /usr/bin/python3 scripts/figures/rqd_threshold.py [--balls rqd_balls.csv]
       [--boreholes boreholes.csv] [--summary summary.json] -o rqd_threshold.png

Balls (rqd_balls.csv: ball,dir_x,dir_y,dir_z,threshold,rqd): the mean over all directions
as a line, the band between the 10th and 90th percentile of the directions shaded, and the
directions of least and greatest RQD at the smallest threshold dashed. Boreholes
(boreholes.csv: borehole,from,to,threshold,rqd): the RQD of the whole hole, as the
run-length-weighted mean of its core runs, per threshold. When summary.json names a measured
log (`boreholes.measured.file`, CSV id,from,to,rqd, measured at `boreholes.measured.threshold`:
the scene's analysis.rqd.boreholes.measured), each hole's measured RQD (interval-length
weighted) is drawn at that threshold as a black-edged diamond in the hole's colour, labelled
"measured".
"""
import argparse
import csv
import os
import sys

import numpy as np

from figure_io import add_scene_argument, number, plt, read_rows, read_summary, save


def ball_curves(path):
    """{ball: (thresholds, rqd[direction, threshold])} from rqd_balls.csv."""
    rows = read_rows(path, ["ball", "dir_x", "dir_y", "dir_z", "threshold", "rqd"])
    data = {}
    for line, row in enumerate(rows, start=2):
        key = (number(row, "dir_x", path, line), number(row, "dir_y", path, line),
               number(row, "dir_z", path, line))
        data.setdefault(row["ball"], {}).setdefault(key, {})[
            number(row, "threshold", path, line)] = number(row, "rqd", path, line)
    curves = {}
    for ball, by_direction in data.items():
        thresholds = sorted({t for d in by_direction.values() for t in d})
        matrix = np.array([[d.get(t, np.nan) for t in thresholds] for d in by_direction.values()])
        curves[ball] = (np.array(thresholds), matrix)
    return curves


def borehole_curves(path):
    """{hole: (thresholds, rqd)}: run-length-weighted mean RQD of each hole per threshold."""
    rows = read_rows(path, ["borehole", "from", "to", "threshold", "rqd"])
    sums = {}
    for line, row in enumerate(rows, start=2):
        length = number(row, "to", path, line) - number(row, "from", path, line)
        t = number(row, "threshold", path, line)
        acc = sums.setdefault(row["borehole"], {}).setdefault(t, [0.0, 0.0])
        acc[0] += length * number(row, "rqd", path, line)
        acc[1] += length
    curves = {}
    for hole, by_t in sums.items():
        thresholds = sorted(by_t)
        curves[hole] = (np.array(thresholds),
                        np.array([by_t[t][0] / by_t[t][1] if by_t[t][1] > 0 else np.nan
                                  for t in thresholds]))
    return curves


def find_measured(summary):
    """summary.json's boreholes.measured entry (top level or under a stage's key), or None."""
    if not isinstance(summary, dict):
        return None
    holes = summary.get("boreholes")
    if isinstance(holes, dict) and isinstance(holes.get("measured"), dict):
        return holes["measured"]
    for value in summary.values():
        found = find_measured(value) if isinstance(value, dict) else None
        if found:
            return found
    return None


def measured_logs(entry, base):
    """({hole: measured whole-hole RQD}, threshold) from the measured log's CSV."""
    path = entry.get("file", "")
    if not os.path.isabs(path):
        path = os.path.join(base, path)
    sums = {}
    with open(path, newline="") as f:
        for line, row in enumerate(csv.DictReader(f), start=2):
            length = number(row, "to", path, line) - number(row, "from", path, line)
            acc = sums.setdefault(row["id"], [0.0, 0.0])
            acc[0] += length * number(row, "rqd", path, line)
            acc[1] += length
    return ({hole: a / b for hole, (a, b) in sums.items() if b > 0},
            float(entry.get("threshold", 0.1)))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--balls", help="rqd_balls.csv")
    parser.add_argument("--boreholes", help="boreholes.csv")
    parser.add_argument("--summary", help="summary.json (the measured logs, if any)")
    parser.add_argument("-o", "--output", default="rqd_threshold.png")
    add_scene_argument(parser)
    args = parser.parse_args(argv)
    measured, measured_t = {}, None
    entry = find_measured(read_summary(args.summary)) if args.summary else None
    if entry:
        try:
            measured, measured_t = measured_logs(entry, os.path.dirname(args.summary))
        except OSError as error:
            print(f"rqd_threshold: measured logs not drawn: {error}")
    if not args.balls and not args.boreholes:
        sys.exit("rqd_threshold: give --balls and/or --boreholes")

    panels = [p for p in (args.balls, args.boreholes) if p]
    fig, axes = plt.subplots(1, len(panels), figsize=(6.5 * len(panels), 4.8), squeeze=False)
    k = 0
    if args.balls:
        ax = axes[0][k]
        k += 1
        for ball, (t, m) in sorted(ball_curves(args.balls).items()):
            mean = np.nanmean(m, axis=0)
            line, = ax.plot(t, mean, "o-", ms=3, label=f"ball {ball}: mean of {len(m)} directions")
            ax.fill_between(t, np.nanpercentile(m, 10, axis=0), np.nanpercentile(m, 90, axis=0),
                            color=line.get_color(), alpha=0.15)
            order = np.argsort(m[:, 0])
            for row, style in ((order[0], ":"), (order[-1], "--")):
                ax.plot(t, m[row], style, color=line.get_color(), lw=0.8)
        ax.set_title("RQD balls (band: 10-90% of directions;\n"
                     "dotted/dashed: least/most RQD direction)", fontsize=10)
    if args.boreholes:
        ax = axes[0][k]
        for hole, (t, r) in sorted(borehole_curves(args.boreholes).items()):
            line, = ax.plot(t, r, "s-", ms=3, label=f"borehole {hole} (simulated)")
            if hole in measured:
                ax.plot([measured_t], [measured[hole]], "D", ms=8, color=line.get_color(),
                        mec="k", label=f"borehole {hole} measured (t = {measured_t:g} m)")
        ax.set_title("Virtual boreholes (whole hole)" +
                     ("; diamonds: the measured logs" if measured else ""), fontsize=10)
    for ax in axes[0]:
        ax.set_xlabel("threshold t (m)")
        ax.set_ylabel("RQD (%)")
        ax.set_ylim(-2, 102)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("RQD against threshold")
    fig.tight_layout()
    save(fig, args.output, facts={"measured": sorted(measured), "measured_threshold": measured_t},
         scene=args.scene)
    print(f"rqd_threshold: wrote {args.output}")


if __name__ == "__main__":
    main()
