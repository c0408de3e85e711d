#!/usr/bin/python3
"""report.html in headless Chromium (Debian's `chromium`, SwiftShader WebGL): `rockmass run` of a
small scene with blocks, an RQD ball, a DDA with monitors and figures writes report.html; opened
from disk it must raise no script error, show as many blocks as blocks.csv holds (and the DDA's
blocks, balls, monitors and frames the run made), pick a block at the canvas centre and name it
with its id, volume and material as blocks.csv has them, and draw a 3D canvas that is not blank
(screenshot pixels: many non-white pixels of several colours).

Usage: report_test.py ROCKMASS_BINARY. Exits 77 (skipped) when chromium, libjs-three or
matplotlib is missing.
"""
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

SCENE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "data",
                     "two_sets_small.yaml")

FLAGS = ["--headless", "--no-sandbox", "--enable-unsafe-swiftshader", "--use-angle=swiftshader",
         "--window-size=1400,900", "--virtual-time-budget=30000"]


def chromium(*args):
    return subprocess.run(["chromium", *FLAGS, *args], capture_output=True, text=True, timeout=180)


def main():
    binary = sys.argv[1]
    if not shutil.which("chromium") or not os.path.exists("/usr/share/javascript/three/three.min.js"):
        print("chromium or libjs-three is not installed: skipped")
        sys.exit(77)
    try:
        import matplotlib.image  # noqa: F401
    except ImportError:
        print("matplotlib is not installed: skipped")
        sys.exit(77)
    import matplotlib.image as mpimg
    import numpy as np
    with tempfile.TemporaryDirectory() as d:
        scene = SCENE
        out = os.path.join(d, "out")
        done = subprocess.run([binary, "run", scene, "-o", out], capture_output=True, text=True)
        print(done.stderr[-1500:])
        assert done.returncode == 0, "rockmass run failed"
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        assert "report.html" in summary["run"]["files"], summary["run"]["files"]
        assert summary["run"]["figures"], "the run drew no figures"
        with open(os.path.join(out, "blocks.csv"), newline="") as f:
            blocks = {int(r["id"]): r for r in csv.DictReader(f)}
        page = "file://" + os.path.join(out, "report.html")
        with open(os.path.join(out, "report.html")) as f:
            html = f.read()
        assert "src=\"http" not in html and "href=\"http" not in html, "the page loads from the net"
        assert html.count("data:image/png;base64,") == 1  # the template; figures are data URIs

        dom = chromium("--dump-dom", page + "?test&pick=532,284")
        found = re.search(r'<pre id="status">([^<]*)</pre>', dom.stdout)
        assert found, dom.stdout[-2000:] + dom.stderr[-2000:]
        status = json.loads(found.group(1).replace("&quot;", '"').replace("&amp;", "&"))
        print("status", status)
        assert status["errors"] == [], status["errors"]
        assert status["blocks"] == len(blocks), (status["blocks"], len(blocks))
        # The DDA's blocks: the cut's, or fewer when small ones were glued (summary "dda").
        assert status["dda_blocks"] == summary["dda"].get("blocks", summary["blocks"]), status
        assert status["balls"] == 1 and status["monitors"] == 1, status
        assert status["frames"] >= 2, status
        pick = status["pick"]
        assert pick and pick["layer"] == "blocks", pick
        row = blocks[pick["id"]]
        assert abs(pick["volume"] - float(row["volume"])) <= 1e-12 * float(row["volume"]), (pick, row)
        assert pick["material"] == row["material"], (pick, row)
        assert f'id="blockCount">{len(blocks)}<' in dom.stdout  # the count the page shows
        assert "block " + str(pick["id"]) + ":" in dom.stdout  # the pick named in the page
        assert dom.stdout.count("<img") == len(summary["run"]["figures"])

        shot = os.path.join(d, "shot.png")
        chromium("--screenshot=" + shot, page)
        image = mpimg.imread(shot)[:, 320:, :3]  # the view, right of the side panel
        canvas = image[: int(0.7 * image.shape[0])]
        coloured = (canvas.min(axis=2) < 0.9).mean()
        colours = len(np.unique((canvas.reshape(-1, 3) * 15).round(), axis=0))
        print(f"canvas: {coloured:.1%} of the pixels not white, {colours} colour levels")
        assert coloured > 0.05 and colours > 20, "the 3D canvas is blank"
    print("report checked")


if __name__ == "__main__":
    main()
