"""The Python bindings against the command line (same numbers as `biref ... --json`) and against
physics they must keep (energy, the transfer matrix, vectorised calls equal to scalar ones).

Run by ctest (python_bindings) with BIREF_LIBRARY, BIREF_CDEF and BIREF_CLI set; BIREF_CLI
missing skips the comparisons with the command line.
"""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import biref

CLI = os.environ.get("BIREF_CLI")
needs_cli = pytest.mark.skipif(not CLI, reason="BIREF_CLI not set")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

SLAB = dict(eta_o=1.775, eta_e=1.231, axis=(0.084, 0.979, -0.187))
SLAB_ARGS = ["--eta-o", "1.775", "--eta-e", "1.231", "--axis", "0.084,0.979,-0.187"]


def cli_json(*args):
    out = subprocess.run([CLI, *args, "--json"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def assert_same(got, ref, tol, path="$"):
    """Every field of the CLI's JSON is present in got with the same value (numbers to tol)."""
    if isinstance(ref, dict):
        for k, v in ref.items():
            assert k in got, f"{path}.{k} missing"
            assert_same(got[k], v, tol, f"{path}.{k}")
    elif isinstance(ref, list):
        assert len(got) == len(ref), path
        for i, (a, b) in enumerate(zip(got, ref)):
            assert_same(a, b, tol, f"{path}[{i}]")
    elif isinstance(ref, bool) or ref is None or isinstance(ref, str):
        assert got == ref, f"{path}: {got!r} != {ref!r}"
    else:
        assert abs(got - ref) <= tol * max(1.0, abs(ref)), f"{path}: {got!r} != {ref!r}"


@needs_cli
@pytest.mark.parametrize("method", ["closed-form", "tmm"])
def test_slab_matches_cli(method):
    got = biref.slab(**SLAB, thickness_mm=1.15, theta_deg=30, lambda_nm=550, method=method)
    ref = cli_json("slab", *SLAB_ARGS, "--thickness-mm", "1.15", "--theta-deg", "30", "--lambda-nm", "550",
                   "--method", method)
    assert_same(got, ref, 1e-13)


@needs_cli
def test_slab_total_reflection_matches_cli():
    kw = dict(eta_o=1.4, eta_e=1.6, axis=(0.2, 0.3, 0.9), thickness_um=2.5, theta_deg=75, lambda_nm=480, eta_i=1.5)
    ref = cli_json("slab", "--eta-o", "1.4", "--eta-e", "1.6", "--axis", "0.2,0.3,0.9", "--thickness-um", "2.5",
                   "--theta-deg", "75", "--lambda-nm", "480", "--eta-i", "1.5")
    assert ref["total_reflection"]["any"]
    assert_same(biref.slab(**kw), ref, 1e-13)


@needs_cli
def test_stack_matches_cli():
    path = os.path.join(ROOT, "examples", "stacks", "solc_folded.json")
    ref = cli_json("stack", path, "--theta-deg", "20", "--lambda-nm", "520")
    got = biref.stack(path, theta_deg=20, lambda_nm=520)
    for key in ("T", "R", "jones_T", "jones_R", "energy", "K", "total_reflection"):
        assert_same(got[key], ref[key], 1e-13)


def test_stack_of_one_layer_is_the_slab_and_arrays_broadcast():
    lam = np.linspace(400, 700, 5)
    one = {"eta_i": 1.0, "layers": [{"eta_o": 1.775, "eta_e": 1.231, "axis": [0.084, 0.979, -0.187],
                                     "thickness_um": 12}]}
    v = biref.stack(one, theta_deg=30, lambda_nm=lam)
    s = biref.slab(**SLAB, thickness_um=12, theta_deg=30, lambda_nm=lam)
    for d in ("T", "R"):
        for a in "sp":
            for b in "sp":
                np.testing.assert_allclose(v[d][a][b], s[d][a][b], atol=1e-12)
    np.testing.assert_allclose(v["energy"]["p"], 1.0, atol=1e-12)
    t = biref.stack(one, theta_deg=30, lambda_nm=lam, method="tmm")
    np.testing.assert_allclose(t["T"]["s"]["p"], v["T"]["s"]["p"], atol=1e-9)
    with pytest.raises(ValueError, match="layers\\[0\\].thickness_um: missing"):
        biref.stack({"layers": [{"eta": 1.5}]})
    with pytest.raises(ValueError, match="method"):
        biref.stack(one, method="magic")


def test_stack_of_a_dispersive_layer_is_the_material_slab():
    lam = np.linspace(400, 700, 7)
    one = {"eta_i": 1.0, "layers": [{"material": "calcite", "axis": [0.3, 0.5, 0.8], "thickness_um": 12}]}
    v = biref.stack(one, theta_deg=30, lambda_nm=lam)
    s = biref.slab(material="calcite", axis=(0.3, 0.5, 0.8), thickness_um=12, theta_deg=30, lambda_nm=lam)
    for d in ("T", "R"):
        for a in "sp":
            for b in "sp":
                np.testing.assert_allclose(v[d][a][b], s[d][a][b], atol=1e-12)
    assert v["input"]["layers"][0]["material"] == "calcite"
    with pytest.raises(ValueError, match="layers\\[0\\].material: unknown material"):
        biref.stack({"layers": [{"material": "unobtainium", "axis": [0, 0, 1], "thickness_um": 1}]})
    path = os.path.join(ROOT, "examples", "stacks", "quartz_zero_order_halfwave.json")
    got = biref.stack_spectrum(path, polarization="s", analyzer="p")
    assert not got["expansion"]["fallback"] and got["expansion"]["groups"]["T"] > 0  # closed form


@needs_cli
def test_stack_spectrum_matches_cli():
    path = os.path.join(ROOT, "examples", "stacks", "film_on_glass.json")
    ref = cli_json("spectrum", "--stack", path, "--theta-deg", "30", "--polarization", "s", "--analyzer", "p")
    got = biref.stack_spectrum(path, theta_deg=30, polarization="s", analyzer="p")
    for key in ("T", "R"):
        assert_same(got[key], ref[key], 1e-12)
    np.testing.assert_allclose(got["mixed"]["T_xyz"], ref["mixed"]["T_xyz"], atol=1e-12)
    assert got["expansion"]["groups"] == ref["expansion"]["groups"]
    with pytest.raises(ValueError, match="no analytic method"):
        biref.stack_spectrum(path, method="analytic")
    with pytest.raises(ValueError, match="no analytic-pairs method"):
        biref.stack_spectrum(path, method="analytic-pairs")


def test_slab_vectorised_equals_scalar_and_conserves_energy():
    theta = np.array([0.0, 20.0, 45.0, 70.0])
    lam = np.linspace(400, 700, 7)[:, None]
    v = biref.slab(**SLAB, thickness_um=12, theta_deg=theta, lambda_nm=lam)
    assert v["T"]["s"]["p"].shape == (7, 4)
    np.testing.assert_allclose(v["energy"]["s"], 1.0, atol=1e-12)
    np.testing.assert_allclose(v["energy"]["p"], 1.0, atol=1e-12)
    for i, j in [(0, 0), (3, 2), (6, 3)]:
        one = biref.slab(**SLAB, thickness_um=12, theta_deg=theta[j], lambda_nm=lam[i, 0])
        for d in ("T", "R"):
            for a in "sp":
                for b in "sp":
                    assert v[d][a][b][i, j] == pytest.approx(one[d][a][b], abs=1e-15)
        re, im = one["jones_T"]["p"]["s"]
        assert v["jones_T"]["p"]["s"][i, j] == pytest.approx(complex(re, im), abs=1e-15)
    # The closed form against the independent 4x4 transfer matrix, over the whole grid.
    t = biref.slab(**SLAB, thickness_um=12, theta_deg=theta, lambda_nm=lam, method="tmm")
    for a in "sp":
        for b in "sp":
            np.testing.assert_allclose(t["T"][a][b], v["T"][a][b], atol=1e-9)
            np.testing.assert_allclose(t["R"][a][b], v["R"][a][b], atol=1e-9)


@needs_cli
@pytest.mark.parametrize("extra", [
    dict(),
    dict(polarization="p", analyzer="s"),
    dict(polarization=(0.75, 0.25), cmf="wyman2013", range_nm=(400, 680)),
    dict(method="numeric", samples=48, polarizer="linear:30", analyzer="circular:-1"),
    dict(method="expansion", stokes=(1, 0.2, -0.3, 0.5), analyzer="linear:60"),
    dict(polarizer="linear:10", analyzer="circular:+1"),
    dict(method="expansion", order=2),
    dict(method="analytic-pairs", polarization="s", analyzer="p"),
    dict(method="analytic-pairs", polarizer="linear:10", analyzer="circular:+1"),
])
def test_spectrum_matches_cli(extra):
    args = ["spectrum", *SLAB_ARGS, "--thickness-um", "20", "--theta-deg", "30"]
    for k, v in extra.items():
        opt = "--" + k.replace("_", "-")
        args += [opt, ",".join(f"{x:g}" for x in v) if isinstance(v, tuple) else str(v)]
    got = biref.spectrum(**SLAB, thickness_um=20, theta_deg=30, **extra)
    ref = cli_json(*args)
    if "state" in ref["mixed"]["polarization"]:  # the option's text, spelt by the caller
        del ref["mixed"]["polarization"]["state"]
    assert_same(got, ref, 1e-13)


def test_spectrum_vectorised_over_theta():
    theta = np.array([[0.0, 15.0], [40.0, 80.0]])
    v = biref.spectrum(**SLAB, thickness_um=3, theta_deg=theta, method="expansion")
    assert v["mixed"]["T_xyz"].shape == (2, 2, 3)
    one = biref.spectrum(**SLAB, thickness_um=3, theta_deg=40.0, method="expansion")
    np.testing.assert_allclose(v["mixed"]["T_xyz"][1, 0], one["mixed"]["T_xyz"], rtol=0, atol=1e-15)
    np.testing.assert_allclose(v["T"]["s"]["p"][1, 0], one["T"]["s"]["p"], rtol=0, atol=1e-15)
    # Lossless slab, unpolarized light, no analyzer: T + R = white, to the expansion's tolerance.
    np.testing.assert_allclose(v["mixed"]["T_xyz"] + v["mixed"]["R_xyz"], 1.0, atol=2e-3)


def test_bad_input_is_refused_with_the_cli_wording():
    with pytest.raises(ValueError, match="thickness"):
        biref.slab(**SLAB)
    with pytest.raises(ValueError, match="theta_deg"):
        biref.slab(**SLAB, thickness_um=1, theta_deg=95)
    with pytest.raises(ValueError):
        biref.slab(eta_o=float("nan"), eta_e=1.2, axis=(0, 1, 0), thickness_um=1)
    with pytest.raises(ValueError, match="method"):
        biref.spectrum(**SLAB, thickness_um=1, method="magic")
    with pytest.raises(ValueError, match="slabs"):
        biref.render({"camera": {"position": [0, 1, 1], "look_at": [0, 0, 0]}})


def small_scene():
    with open(os.path.join(ROOT, "examples", "fig9a.json"), encoding="utf-8") as f:
        return json.load(f)


@needs_cli
def test_render_matches_cli(tmp_path):
    img = biref.render(small_scene(), width=48, height=27)
    assert img.shape == (27, 48, 3) and np.all(np.isfinite(img))
    pfm = tmp_path / "a.pfm"
    subprocess.run([CLI, "render", os.path.join(ROOT, "examples", "fig9a.json"), "-o", str(tmp_path / "a.png"),
                    "--width", "48", "--height", "27", "--pfm", str(pfm), "-q", "--antialias", "none"], check=True)
    data = pfm.read_bytes()
    header_end = 0
    for _ in range(3):
        header_end = data.index(b"\n", header_end) + 1
    ref = np.frombuffer(data[header_end:], dtype="<f4").reshape(27, 48, 3)[::-1]
    np.testing.assert_allclose(img, ref, atol=1e-6)
    # A path gives the same image; XYZ and encoded sRGB are the same picture in other spaces.
    np.testing.assert_array_equal(biref.render(os.path.join(ROOT, "examples", "fig9a.json"), width=48, height=27),
                                  img)
    enc = biref.render(small_scene(), width=48, height=27, space="srgb")
    inside = (img > 0.01) & (img < 0.99)
    assert np.all(enc[inside] > img[inside])  # the transfer curve lifts values in (0, 1)


def test_render_methods_agree():
    a = biref.render(small_scene(), width=24, height=14)
    # The 1.25 mm slab's bands alias spectrally with a few hundred samples (paper fig. 9): 2048.
    n = biref.render(small_scene(), width=24, height=14, method="numeric", samples=2048)
    assert np.abs(a - n).mean() < 0.01


def test_render_stack_slabs():
    """A slab given as a one-layer stack renders as the slab (numeric: the same exact Jones matrices);
    the tape-art scene (every pane a stack) renders, and a bad layer names its JSON path."""
    plain = small_scene()
    stack = json.loads(json.dumps(plain))
    sl = stack["slabs"][0]
    sl["layers"] = [{k: sl.pop(k) for k in ("eta_o", "eta_e", "axis", "thickness_mm")}]
    a = biref.render(plain, width=24, height=14, method="numeric")
    b = biref.render(stack, width=24, height=14, method="numeric")
    np.testing.assert_allclose(b, a, atol=1e-6)
    with open(os.path.join(ROOT, "examples", "stack_scenes", "tape_art.json"), encoding="utf-8") as f:
        tape = json.load(f)
    img = biref.render(tape, width=32, height=24, method="numeric")
    assert np.all(np.isfinite(img)) and img.max() > 0.1
    sl["layers"][0]["thickness_mm"] = -1
    with pytest.raises(ValueError, match=r"slabs\[0\]\.layers\[0\]\.thickness_mm"):
        biref.render(stack, width=8, height=8)


@needs_cli
def test_photoelastic_matches_cli(tmp_path):
    img = biref.photoelastic(preset="disk", size=64, supersample=1)
    h, w, _ = img.shape
    assert max(h, w) == 64 and np.all(np.isfinite(img))
    from biref._native import ffi, lib

    def cli_and_mine(antialias=None):
        """The CLI's 8-bit PNG read back through the library, and ours encoded and rounded; both
        with their defaults when antialias is None."""
        out = tmp_path / f"disk_{antialias}.png"
        extra = ["--antialias", antialias] if antialias else []
        info = cli_json("photoelastic", "--preset", "disk", "--size", "64", "--supersample", "1", *extra,
                        "-o", str(out))
        assert [info["width"], info["height"]] == [w, h]
        pw, ph, rgb = ffi.new("int *"), ffi.new("int *"), ffi.new("unsigned char **")
        msg = ffi.new("char[]", 256)
        assert lib.biref_png_read_rgb8(str(out).encode(), pw, ph, rgb, msg, 256) == lib.BIREF_OK
        png = np.frombuffer(ffi.buffer(rgb[0], w * h * 3), dtype=np.uint8).reshape(h, w, 3).astype(int)
        opts = {"antialias": antialias} if antialias else {}
        enc = biref.photoelastic(preset="disk", size=64, supersample=1, space="srgb", **opts)
        return png, np.clip(np.round(np.clip(enc, 0, 1) * 255), 0, 255).astype(int)

    # The default (prefiltered) picture and the point-sampled one (--antialias none) each match
    # the CLI's, and they differ from each other.
    png, mine = cli_and_mine()
    assert np.abs(mine - png).max() <= 1
    png_none, mine_none = cli_and_mine("none")
    assert np.abs(mine_none - png_none).max() <= 1
    assert np.abs(mine_none - mine).max() > 1
    with pytest.raises(ValueError):
        biref.photoelastic(preset="disk", size=8, antialias="box")
    # Dark-field circular polariscope: no light around the disk; fringes inside.
    assert img[0, 0].max() < 1e-6
    assert img[h // 2, w // 2].max() > 0.05


def test_photoelastic_dispersion_alpha():
    base = biref.photoelastic(preset="beam", size=48)
    np.testing.assert_array_equal(biref.photoelastic(preset="beam", size=48, dispersion_alpha=0.0), base)
    moved = biref.photoelastic(preset="beam", size=48, dispersion_alpha=0.4)
    assert np.abs(moved - base).max() > 0.05
    with pytest.raises(ValueError, match="alpha"):
        biref.photoelastic(preset="beam", size=48, dispersion_alpha=5)


def test_photoelastic_mono_and_errors():
    img = biref.photoelastic(preset="hole", light="mono", lambda_nm=589, size=40, polariscope="plane", field="light")
    assert np.allclose(img[..., 0], img[..., 1], atol=1e-3)  # grey levels
    with pytest.raises(ValueError, match="material"):
        biref.photoelastic(material="unobtainium")
    with pytest.raises(ValueError, match="preset"):
        biref.photoelastic(preset="gear")


@needs_cli
def test_material_matches_cli():
    ref = cli_json("material", "calcite", "--lambda-nm", "589.3")
    assert_same(biref.material("calcite", lambda_nm=589.3), ref, 1e-15)
    names = [m["name"] for m in biref.materials()]
    assert "rutile" in names and "pmma" in names


@needs_cli
def test_slab_with_a_material_matches_cli():
    kw = dict(material="linbo3", axis=(0.3, 0.9, 0.2), thickness_um=20, theta_deg=40, lambda_nm=450)
    ref = cli_json("slab", "--material", "linbo3", "--axis", "0.3,0.9,0.2", "--thickness-um", "20", "--theta-deg",
                   "40", "--lambda-nm", "450")
    assert_same(biref.slab(**kw), ref, 1e-13)
    # Vectorised over the wavelength: each element is the slab of that wavelength's indices.
    lam = np.array([420.0, 450.0, 600.0])
    vec = biref.slab(**dict(kw, lambda_nm=lam, method="tmm"))
    assert abs(vec["T"]["s"]["p"][1] - ref["T"]["s"]["p"]) < 1e-9


@needs_cli
def test_spectrum_with_a_material_matches_cli():
    with pytest.warns(UserWarning, match="extrapolated"):
        got = biref.spectrum(material="rutile", axis=(0.3, 0.9, 0.2), thickness_um=10, theta_deg=30,
                             method="numeric", samples=96, polarizer="linear:45", analyzer="linear:-45")
    ref = cli_json("spectrum", "--material", "rutile", "--axis", "0.3,0.9,0.2", "--thickness-um", "10",
                   "--theta-deg", "30", "--method", "numeric", "--spectral-samples", "96", "--polarizer", "linear:45",
                   "--analyzer", "linear:-45")
    assert_same(got, ref, 1e-12)
    # The closed-form methods take dispersion too (linearised per band, or exact where not).
    got = biref.spectrum(material="calcite", axis=(0.5, 0.7071, 0.5), thickness_um=50, theta_deg=[10.0, 30.0],
                         method="expansion", polarization="s", analyzer="p")
    ref = cli_json("spectrum", "--material", "calcite", "--axis", "0.5,0.7071,0.5", "--thickness-um", "50",
                   "--theta-deg", "30", "--method", "expansion", "--polarization", "s", "--analyzer", "p")
    assert np.allclose(got["mixed"]["T_xyz"][1], ref["mixed"]["T_xyz"], atol=1e-12)
    with pytest.raises(ValueError, match="unknown material"):
        biref.slab(material="unobtainium", axis=(0, 0, 1), thickness_um=10)
    with pytest.raises(ValueError, match="eta_o"):
        biref.slab(eta_o=1.5, material="calcite", axis=(0, 0, 1), thickness_um=10)


# The bindings refuse what the command line refuses, each with one message (the library's where
# the library checks): (photoelastic arguments, text of the message, the command line's options).
GRID = os.path.join(ROOT, "examples", "photoelastic", "gradient.csv")
PE_REFUSALS = [
    (dict(preset="disk", stress_grid=GRID), "preset and stress_grid exclude each other",
     ["--preset", "disk", "--stress-grid", GRID]),
    (dict(preset="disk", stress_MPa=5.0), "stress_MPa does not apply to disk", ["--preset", "disk", "--stress-MPa", "5"]),
    (dict(stress_grid=GRID, radius_mm=3.0), "radius_mm does not apply to stress_grid",
     ["--stress-grid", GRID, "--radius-mm", "3"]),
    (dict(light="mono", lambda_nm=np.inf), "wavelength", ["--light", "mono", "--lambda-nm", "inf"]),
    (dict(light="mono", lambda_nm=100.0), "wavelength", ["--light", "mono", "--lambda-nm", "100"]),
    (dict(lambda_nm=600.0), "lambda_nm needs light 'mono'", ["--lambda-nm", "600"]),
    (dict(supersample=2.5), "supersample: expected an integer", ["--supersample", "2.5"]),
    (dict(supersample=65), "supersampl", ["--supersample", "65"]),
    (dict(threads=10000), "threads", ["--threads", "10000"]),
    (dict(size=9000), "size", ["--size", "9000"]),
    (dict(tilt_deg=85.0), "tilt", ["--tilt-deg", "85"]),
    (dict(eta_i=9.0), "eta_i", ["--eta-i", "9"]),
    (dict(exposure=1e31), "exposure", ["--exposure", "1e31"]),
]


@pytest.mark.parametrize("kwargs, text, args", PE_REFUSALS, ids=[c[1][:30] for c in PE_REFUSALS])
def test_photoelastic_refuses_what_the_command_line_refuses(kwargs, text, args):
    call = dict(size=16, supersample=1)
    call.update(kwargs)
    with pytest.raises(ValueError, match=text):
        biref.photoelastic(**call)
    if CLI:
        r = subprocess.run([CLI, "photoelastic", *args, "--profile", "0,0,1,1"], capture_output=True, text=True)
        assert r.returncode == 2 and len(r.stderr.splitlines()) == 1, (args, r.stderr)


def test_integer_arguments_are_not_truncated():
    for call in (lambda: biref.spectrum(**SLAB, thickness_um=20, method="numeric", samples=2.5),
                 lambda: biref.render(os.path.join(ROOT, "examples", "default.json"), width=8, height=8.0),
                 lambda: biref.render(os.path.join(ROOT, "examples", "default.json"), width=8, height=8, threads=1.5)):
        with pytest.raises(ValueError, match="expected an integer"):
            call()
    assert biref.render(os.path.join(ROOT, "examples", "default.json"), width=np.int64(8), height=8).shape == (8, 8, 3)
    with pytest.raises(ValueError, match="threads"):
        biref.render(os.path.join(ROOT, "examples", "default.json"), width=8, height=8, threads=10000)


@needs_cli
def test_photoelastic_meshio_mesh_matches_cli_fea(tmp_path):
    """A meshio mesh (here the plate with a hole's .vtu) renders as `biref photoelastic --fea`
    renders the file: the same picture, the hole empty without a boundary."""
    meshio = pytest.importorskip("meshio")
    from biref._native import ffi, lib
    vtu = os.path.join(ROOT, "examples", "photoelastic", "fea", "plate_hole.vtu")
    m = meshio.read(vtu)
    args = dict(thickness_mm=3, light="mono", lambda_nm=589, size=48, supersample=1, antialias="none")
    enc = biref.photoelastic(mesh=m, space="srgb", **args)
    out = tmp_path / "plate.png"
    info = cli_json("photoelastic", "--fea", vtu, "--thickness-mm", "3", "--light", "mono", "--size", "48",
                    "--supersample", "1", "--antialias", "none", "-o", str(out))
    h, w, _ = enc.shape
    assert [info["width"], info["height"]] == [w, h]
    pw, ph, rgb = ffi.new("int *"), ffi.new("int *"), ffi.new("unsigned char **")
    msg = ffi.new("char[]", 256)
    assert lib.biref_png_read_rgb8(str(out).encode(), pw, ph, rgb, msg, 256) == lib.BIREF_OK
    png = np.frombuffer(ffi.buffer(rgb[0], w * h * 3), dtype=np.uint8).reshape(h, w, 3).astype(int)
    mine = np.clip(np.round(np.clip(enc, 0, 1) * 255), 0, 255).astype(int)
    assert np.abs(mine - png).max() <= 1
    assert mine[h // 2, w // 2].max() == 0  # the hole: the dark field's background
    stressed = biref.photoelastic(mesh=m, stress="S", **args)
    assert np.array_equal(stressed, biref.photoelastic(mesh=m, **args))
    with pytest.raises(ValueError, match="no point-data array"):
        biref.photoelastic(mesh=m, stress="sigma_vm", **args)
    solid = meshio.Mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]]), [("tetra", np.array([[0, 1, 2, 3]]))],
                        point_data={"S": np.zeros((4, 6))})
    with pytest.raises(ValueError, match="plane-stress"):
        biref.photoelastic(mesh=solid, **args)
