#!/usr/bin/python3
"""Frame times of the BirefringentMaterial example pages in headless Chromium (SwiftShader: a
software figure, not a GPU one), and the same scenes with three.js's MeshPhysicalMaterial
iridescence in place of every birefringent material.

usage: frame_times.py [--width W] [--height H] [--frames N] [EXAMPLE ...]

Prints one line per page: first frame (shader compile included) and the median of N more frames,
each frame timed to a finished picture (a one-pixel read-back). Uses tests/web/screenshot.py's
DevTools pipe; Python's standard library only."""
import argparse
import json
import os
import shutil
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tests", "web"))
import screenshot  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=360)
    ap.add_argument("--frames", type=int, default=5)
    ap.add_argument("examples", nargs="*", default=["fig9c", "polariscope", "gem", "sheet"])
    a = ap.parse_args()
    base = "file://" + os.path.join(ROOT, "web", "three", "examples", "index.html")
    proc, cdp, profile = screenshot.launch(shutil.which("chromium") or "/usr/bin/chromium", a.width, a.height)
    try:
        target = cdp.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        sess = cdp.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        for ex in a.examples:
            for material in ("birefringent", "iridescence"):
                url = f"{base}?example={ex}&width={a.width}&height={a.height}&view=canvas&frames={a.frames}"
                if material == "iridescence":
                    url += "&material=iridescence"
                cdp.call("Page.navigate", {"url": url}, sess)
                title, deadline = "", time.time() + 600
                while time.time() < deadline and title != "biref ready" and not title.startswith("biref error"):
                    time.sleep(0.2)
                    title = cdp.call("Runtime.evaluate", {"expression": "document.title", "returnByValue": True},
                                     sess, timeout=600)["result"].get("value", "")
                if title != "biref ready":
                    print(f"{ex} {material}: {title}", file=sys.stderr)
                    return 1
                got = cdp.call("Runtime.evaluate", {"expression": "JSON.stringify(document.body.dataset)",
                                                    "returnByValue": True}, sess)["result"]["value"]
                d = json.loads(got)
                print(f"{ex:12s} {material:13s} {a.width}x{a.height}  first frame {d['firstFrameMs']:>8s} ms   "
                      f"median of {a.frames}: {d['frameMs']:>7s} ms", flush=True)
        return 0
    finally:
        proc.kill()
        proc.wait()
        shutil.rmtree(profile, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
