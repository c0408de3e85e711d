#!/usr/bin/python3
"""Draws every figure whose input exists in a rockmass output folder (`rockmass run` calls it).

Usage: /usr/bin/python3 scripts/figures/make_figures.py OUTDIR [--only PNG,...] [--skip PNG,...]
       [--scene NAME]

| figure | script | input |
|---|---|---|
| stereonet.png (poles per set) | stereonet.py | fractures.csv |
| rqd_threshold.png (Figure 6b) | rqd_threshold.py | rqd_balls.csv, boreholes.csv (summary.json) |
| rqd_ball_maps.png (RQD-ball contours) | rqd_ball_maps.py | rqd_balls.csv |
| block_volumes.png (Figure 7) | block_volumes.py | blocks.csv, summary.json |
| histories.png (Figure 8) | histories.py | history.csv |
| overload_curve.png (Figure 10) | overload_curve.py | overload.csv, summary.json |
| section.png (Figure 5) | section.py | section.csv |
| damage_map.png (Figure 9) | damage_map.py | damage.csv (section.csv, summary.json) |

Prints `figure: NAME` for every PNG written; a script that fails is reported and the others
still run (exit status 1 then). `--only` draws only the named figures (when their inputs
exist), `--skip` all but them; `--scene` names the scene in every title (by default
summary.json's `name`): `rockmass run` draws the figures whose inputs are final early, beside
its stability analyses, and the others at the end.
"""
import argparse
import concurrent.futures
import os
import subprocess
import sys

from figure_io import read_summary

HERE = os.path.dirname(os.path.abspath(__file__))


# Every figure this script can draw (jobs() draws those whose inputs are present).
FIGURES = ("stereonet.png", "rqd_threshold.png", "rqd_ball_maps.png", "block_volumes.png",
           "histories.png", "overload_curve.png", "section.png", "damage_map.png")


def jobs(out):
    """(png, script, arguments) for the inputs present in `out`."""
    has = lambda name: os.path.exists(os.path.join(out, name))  # noqa: E731
    path = lambda name: os.path.join(out, name)  # noqa: E731
    result = []
    if has("fractures.csv"):
        result.append(("stereonet.png", "stereonet.py", [path("fractures.csv")]))
    rqd_inputs = []
    if has("rqd_balls.csv"):
        rqd_inputs += ["--balls", path("rqd_balls.csv")]
    if has("boreholes.csv"):
        rqd_inputs += ["--boreholes", path("boreholes.csv")]
    if rqd_inputs:
        if has("summary.json"):
            rqd_inputs += ["--summary", path("summary.json")]
        result.append(("rqd_threshold.png", "rqd_threshold.py", rqd_inputs))
    if has("rqd_balls.csv"):
        result.append(("rqd_ball_maps.png", "rqd_ball_maps.py", [path("rqd_balls.csv")]))
    if has("blocks.csv"):
        result.append(("block_volumes.png", "block_volumes.py",
                       [path("blocks.csv"), "--summary", path("summary.json")]))
    if has("history.csv"):
        result.append(("histories.png", "histories.py", [path("history.csv")]))
    if has("overload.csv"):
        result.append(("overload_curve.png", "overload_curve.py",
                       [path("overload.csv"), "--summary", path("summary.json")]))
    if has("section.csv"):
        result.append(("section.png", "section.py", [path("section.csv")]))
    if has("damage.csv"):
        arguments = [path("damage.csv")]
        if has("section.csv"):
            arguments += ["--section", path("section.csv")]
        plane = read_summary(path("summary.json")).get("run", {}).get("section", "")
        if "=" in plane:
            arguments += ["--plane", plane]
        result.append(("damage_map.png", "damage_map.py", arguments))
    return result


def names(text):
    """The PNG names of a comma-separated list."""
    return {name.strip() for name in text.split(",") if name.strip()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", help="a rockmass output folder")
    parser.add_argument("--only", type=names, help="draw only these figures (PNG names)")
    parser.add_argument("--skip", type=names, default=set(), help="do not draw these figures")
    parser.add_argument("--scene", help="the scene's name for the titles (default: "
                        "summary.json's name)")
    args = parser.parse_args()
    out = args.out
    failed = False
    # Every figure names the scene it is of (summary.json's name unless given).
    scene = args.scene
    if scene is None:
        scene = read_summary(os.path.join(out, "summary.json")).get("name", "")
    # A name that is no figure's would silently leave a figure out (or draw none).
    known = set(FIGURES)
    unknown = sorted(((args.only or set()) | args.skip) - known)
    if unknown:
        parser.error(f"unknown figure {', '.join(unknown)}; expected one of: "
                     f"{', '.join(sorted(known))}")
    todo = [job for job in jobs(out)
            if (args.only is None or job[0] in args.only) and job[0] not in args.skip]

    def draw(job):
        png, script, arguments = job
        command = [sys.executable, os.path.join(HERE, script), *arguments, "-o",
                   os.path.join(out, png)] + (["--scene", scene] if scene else [])
        return subprocess.run(command, capture_output=True, text=True)

    # The figures are independent scripts, each writing its own PNG: drawn as many at a time
    # as the run may keep threads busy (ROCKMASS_THREADS, from `rockmass run --threads`; else
    # the cores this process may use), reported in the list's order.
    workers = int(os.environ.get("ROCKMASS_THREADS", "0") or 0)
    if workers < 1:
        workers = len(os.sched_getaffinity(0))
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, workers)) as pool:
        results = list(pool.map(draw, todo))
    for (png, script, _), done in zip(todo, results):
        if done.returncode == 0 and os.path.exists(os.path.join(out, png)):
            print(f"figure: {png}", flush=True)
        else:
            failed = True
            message = (done.stderr or done.stdout).strip().splitlines()
            print(f"{script} failed: {message[-1] if message else done.returncode}", flush=True)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
