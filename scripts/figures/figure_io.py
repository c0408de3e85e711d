"""Shared helpers of the figure scripts: reading rockmass CSV/JSON outputs and saving PNGs.

Every figure script reads only the files `rockmass` writes (the contract in
shared/docs/scene-format.md and docs/scene-reference.md), never the program's memory.
"""
import csv
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported for the scripts)


def read_rows(path, columns):
    """Rows of a CSV file as dicts; exits with file:line when a needed column is missing."""
    rows = []
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in columns if c not in (reader.fieldnames or [])]
        if missing:
            sys.exit(f"{path}:1: expected the columns {', '.join(columns)}; missing "
                     f"{', '.join(missing)}")
        for row in reader:
            rows.append(row)
    return rows


def number(row, key, path, line):
    """A float field; exits with file:line when it is not a number."""
    try:
        return float(row[key])
    except (TypeError, ValueError):
        sys.exit(f"{path}:{line}: {key}: expected a number, got {row.get(key)!r}")


def read_summary(path):
    """summary.json as a dict, or {} when the file does not exist."""
    try:
        with open(path) as f:
            return json.load(f)
    except FileNotFoundError:
        return {}


# (scale from m, label), largest first: unit_for picks the first that shows the data well.
UNITS = ((100.0, "cm"), (1000.0, "mm"), (1e6, "µm"))


def unit_for(values):
    """(scale, label) among cm, mm and um that shows the largest |value| (m) as at least 0.1
    (the paper's cm when the values are that large)."""
    largest = max((abs(v) for v in values), default=0.0)
    for scale, label in UNITS:
        if largest * scale >= 0.1:
            return scale, label
    return UNITS[-1]


def compass(ax, fontsize=9):
    """N, E, S and W around the unit circle of a projection (x east, y north)."""
    for label, (x, y, ha, va) in {"N": (0, 1.04, "center", "bottom"),
                                  "E": (1.04, 0, "left", "center"),
                                  "S": (0, -1.04, "center", "top"),
                                  "W": (-1.04, 0, "right", "center")}.items():
        ax.text(x, y, label, ha=ha, va=va, fontsize=fontsize)


def describe(fig, facts=None):
    """What the figure shows, as the tests read it: the suptitle, and per panel its title,
    axis labels, legend entries and texts, plus the script's `facts` (the population drawn,
    units, choices), as JSON."""
    panels = []
    for ax in fig.axes:
        legend = ax.get_legend()
        panels.append({
            "title": ax.get_title(),
            "xlabel": ax.get_xlabel(),
            "ylabel": ax.get_ylabel(),
            "legend": [t.get_text() for t in legend.get_texts()] if legend else [],
            "texts": [t.get_text() for t in ax.texts],
        })
    title = fig._suptitle.get_text() if fig._suptitle is not None else ""
    return json.dumps({"suptitle": title, "panels": panels, "facts": facts or {}},
                      sort_keys=True)


def add_scene_argument(parser):
    """--scene NAME: the scene the figure is of (make_figures passes summary.json's name)."""
    parser.add_argument("--scene", default="", help="scene name, put in the figure's title")


def save(fig, path, facts=None, scene=""):
    """Saves a figure as PNG without a timestamp (same inputs, same bytes), with describe()
    in the PNG's text chunk "rockmass" (tests/figures/figure_smoke_test.py reads it). A
    `scene` name starts the figure's title (a figure pasted in a report says what it is of)."""
    if scene:
        title = fig._suptitle.get_text() if fig._suptitle is not None else ""
        if not title.startswith(scene):
            size = fig._suptitle.get_fontsize() if fig._suptitle is not None else 11
            fig.suptitle(f"{scene}: {title}" if title else scene, fontsize=size)
        facts = dict(facts or {}, scene=scene)
    fig.savefig(path, dpi=120, metadata={"Software": None, "rockmass": describe(fig, facts)})
    plt.close(fig)
