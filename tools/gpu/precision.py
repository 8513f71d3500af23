#!/usr/bin/python3
"""Single-precision GPU shader against the double-precision CPU renderer, per pixel.

usage: tools/gpu/precision.py [--biref build/biref] [--width 320 --height 180] [SCENE.json ...]

Renders each scene with `biref render --backend gl` and with the CPU (the analytic method; the
path-group expansion for world-fixed polarizers, which the CPU's analytic method refuses), both
as linear-sRGB PFM, and prints one Markdown row per scene: largest absolute and relative
difference of the linear values (relative where the CPU value exceeds 0.01) and dE00 mean / p99 /
max of the 8-bit pictures. Needs Debian's python3-numpy (hence /usr/bin/python3)."""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

import numpy as np


def read_pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3)[::-1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--biref", default="build/biref")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("scenes", nargs="*")
    a = ap.parse_args()
    scenes = a.scenes or sorted(glob.glob("examples/*.json"))
    size = ["--width", str(a.width), "--height", str(a.height)]
    print("| scene | CPU reference | max abs | max rel | dE00 mean | p99 | max |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            name = os.path.splitext(os.path.basename(scene))[0]
            world_fixed = '"linear"' in open(scene).read()
            ref = ["--method", "expansion"] if world_fixed else []
            out = {}
            # The shader has no prefilter: the CPU's point look-ups (as tests/cli/gl.sh).
            for backend, extra in (("cpu", ref + ["--quiet", "--antialias", "none"]), ("gl", ["--backend", "gl"])):
                png, pfm = f"{tmp}/{name}-{backend}.png", f"{tmp}/{name}-{backend}.pfm"
                subprocess.run([a.biref, "render", scene, "-o", png, "--pfm", pfm] + size + extra,
                               check=True, stdout=subprocess.DEVNULL)
                out[backend] = (png, read_pfm(pfm))
            cpu, gpu = out["cpu"][1].astype(np.float64), out["gl"][1].astype(np.float64)
            d = np.abs(gpu - cpu)
            big = np.abs(cpu) > 0.01
            rel = (d[big] / np.abs(cpu[big])).max() if big.any() else 0.0
            de = json.loads(subprocess.run([a.biref, "diff", out["gl"][0], out["cpu"][0], "--json"], check=True,
                                           capture_output=True, text=True).stdout)
            print(f"| {name} | {'expansion' if world_fixed else 'analytic'} | {d.max():.2e} | {rel:.2e} | "
                  f"{de['mean']:.4f} | {de['p99']:.3f} | {de['max']:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
