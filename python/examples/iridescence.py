"""Iridescence of a thin calcite-like plate, step by step (run the cells in order, or the file).

    /usr/bin/python3 python/examples/iridescence.py [OUT_DIR]
"""
# %% The slab at one wavelength: power fractions, as `biref slab --json` gives them
import os
import sys

import numpy as np

import biref

plate = dict(eta_o=1.658, eta_e=1.486, axis=(1.0, 0.0, 0.3), thickness_um=6.0)
one = biref.slab(**plate, theta_deg=30, lambda_nm=550)
print("T s->s %.4f  s->p %.4f   energy %.12f" % (one["T"]["s"]["s"], one["T"]["s"]["p"], one["energy"]["s"]))

# %% Vectorised: transmission s->p over angle and wavelength in one call
theta = np.linspace(0, 80, 81)
lam = np.linspace(400, 700, 61)[:, None]
grid = biref.slab(**plate, theta_deg=theta, lambda_nm=lam)
Tsp = grid["T"]["s"]["p"]  # shape (61, 81)
print("T s->p over the grid: min %.3f max %.3f" % (Tsp.min(), Tsp.max()))

# %% Colours between crossed polarizers (p in, s out) as the plate tilts
col = biref.spectrum(**plate, theta_deg=theta, polarization="p", analyzer="s")
rgb = np.clip(col["mixed"]["T_srgb"], 0, 1)  # shape (81, 3)
for t in (0, 20, 40, 60):
    print("theta %2d deg: sRGB %.2f %.2f %.2f" % (t, *rgb[t]))

# %% The same with the exact path-group expansion and a world-fixed polarizer at 45 degrees
exact = biref.spectrum(**plate, theta_deg=30, method="expansion", polarizer="linear:45", analyzer="linear:-45")
print("expansion, crossed linear polarizers at +-45 deg: sRGB", np.round(exact["mixed"]["T_srgb"], 3))

# %% A rendered scene as a numpy image (linear sRGB), and a photoelastic disk
here = os.path.dirname(os.path.abspath(__file__))
scene = os.path.join(here, os.pardir, os.pardir, "examples", "fig9a.json")
if os.path.exists(scene):
    img = biref.render(scene, width=160, height=90)
    print("render:", img.shape, "mean linear sRGB", np.round(img.reshape(-1, 3).mean(0), 3))
disk = biref.photoelastic(preset="disk", load_N=800, size=128)
print("photoelastic disk:", disk.shape, "brightest pixel", np.round(disk.max(), 3))

# %% Save the colour strip and the disk as PPM images (no plotting library needed)
out = sys.argv[1] if len(sys.argv) > 1 else None
if out:
    os.makedirs(out, exist_ok=True)

    def save_ppm(path, linear_or_encoded, encoded):
        a = np.clip(linear_or_encoded, 0, 1)
        if not encoded:
            a = np.where(a <= 0.0031308, 12.92 * a, 1.055 * a ** (1 / 2.4) - 0.055)
        a = (a * 255 + 0.5).astype(np.uint8)
        with open(path, "wb") as f:
            f.write(b"P6 %d %d 255\n" % (a.shape[1], a.shape[0]) + a.tobytes())

    save_ppm(os.path.join(out, "tilt_strip.ppm"), np.repeat(rgb[None], 20, axis=0), encoded=True)
    save_ppm(os.path.join(out, "disk.ppm"), disk, encoded=False)
    print("wrote", out)
