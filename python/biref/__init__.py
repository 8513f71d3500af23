"""biref: birefringence-induced iridescence of uniaxial slabs, from Python.

A thin layer over the C library libbiref (through cffi). Names and units follow the command
line: ``biref.slab(...)`` takes the options of ``biref slab`` (``--eta-o`` -> ``eta_o``,
``--thickness-mm`` -> ``thickness_mm``, angles in degrees, wavelengths in nm) and returns the
fields of ``biref slab --json``; likewise ``spectrum``, ``render`` and ``photoelastic``.

Frame (docs/CONVENTIONS.md): slab surface y = 0, slab below, light in the YZ plane; the optic
axis is given in that frame and normalised by biref.
"""
import json as _json
import math as _math
import operator as _operator
import os as _os
import warnings as _warnings

import numpy as _np

from ._native import ffi as _ffi, lib as _lib, library_path

__all__ = ["slab", "stack", "stack_spectrum", "spectrum", "material", "materials", "render", "photoelastic", "BirefError",
           "library_path", "__version__"]
__version__ = "0.1.0"

_SP = ("s", "p")
_MSG = 512  # BIREF_MSG_SIZE: the library writes one line of at most this into a caller-owned buffer


class BirefError(RuntimeError):
    """The library refused a computation for a reason other than bad input (numerical failure)."""


def _status(s):
    return _ffi.string(_lib.biref_status_string(s)).decode()


def _check(s, what):
    if s != _lib.BIREF_OK:
        if s == _lib.BIREF_ERR_INVALID:
            raise ValueError(f"{what}: {_status(s)}")
        raise BirefError(f"{what}: {_status(s)}")


def _msg_error(s, msg, exc=ValueError):
    text = _ffi.string(msg).decode(errors="replace") or _status(s)
    raise (exc if s == _lib.BIREF_ERR_INVALID else BirefError)(text)


def _call(what, fn, *args):
    """Calls a library function that takes a message buffer last; raises with its reason."""
    msg = _ffi.new("char[]", _MSG)
    s = fn(*args, msg, _MSG)
    if s != _lib.BIREF_OK:
        text = _ffi.string(msg).decode(errors="replace") or _status(s)
        raise (ValueError if s == _lib.BIREF_ERR_INVALID else BirefError)(f"{what}: {text}")


def _int(name, v):
    """An integer argument (Python or numpy), as the command line's integer options: 2.5 or 2.0 is
    refused, not truncated."""
    try:
        return _operator.index(v)
    except TypeError:
        raise ValueError(f"{name}: expected an integer, got {v!r}") from None


def _thickness_nm(thickness_mm, thickness_um, thickness_nm):
    given = [(v, f) for v, f in ((thickness_mm, 1e6), (thickness_um, 1e3), (thickness_nm, 1.0)) if v is not None]
    if not given:
        raise ValueError("missing thickness_um (or thickness_mm, thickness_nm)")
    if len(given) > 1:
        raise ValueError("thickness given twice (use one of thickness_mm, thickness_um, thickness_nm)")
    return float(given[0][0]) * given[0][1]


def _make_slab(eta_o, eta_e, axis, thickness_mm, thickness_um, thickness_nm, eta_i):
    """A checked biref_slab with its axis normalised, as the CLI builds it."""
    a = [float(x) for x in axis]
    if len(a) != 3:
        raise ValueError("axis: expected 3 numbers")
    slab = _ffi.new("biref_slab *")
    slab.eta_o, slab.eta_e, slab.eta_i = float(eta_o), float(eta_e), float(eta_i)
    slab.axis = a
    slab.thickness_nm = _thickness_nm(thickness_mm, thickness_um, thickness_nm)
    msg = _ffi.new("char[]", _MSG)
    s = _lib.biref_slab_check(slab, msg, _MSG)
    if s != _lib.BIREF_OK:
        _msg_error(s, msg)
    _lib.biref_axis_normalize(slab.axis, slab.axis)
    return slab


def _material(name, eta_o, eta_e):
    """The named dispersive material (a cdata pointer), or None for constant indices."""
    if name is None:
        if eta_o is None or eta_e is None:
            raise ValueError("missing eta_o/eta_e (or material)")
        return None
    if eta_o is not None or eta_e is not None:
        raise ValueError(f"{'eta_o' if eta_o is not None else 'eta_e'}: the material {name!r} gives the indices")
    m = _lib.biref_material_find(str(name).encode())
    if m == _ffi.NULL:
        raise ValueError(f"material: unknown material {name!r} (biref.materials() names them)")
    return m


def _material_band(m, lo, hi):
    """Refuses an unphysical band (one line), warns about its extrapolated part, as the CLI does;
    returns the material's JSON fields over the band."""
    msg = _ffi.new("char[]", _MSG)
    s = _lib.biref_material_check_band(m, lo, hi, msg, _MSG)
    if s != _lib.BIREF_OK:
        _msg_error(s, msg)
    info = _ffi.new("biref_material_info *")
    _lib.biref_material_get_info(m, info)
    ex = _ffi.new("double[2][2]")
    n = _lib.biref_material_extrapolated(m, lo, hi, ex)
    name = _ffi.string(info.name).decode()
    for i in range(n):
        _warnings.warn(f"{name}: {ex[i][0]:g}-{ex[i][1]:g} nm is outside the valid range "
                       f"{info.range_nm[0]:g}-{info.range_nm[1]:g} nm (extrapolated)", stacklevel=3)
    return {"name": name, "source": _ffi.string(info.source).decode(),
            "range_nm": [info.range_nm[0], info.range_nm[1]] if _math.isfinite(info.range_nm[1]) else None,
            "extrapolated_nm": [[ex[i][0], ex[i][1]] for i in range(n)]}


def _slab_at(m, geometry, lambda_nm):
    """The slab of material m at one wavelength (geometry's axis, thickness, eta_i)."""
    out = _ffi.new("biref_slab *")
    _check(_lib.biref_material_slab_at(m, geometry, lambda_nm, out), "material")
    return out


def materials():
    """The named dispersive materials: a list of dicts (name, description, isotropic, range_nm,
    source), as ``biref material list --json``."""
    out = []
    info = _ffi.new("biref_material_info *")
    for i in range(_lib.biref_material_catalogue_size()):
        _lib.biref_material_get_info(_lib.biref_material_catalogue(i), info)
        out.append({"name": _ffi.string(info.name).decode(), "description": _ffi.string(info.description).decode(),
                    "isotropic": bool(info.isotropic), "range_nm": [info.range_nm[0], info.range_nm[1]],
                    "source": _ffi.string(info.source).decode()})
    return out


def material(name, lambda_nm=589.3):
    """Indices and group indices (n - lambda dn/dlambda) of a named material at lambda_nm: the
    fields of ``biref material NAME --json``."""
    m = _material(name, None, None)
    lam = float(lambda_nm)
    if not lam > 0:
        raise ValueError(f"lambda_nm: must be positive, got {lam:g}")
    band = _material_band(m, lam, lam)
    n = _ffi.new("double[2]")
    ng = _ffi.new("double[2]")
    _check(_lib.biref_material_indices(m, lam, n, ng), "material")
    return {"name": band["name"], "lambda_nm": lam, "n_o": n[0], "n_e": n[1], "n_o_group": ng[0],
            "n_e_group": ng[1], "source": band["source"], "range_nm": band["range_nm"]}


def _theta_rad(theta_deg):
    t = float(theta_deg) * _math.pi / 180.0
    msg = _ffi.new("char[]", _MSG)
    s = _lib.biref_theta_check(t, msg, _MSG)
    if s != _lib.BIREF_OK:
        raise ValueError("theta_deg: " + _ffi.string(msg).decode())
    return t


def _input(slab, theta_deg, material=None, **extra):
    d = {"material": material, "eta_o": slab.eta_o, "eta_e": slab.eta_e, "axis": list(slab.axis),
         "thickness_nm": slab.thickness_nm, "theta_deg": theta_deg}
    d.update(extra)
    d["eta_i"] = slab.eta_i
    return d


def _sp_matrix(m):
    return {_SP[i]: {_SP[o]: m[i][o] for o in range(2)} for i in range(2)}


def _prepare(slab, theta):
    st = _ffi.new("biref_slab_state *")
    _check(_lib.biref_slab_prepare(slab, theta, st), "slab")
    return st


def _modes(st):
    names = ("o_down", "e_down", "o_up", "e_up")
    m = st.modes
    out = {}
    for i, name in enumerate(names):
        out[name] = {
            "q": [m.q[i].real, m.q[i].imag],
            "E": [[m.E[i][k].real, m.E[i][k].imag] for k in range(3)],
            "poynting": [m.poynting[i][k] for k in range(3)],
            "eta_eff": m.eta_eff[i] if _math.isfinite(m.eta_eff[i]) else None,  # evanescent
        }
    return out


def slab(eta_o=None, eta_e=None, axis=None, thickness_mm=None, thickness_um=None, thickness_nm=None, theta_deg=0.0,
         lambda_nm=550.0, eta_i=1.0, method="closed-form", material=None):
    """Transmission and reflection of a plane wave by the slab: the fields of ``biref slab --json``.

    T and R are power fractions indexed [input s/p][output s/p]; jones_T/jones_R the complex
    amplitudes as [re, im]. theta_deg and lambda_nm may be numpy arrays (broadcast together): the
    leaves of T, R, energy and K are then arrays of the broadcast shape, jones_T/jones_R complex
    arrays, and the per-angle details (K_max, modes) are left out. method: "closed-form" (paper
    eq. 17) or "tmm" (the independent 4x4 transfer matrix). material: a named dispersive material
    (biref.materials()) instead of eta_o/eta_e, its indices taken at each lambda_nm.
    """
    if method not in ("closed-form", "tmm"):
        raise ValueError(f"method: expected closed-form or tmm, got {method!r}")
    if axis is None:
        raise ValueError("missing axis")
    mat = _material(material, eta_o, eta_e)
    sl = _make_slab(1.5 if mat else eta_o, 1.5 if mat else eta_e, axis, thickness_mm, thickness_um, thickness_nm,
                    eta_i)
    if _np.ndim(theta_deg) == 0 and _np.ndim(lambda_nm) == 0:
        lam = float(lambda_nm)
        if not mat:
            return _slab_one(sl, float(theta_deg), lam, method)
        if not lam > 0:
            raise ValueError(f"lambda_nm: must be positive, got {lam:g}")
        band = _material_band(mat, lam, lam)
        return _slab_one(_slab_at(mat, sl, lam), float(theta_deg), lam, method, band)
    th, lam = _np.broadcast_arrays(_np.asarray(theta_deg, dtype=float), _np.asarray(lambda_nm, dtype=float))
    if not _np.all(lam > 0):
        raise ValueError("lambda_nm: must be positive")
    JT = _np.empty(th.shape + (2, 2), dtype=complex)
    JR = _np.empty_like(JT)
    K = _np.empty(th.shape)
    tot = _np.empty(th.shape, dtype=bool)
    T = _ffi.new("biref_jones *")
    R = _ffi.new("biref_jones *")
    states = {}
    band = _material_band(mat, float(lam.min()), float(lam.max())) if mat and lam.size else None
    for idx in _np.ndindex(th.shape):
        t, l = float(th[idx]), float(lam[idx])
        key = (t, l) if mat else t
        st = states.get(key)
        if st is None:
            st = states[key] = _prepare(_slab_at(mat, sl, l) if mat else sl, _theta_rad(t))
        if method == "tmm":
            _check(_lib.biref_slab_jones_tmm(_ffi.addressof(st, "slab"), st.theta, l, T, R), "tmm")
        else:
            _lib.biref_slab_jones_at(st, float(lam[idx]), T, R)
        JT[idx] = [[T.m[i][o] for o in range(2)] for i in range(2)]
        JR[idx] = [[R.m[i][o] for o in range(2)] for i in range(2)]
        K[idx] = st.K
        tot[idx] = bool(st.total_reflection)
    PT, PR = _np.abs(JT) ** 2, _np.abs(JR) ** 2
    return {
        "method": method,
        "input": _input(sl, th, band, lambda_nm=lam) if not mat else
        dict(_input(sl, th, band, lambda_nm=lam), eta_o=None, eta_e=None),  # n(lambda) per element
        "T": _sp_matrix(_np.moveaxis(PT, (-2, -1), (0, 1))),
        "R": _sp_matrix(_np.moveaxis(PR, (-2, -1), (0, 1))),
        "jones_T": _sp_matrix(_np.moveaxis(JT, (-2, -1), (0, 1))),
        "jones_R": _sp_matrix(_np.moveaxis(JR, (-2, -1), (0, 1))),
        "energy": {_SP[i]: PT[..., i, :].sum(-1) + PR[..., i, :].sum(-1) for i in range(2)},
        "K": K,
        "total_reflection": {"any": tot},
    }


def _slab_one(sl, theta_deg, lambda_nm, method, band=None):
    if not lambda_nm > 0:
        raise ValueError(f"lambda_nm: must be positive, got {lambda_nm:g}")
    theta = _theta_rad(theta_deg)
    st = _prepare(sl, theta)
    T = _ffi.new("biref_jones *")
    R = _ffi.new("biref_jones *")
    if method == "tmm":
        _check(_lib.biref_slab_jones_tmm(sl, theta, lambda_nm, T, R), "tmm")
    else:
        _lib.biref_slab_jones_at(st, lambda_nm, T, R)
    PT = _ffi.new("double[2][2]")
    PR = _ffi.new("double[2][2]")
    _lib.biref_jones_intensity(T, PT)
    _lib.biref_jones_intensity(R, PR)
    if not all(_math.isfinite(x) for M in (PT, PR) for row in M for x in row):
        raise BirefError("numerical failure (non-finite result)")
    pt = [[PT[i][o] for o in range(2)] for i in range(2)]
    pr = [[PR[i][o] for o in range(2)] for i in range(2)]
    cj = lambda J: [[[J.m[i][o].real, J.m[i][o].imag] for o in range(2)] for i in range(2)]  # noqa: E731
    return {
        "method": method,
        "input": _input(sl, theta_deg, band, lambda_nm=lambda_nm),
        "T": _sp_matrix(pt),
        "R": _sp_matrix(pr),
        "jones_T": _sp_matrix(cj(T)),
        "jones_R": _sp_matrix(cj(R)),
        "energy": {_SP[i]: pt[i][0] + pt[i][1] + pr[i][0] + pr[i][1] for i in range(2)},
        "K": st.K,
        "K_max": {"o": st.modes.K_max_o, "e": st.modes.K_max_e},
        "total_reflection": {"o": bool(st.modes.evanescent_o), "e": bool(st.modes.evanescent_e),
                             "any": bool(st.total_reflection)},
        "modes": _modes(st),
    }


# --------------------------------------------------------------------------------------------
# Stacks of layers
# --------------------------------------------------------------------------------------------

def _load_stack(stack):
    """A checked biref_stack from a stack file's path or a dict in the file's form."""
    st = _ffi.new("biref_stack *")
    if isinstance(stack, dict):
        text = _json.dumps(stack).encode()
        _call("stack", _lib.biref_stack_parse, text, len(text), st)
    elif isinstance(stack, (str, bytes, _os.PathLike)):
        _call(_os.fsdecode(stack), _lib.biref_stack_load, _os.fsencode(stack), st)
    else:
        raise TypeError("stack: expected a stack file's path or a dict {'eta_i': ..., 'layers': [...]}")
    return st


def _stack_layers(st):
    out = []
    for i in range(st.n_layers):
        l = st.layers[i]
        if l.material != _ffi.NULL:
            info = _ffi.new("biref_material_info *")
            _lib.biref_material_get_info(l.material, info)
            d = {"material": _ffi.string(info.name).decode()}
            if not l.isotropic:
                d["axis"] = list(l.axis)
        elif l.isotropic:
            d = {"eta": l.eta_o}
        else:
            d = {"eta_o": l.eta_o, "eta_e": l.eta_e, "axis": list(l.axis)}
        d["thickness_nm"] = l.thickness_nm
        out.append(d)
    return out


def _stack_check_band(sk, lo, hi):
    """Refuses wavelengths where a dispersive layer's material is unphysical, with its reason."""
    for i in range(sk.n_layers):
        m = sk.layers[i].material
        if m != _ffi.NULL:
            msg = _ffi.new("char[]", 256)
            if _lib.biref_material_check_band(m, lo, hi, msg, 256) != 0:
                raise BirefError(f"stack: layers[{i}]: {_ffi.string(msg).decode()}")


def stack(stack, theta_deg=0.0, lambda_nm=550.0, method="exact"):
    """Transmission and reflection of a plane wave by a stack of layers: the fields of
    ``biref stack FILE --json``. stack: a stack file's path, or a dict in the file's form
    ({"eta_i": 1.0, "layers": [{"eta_o": ..., "eta_e": ..., "azimuth_deg": ..., "thickness_um": ...}]},
    docs/STACKS.md). lambda_nm may be a numpy array: the leaves of T, R and energy are then arrays
    of its shape and jones_T/jones_R complex arrays. method: "exact" or "tmm" (4x4 product).
    """
    if method not in ("exact", "tmm"):
        raise ValueError(f"method: expected exact or tmm, got {method!r}")
    sk = _load_stack(stack)
    theta = _theta_rad(theta_deg)
    lam = _np.asarray(lambda_nm, dtype=float)
    if not _np.all(lam > 0):
        raise ValueError("lambda_nm: must be positive")
    st = _ffi.new("biref_stack_state *")
    _check(_lib.biref_stack_prepare(sk, theta, st), "stack")
    if _lib.biref_stack_dispersive(sk):
        _stack_check_band(sk, float(lam.min()), float(lam.max()))
    T = _ffi.new("biref_jones *")
    R = _ffi.new("biref_jones *")
    JT = _np.empty(lam.shape + (2, 2), dtype=complex)
    JR = _np.empty_like(JT)
    for idx in _np.ndindex(lam.shape):
        if method == "tmm":
            _check(_lib.biref_stack_jones_tmm(sk, theta, float(lam[idx]), T, R), "tmm")
        else:
            _lib.biref_stack_jones_at(st, float(lam[idx]), T, R)
        JT[idx] = [[T.m[i][o] for o in range(2)] for i in range(2)]
        JR[idx] = [[R.m[i][o] for o in range(2)] for i in range(2)]
    if not (_np.all(_np.isfinite(JT)) and _np.all(_np.isfinite(JR))):
        raise BirefError("numerical failure (non-finite result)")
    PT, PR = _np.abs(JT) ** 2, _np.abs(JR) ** 2
    scalar = lam.ndim == 0
    if scalar:
        jones = lambda J: _sp_matrix([[[J[i, o].real, J[i, o].imag] for o in range(2)] for i in range(2)])  # noqa: E731
        power = lambda P: _sp_matrix(P.tolist())  # noqa: E731
    else:
        jones = power = lambda M: _sp_matrix(_np.moveaxis(M, (-2, -1), (0, 1)))  # noqa: E731
    return {
        "method": method,
        "input": {"eta_i": sk.eta_i, "theta_deg": float(theta_deg), "lambda_nm": float(lam) if scalar else lam,
                  "layers": _stack_layers(sk)},
        "T": power(PT),
        "R": power(PR),
        "jones_T": jones(JT),
        "jones_R": jones(JR),
        "energy": {_SP[i]: PT[..., i, :].sum(-1) + PR[..., i, :].sum(-1) for i in range(2)},
        "K": st.K,
        "total_reflection": {"any": bool(st.evanescent), "layers": st.evanescent},
    }


# --------------------------------------------------------------------------------------------
# Spectra
# --------------------------------------------------------------------------------------------

_METHODS = ("analytic", "analytic-pairs", "numeric", "ground-truth", "expansion")


def _method(name):
    m = _ffi.new("biref_method *")
    if not isinstance(name, str) or _lib.biref_method_from_name(name.encode(), m) != _lib.BIREF_OK:
        raise ValueError(f"method: expected one of {', '.join(_METHODS)}, got {name!r}")
    return m[0]


_PROCESS_SP = []


def _default_sp():
    """The process's spectral context (default band and colour-matching functions), created at the
    first use and shared by every render, as one context serves a whole process."""
    if not _PROCESS_SP:
        spp = _ffi.new("biref_spectral **")
        _call("spectral tables", _lib.biref_spectral_create, _ffi.NULL, spp)
        _PROCESS_SP.append(_ffi.gc(spp[0], _lib.biref_spectral_destroy))
    return _PROCESS_SP[0]


def _polarizer(what, text):
    """The library's parser of the polarizer text form ("linear:DEG", "circular:+1|-1")."""
    p = _ffi.new("biref_polarizer *")
    _call(what, _lib.biref_polarizer_parse, str(text).encode(), p)
    return p


def _light(polarization, polarizer, stokes, analyzer):
    """(w_in, mask, stokes or None, P or None, names): the paper's s/p model, or a general state."""
    w_in, mask = [0.5, 0.5], [1.0, 1.0]
    S, P = None, None
    if polarizer is not None and stokes is not None:
        raise ValueError("polarizer and stokes exclude each other")
    if polarizer is not None:
        S = list(_polarizer("polarizer", polarizer).stokes)
        pol_name = str(polarizer)
    elif stokes is not None:
        S = [float(x) for x in stokes]
        if len(S) != 4:
            raise ValueError("stokes: expected S0, S1, S2, S3")
        pol_name = "stokes:" + ",".join(f"{x:g}" for x in S)
    else:
        if isinstance(polarization, str):
            table = {"s": [1.0, 0.0], "p": [0.0, 1.0], "unpolarized": [0.5, 0.5]}
            if polarization not in table:
                raise ValueError(f"polarization: expected s, p, unpolarized or (S, P) weights, got {polarization!r}")
            w_in = table[polarization]
        else:
            w = [float(x) for x in polarization]
            if len(w) != 2 or min(w) < 0 or not sum(w) > 0:
                raise ValueError("polarization: weights must be two non-negative numbers, not both zero")
            w_in = [w[0] / sum(w), w[1] / sum(w)]
        pol_name = None
    an = str(analyzer)
    if an.startswith(("linear:", "circular:")):
        P = _ffi.new("biref_complex[2][2]")
        _ffi.memmove(P, _polarizer("analyzer", an).analyzer, _ffi.sizeof(P))
    elif an in ("none", "s", "p"):
        mask = {"none": [1.0, 1.0], "s": [1.0, 0.0], "p": [0.0, 1.0]}[an]
    else:
        raise ValueError(f"analyzer: expected none, s, p, linear:DEG or circular:+1|-1, got {analyzer!r}")
    return w_in, mask, S, P, pol_name, an


def _material_integrator(sp, m, n_samples, eopts):
    o = _ffi.new("biref_integrator_options *")
    _lib.biref_integrator_options_default(o)
    o.method = m
    if m == _lib.BIREF_METHOD_NUMERIC:
        o.samples = n_samples
    o.expansion = eopts[0]
    itp = _ffi.new("biref_integrator **")
    _call("integrator", _lib.biref_integrator_create, sp, o, itp)
    return _ffi.gc(itp[0], _lib.biref_integrator_destroy)


def _dispersive_one(it, mat, sl, theta, light, spec, mixed, orders, idx):
    """One angle of a dispersive slab through the integrator (material.h): the numeric methods
    sample n(lambda), the closed-form ones linearise each band's phases (or integrate exactly)."""
    _check(_lib.biref_integrate_material_spectrum(it, mat, sl, theta, spec), "integration")
    out = _ffi.new("biref_integration *")
    _check(_lib.biref_integrate_material(it, mat, sl, theta, _lib.BIREF_SIDE_BOTH, light, out), "integration")
    mixed[idx + (0,)] = list(out.T)
    mixed[idx + (1,)] = list(out.R)
    orders[idx + (0,)], orders[idx + (1,)] = out.order_used[0], out.order_used[1]


def spectrum(eta_o=None, eta_e=None, axis=None, thickness_mm=None, thickness_um=None, thickness_nm=None,
             theta_deg=0.0, eta_i=1.0, method="analytic", samples=None, order=None, tolerance=None, cmf="cie1931",
             range_nm=(380.0, 700.0), polarization="unpolarized", polarizer=None, stokes=None, analyzer="none",
             material=None):
    """Colour of the light transmitted and reflected by the slab: the fields of ``biref spectrum --json``.

    T and R are band-normalised XYZ ([input s/p][output s/p] -> [X, Y, Z]); "mixed" holds the colour
    for the incident light (polarization s/p/unpolarized/(S, P) weights, or a fully polarised
    ``polarizer`` "linear:DEG" / "circular:+1", or ``stokes``) seen through ``analyzer``. General
    states (polarizer, stokes, linear/circular analyzers) need method numeric, ground-truth or
    expansion, as on the command line. theta_deg may be a numpy array: every leaf then gains its
    shape in front of the colour axis. material: a named dispersive material (biref.materials())
    instead of eta_o/eta_e, its indices evaluated at every sample (methods numeric and ground-truth).
    """
    m = _method(method)
    if axis is None:
        raise ValueError("missing axis")
    mat = _material(material, eta_o, eta_e)
    if samples is not None and m != _lib.BIREF_METHOD_NUMERIC:
        raise ValueError(f"samples: only valid with method numeric (method is {method})")
    if (order is not None or tolerance is not None) and m != _lib.BIREF_METHOD_EXPANSION:
        raise ValueError(f"{'order' if order is not None else 'tolerance'}: only valid with method expansion")
    if order is not None and tolerance is not None:
        raise ValueError("order and tolerance exclude each other")
    w_in, mask, S, P, pol_name, an_name = _light(polarization, polarizer, stokes, analyzer)
    general_in, general_an = S is not None, P is not None
    general = general_in or general_an
    if S is None:
        S = [1.0, w_in[0] - w_in[1], 0.0, 0.0]
    if P is None:
        P = _ffi.new("biref_complex[2][2]")
        P[0][0], P[1][1] = mask
    C = _ffi.new("biref_complex[2][2]")
    _check(_lib.biref_stokes_to_coherency(S, C), "stokes: not a physical Stokes vector "
                                                 "(need S0 >= 0 and S1^2+S2^2+S3^2 <= S0^2)")
    eopts = _ffi.new("biref_expansion_opts *")
    _lib.biref_expansion_opts_default(eopts)
    if order is not None:
        if not 0 <= _int("order", order) <= 8:
            raise ValueError("order: must be 0-8")
        eopts.order = _int("order", order)
    if tolerance is not None:
        if not 0 < float(tolerance) < 1:
            raise ValueError("tolerance: must be in (0, 1)")
        eopts.tolerance = float(tolerance)
    n_samples = (_int("samples", samples) if samples is not None else 64) if m == _lib.BIREF_METHOD_NUMERIC else \
        16384 if m == _lib.BIREF_METHOD_GROUND_TRUTH else 0
    if m == _lib.BIREF_METHOD_NUMERIC and not 1 <= n_samples <= 65536:
        raise ValueError("samples: must be between 1 and 65536")

    sl = _make_slab(1.5 if mat else eta_o, 1.5 if mat else eta_e, axis, thickness_mm, thickness_um, thickness_nm,
                    eta_i)
    cfg = _ffi.new("biref_spectral_config *")
    _lib.biref_spectral_config_default(cfg)
    kind = _ffi.new("biref_cmf_kind *")
    if _lib.biref_cmf_kind_from_name(str(cmf).encode(), kind) != _lib.BIREF_OK:
        raise ValueError(f"cmf: expected cie1931 or wyman2013, got {cmf!r}")
    cfg.cmf = kind[0]
    cfg.lambda_min_nm, cfg.lambda_max_nm = (float(x) for x in range_nm)
    spp = _ffi.new("biref_spectral **")
    _call("range_nm", _lib.biref_spectral_create, cfg, spp)
    sp = _ffi.gc(spp[0], _lib.biref_spectral_destroy)
    plan = None
    if n_samples:
        pp = _ffi.new("biref_numeric_plan **")
        _call("numeric plan", _lib.biref_numeric_plan_create, sp, n_samples, pp)
        plan = _ffi.gc(pp[0], _lib.biref_numeric_plan_destroy)

    integ = None
    analytic = m in (_lib.BIREF_METHOD_ANALYTIC, _lib.BIREF_METHOD_ANALYTIC_PAIRS)
    if general and analytic:
        # Any other light: the analytic method's general terms, through the integrator.
        io = _ffi.new("biref_integrator_options *")
        _lib.biref_integrator_options_default(io)
        io.method = m
        ip = _ffi.new("biref_integrator **")
        _call("integrator", _lib.biref_integrator_create, sp, io, ip)
        integ = _ffi.gc(ip[0], _lib.biref_integrator_destroy)
        light = _ffi.new("biref_light *")
        _lib.biref_light_coherency(C, light)
        _lib.biref_light_set_analyzer(light, P)
        res = _ffi.new("biref_integration *")
    band = _material_band(mat, cfg.lambda_min_nm, cfg.lambda_max_nm) if mat else None
    if mat:
        it = _material_integrator(sp, m, n_samples, eopts)
        light = _ffi.new("biref_light *")
        if general:  # as the command line: the coherency and the analyzer (diag(mask) unless given)
            _lib.biref_light_coherency(C, light)
            _lib.biref_light_set_analyzer(light, P)
        else:
            _check(_lib.biref_light_sp(w_in, mask, light), "light")
    thetas = _np.asarray(theta_deg, dtype=float)
    spec = _ffi.new("biref_spectrum *")
    T_all = _np.empty(thetas.shape + (2, 2, 3))
    R_all = _np.empty_like(T_all)
    mixed = _np.empty(thetas.shape + (2, 3))
    tot = _np.empty(thetas.shape, dtype=bool)
    xyz = _ffi.new("double[3]")
    order_used = _ffi.new("int *")
    orders = _np.full(thetas.shape + (2,), -1, dtype=int)
    for idx in _np.ndindex(thetas.shape):
        if mat:
            _dispersive_one(it, mat, sl, _theta_rad(thetas[idx]), light, spec, mixed, orders, idx)
            T_all[idx] = _np.array(_ffi.unpack(_ffi.cast("double *", spec.T), 12)).reshape(2, 2, 3)
            R_all[idx] = _np.array(_ffi.unpack(_ffi.cast("double *", spec.R), 12)).reshape(2, 2, 3)
            continue
        st = _prepare(sl, _theta_rad(thetas[idx]))
        tot[idx] = bool(st.total_reflection)
        if plan is not None:
            _lib.biref_spectrum_numeric(plan, st, spec)
        elif m == _lib.BIREF_METHOD_EXPANSION:
            _check(_lib.biref_spectrum_expansion(sp, st, eopts, spec), "expansion")
        elif m == _lib.BIREF_METHOD_ANALYTIC_PAIRS:
            _lib.biref_spectrum_analytic_pairs(sp, st, spec)
        else:
            _lib.biref_spectrum_analytic(sp, st, spec)
        T_all[idx] = _np.array(_ffi.unpack(_ffi.cast("double *", spec.T), 12)).reshape(2, 2, 3)
        R_all[idx] = _np.array(_ffi.unpack(_ffi.cast("double *", spec.R), 12)).reshape(2, 2, 3)
        for w in range(2):
            if general and plan is not None:
                _lib.biref_spectrum_numeric_polarized(plan, st, w, C, P, xyz)
            elif m == _lib.BIREF_METHOD_EXPANSION:
                _check(_lib.biref_spectrum_expansion_polarized(sp, st, w, C, P, eopts, xyz, order_used), "expansion")
                orders[idx + (w,)] = order_used[0]
            elif integ is not None:
                _check(_lib.biref_integrate(integ, st, 2 if w else 1, light, res), "analytic")
                xyz = res.R if w else res.T
            else:
                _lib.biref_spectrum_mix(spec.R if w else spec.T, w_in, mask, xyz)
            mixed[idx + (w,)] = list(xyz)
    if not (_np.all(_np.isfinite(T_all)) and _np.all(_np.isfinite(R_all)) and _np.all(_np.isfinite(mixed))):
        raise BirefError("numerical failure (non-finite result)")
    srgb = _np.empty_like(mixed)
    rgb = _ffi.new("double[3]")
    for idx in _np.ndindex(mixed.shape[:-1]):
        _lib.biref_xyz_to_srgb(list(mixed[idx]), rgb)
        srgb[idx] = list(rgb)

    scalar = thetas.ndim == 0

    def leaf(a):
        return a.tolist() if scalar else a

    def pairs(A):
        return {_SP[i]: {_SP[o]: leaf(A[..., i, o, :]) for o in range(2)} for i in range(2)}

    pol = {"s": w_in[0], "p": w_in[1], "stokes": S} if not general_in else {"state": pol_name, "stokes": S}
    result = {
        "method": _ffi.string(_lib.biref_method_name(m)).decode(),
        "samples": n_samples or None,
        "cmf": str(cmf),
        "range_nm": [cfg.lambda_min_nm, cfg.lambda_max_nm],
        "input": _input(sl, float(thetas) if scalar else thetas, band) if not mat else
        dict(_input(sl, float(thetas) if scalar else thetas, band), eta_o=None, eta_e=None),
        "total_reflection": None if mat else bool(tot) if scalar else tot,
        "T": pairs(T_all),
        "R": pairs(R_all),
        "mixed": {
            "polarization": pol,
            "analyzer": an_name,
            "T_xyz": leaf(mixed[..., 0, :]),
            "R_xyz": leaf(mixed[..., 1, :]),
            "T_srgb": leaf(srgb[..., 0, :]),
            "R_srgb": leaf(srgb[..., 1, :]),
            "srgb_note": "encoded sRGB (IEC 61966-2-1), white E -> (1,1,1), not clamped",
        },
    }
    if m == _lib.BIREF_METHOD_EXPANSION:
        # The pair order the adaptive (or fixed) expansion used for the mixed colours.
        result["expansion_order"] = {"T": leaf(orders[..., 0]), "R": leaf(orders[..., 1])}
    return result


def stack_spectrum(stack, theta_deg=0.0, method="expansion", samples=None, tolerance=None,
                   polarization="unpolarized", polarizer=None, stokes=None, analyzer="none"):
    """Colours of a stack of layers: the fields of ``biref spectrum --stack FILE --json``. stack: a
    stack file's path or a dict in the file's form; method: expansion (default; falls back to
    adaptive numeric integration, reported under "expansion"), numeric or ground-truth. The light
    options are those of ``spectrum``.
    """
    sk = _load_stack(stack)
    theta = _theta_rad(theta_deg)
    m = _method(method)
    opts = _ffi.new("biref_stack_spectrum_opts *")
    _lib.biref_stack_spectrum_opts_default(opts)
    opts.method = m
    if samples is not None:
        if m != _lib.BIREF_METHOD_NUMERIC:
            raise ValueError("samples: only valid with method numeric")
        opts.samples = int(samples)
    if tolerance is not None:
        if m != _lib.BIREF_METHOD_EXPANSION:
            raise ValueError("tolerance: only valid with method expansion")
        opts.tolerance = float(tolerance)
    w_in, mask, S, P, pol_name, an_name = _light(polarization, polarizer, stokes, analyzer)
    light = _ffi.new("biref_light *")
    if S is None and P is None:
        _check(_lib.biref_light_sp(w_in, mask, light), "light")
    else:
        _check(_lib.biref_light_stokes(S if S is not None else [1.0, w_in[0] - w_in[1], 0.0, 0.0], light),
               "stokes: not a physical Stokes vector")
        if P is None:
            P = _ffi.new("biref_complex[2][2]")
            P[0][0], P[1][1] = mask
        _lib.biref_light_set_analyzer(light, P)
    st = _ffi.new("biref_stack_state *")
    _check(_lib.biref_stack_prepare(sk, theta, st), "stack")
    spp = _ffi.new("biref_spectral **")
    _call("spectral context", _lib.biref_spectral_create, _ffi.NULL, spp)
    sp = _ffi.gc(spp[0], _lib.biref_spectral_destroy)
    spec = _ffi.new("biref_spectrum *")
    mt, mr = _ffi.new("double[3]"), _ffi.new("double[3]")
    info = _ffi.new("biref_stack_spectrum_info *")
    _call("stack spectrum", _lib.biref_stack_spectrum, sp, st, opts, light, spec, mt, mr, info)
    pairs = lambda X: {_SP[i]: {_SP[o]: list(X[i][o]) for o in range(2)} for i in range(2)}  # noqa: E731
    out = {
        "method": _ffi.string(_lib.biref_method_name(m)).decode(),
        "samples": info.samples or None,
        "input": {"eta_i": sk.eta_i, "theta_deg": float(theta_deg), "layers": _stack_layers(sk)},
        "total_reflection": bool(st.evanescent),
        "T": pairs(spec.T),
        "R": pairs(spec.R),
        "mixed": {"polarization": pol_name, "analyzer": an_name, "T_xyz": list(mt), "R_xyz": list(mr)},
    }
    if m == _lib.BIREF_METHOD_EXPANSION:
        out["expansion"] = {"fallback": bool(info.fallback), "reason": _ffi.string(info.reason).decode(),
                            "bound": info.bound if _math.isfinite(info.bound) else None, "legs": info.legs,
                            "groups": {"T": info.groups[0], "R": info.groups[1]}}
    return out


# --------------------------------------------------------------------------------------------
# Images
# --------------------------------------------------------------------------------------------

def _convert(xyz, n, space):
    """(n*3,) float32 XYZ buffer -> numpy float array in the requested colour space."""
    out = _np.frombuffer(_ffi.buffer(xyz, n * 3 * 4), dtype=_np.float32).astype(_np.float64)
    if space == "xyz":
        return out
    rgb = _ffi.new("float[]", n * 3)
    _lib.biref_xyz_image_to_linear_srgb(xyz, n, rgb)
    lin = _np.frombuffer(_ffi.buffer(rgb, n * 3 * 4), dtype=_np.float32).astype(_np.float64)
    if space == "linear_srgb":
        return lin
    # Encoded sRGB, unclamped (odd extension of the transfer curve, like biref_srgb_encode).
    a = _np.abs(lin)
    enc = _np.where(a <= 0.0031308, 12.92 * a, 1.055 * a ** (1 / 2.4) - 0.055)
    return _np.sign(lin) * enc


_SPACES = ("linear_srgb", "srgb", "xyz")


def render(scene, method="analytic", width=None, height=None, samples=None, order=None, tolerance=None,
           threads=0, space="linear_srgb"):
    """Renders a scene (a path to a scene file or the scene as a dict, docs/SCENES.md) like
    ``biref render``; returns a numpy float array of shape (height, width, 3).

    space: "linear_srgb" (default; white E -> (1, 1, 1), not clamped), "srgb" (encoded, not
    clamped) or "xyz" (band-normalised CIE XYZ). The camera's exposure is applied.
    """
    if space not in _SPACES:
        raise ValueError(f"space: expected one of {', '.join(_SPACES)}, got {space!r}")
    if isinstance(scene, dict):
        text = _json.dumps(scene).encode()
    elif isinstance(scene, (str, bytes, _os.PathLike)):
        with open(scene, "rb") as f:
            text = f.read()
    else:
        raise TypeError("scene: expected a path or a dict")
    sc = _ffi.new("biref_scene *")
    msg = _ffi.new("char[]", _MSG)
    s = _lib.biref_scene_parse(text, len(text), sc, msg, _MSG)
    if s != _lib.BIREF_OK:
        _msg_error(s, msg)
    for name, v in (("width", width), ("height", height)):
        if v is not None:  # the range is the library's (biref_scene_validate), as on the command line
            setattr(sc.camera, name, max(-1, min(_int(name, v), 1 << 30)))
    s = _lib.biref_scene_validate(sc, msg, _MSG)
    if s != _lib.BIREF_OK:
        _msg_error(s, msg)
    opt = _ffi.new("biref_render_options *")
    _lib.biref_render_options_default(opt)
    opt.method = _method(method)
    if samples is not None:
        if opt.method != _lib.BIREF_METHOD_NUMERIC:
            raise ValueError(f"samples: only valid with method numeric (method is {method})")
        opt.samples = _int("samples", samples)
    if order is not None or tolerance is not None:
        if opt.method != _lib.BIREF_METHOD_EXPANSION:
            raise ValueError("order/tolerance: only valid with method expansion")
        if order is not None:
            opt.expansion.order = _int("order", order)
        if tolerance is not None:
            opt.expansion.tolerance = float(tolerance)
    opt.threads = max(-1, min(_int("threads", threads), 1 << 30))
    rp = _ffi.new("biref_renderer **")
    s = _lib.biref_renderer_create(_default_sp(), sc, opt, rp, msg, _MSG)
    if s != _lib.BIREF_OK:
        _msg_error(s, msg)
    r = _ffi.gc(rp[0], _lib.biref_renderer_destroy)
    w, h = _lib.biref_renderer_width(r), _lib.biref_renderer_height(r)
    xyz = _ffi.new("float[]", w * h * 3)
    _check(_lib.biref_render_image(r, xyz, _ffi.NULL, _ffi.NULL, _ffi.NULL), "render")
    return _convert(xyz, w * h, space).reshape(h, w, 3)


_PRESETS = {"disk": 0, "hole": 1, "beam": 2}
# The geometry arguments, their defaults and the presets they apply to (as the command line's).
_GEOMETRY = {"radius_mm": (None, ("disk", "hole")), "load_N": (500.0, ("disk",)), "stress_MPa": (4.0, ("hole",)),
             "width_mm": (60.0, ("hole",)), "height_mm": (None, ("hole",)), "tension_deg": (0.0, ("hole",)),
             "length_mm": (100.0, ("beam",)), "depth_mm": (20.0, ("beam",)), "moment_Nmm": (2000.0, ("beam",))}


_MESHIO_CELLS = {"triangle": 0, "triangle6": 1, "quad": 2, "quad8": 3, "quad9": 4}
_MESHIO_SKIPPED = ("vertex", "line", "line3", "line4")
_TENSORS = ("stress", "S", "sigma", "stresses")
_SCALARS = (("stress_xx", "stress_yy", "stress_xy"), ("sxx", "syy", "sxy"), ("S11", "S22", "S12"), ("sxx", "syy", "txy"))


def _point_array(mesh, name):
    for k, v in mesh.point_data.items():
        if k.lower() == name.lower():
            return _np.asarray(v, dtype=float)
    return None


def _mesh_stress(mesh, stress):
    """The nodal (sxx, syy, txy) as an (n, 3) array from a tensor or three scalars, by name."""
    have = ", ".join(f"{k} ({_np.asarray(v).reshape(len(v), -1).shape[1]})" for k, v in mesh.point_data.items()) or "none"
    if isinstance(stress, (tuple, list)):
        cols = [_point_array(mesh, n) for n in stress]
        if len(cols) != 3 or any(c is None for c in cols):
            raise ValueError(f"stress: expected three point-data arrays of {list(stress)} (point data: {have})")
        return _np.stack([c.reshape(-1) for c in cols], axis=1)
    names = [stress] if stress else list(_TENSORS)
    for n in names:
        t = _point_array(mesh, n)
        if t is None:
            continue
        t = t.reshape(len(t), -1)
        idx = {3: (0, 1, 2), 6: (0, 1, 3), 9: (0, 4, 1)}.get(t.shape[1])
        if idx is None:
            raise ValueError(f"stress: array '{n}' has {t.shape[1]} components; a stress tensor has 3, 6 or 9")
        return t[:, idx]
    if not stress:
        for trio in _SCALARS:
            cols = [_point_array(mesh, n) for n in trio]
            if all(c is not None for c in cols):
                return _np.stack([c.reshape(-1) for c in cols], axis=1)
        for k in mesh.cell_data:
            if k.lower() in [t.lower() for t in _TENSORS]:
                raise ValueError(f"stress: '{k}' is cell data (one value per element); export nodal stresses")
    raise ValueError(f"stress: no point-data array {stress or 'with a usual stress name'} (point data: {have})")


def _mesh_from_meshio(mesh, stress, length_unit, stress_unit):
    """A biref_pe_mesh (garbage-collected) from a meshio mesh: plane cells, nodal stresses."""
    lengths, stresses = {"mm": 1e-3, "m": 1.0}, {"MPa": 1e6, "Pa": 1.0}
    if length_unit not in lengths or stress_unit not in stresses:
        raise ValueError("length_unit: expected mm or m; stress_unit: expected MPa or Pa")
    pts = _np.asarray(mesh.points, dtype=float)
    if pts.ndim != 2 or pts.shape[1] not in (2, 3) or not len(pts):
        raise ValueError("mesh: expected points of 2 or 3 coordinates")
    if pts.shape[1] == 3 and _np.ptp(pts[:, 2]) > 1e-9 * max(1.0, _np.abs(pts[:, :2]).max()):
        raise ValueError("mesh: the points are not in one plane z = const (a shell or a 3-D part); export a "
                         "plane-stress model, or a section in the x-y plane")
    types, conn = [], []
    for block in mesh.cells:
        if block.type in _MESHIO_SKIPPED:
            continue
        if block.type not in _MESHIO_CELLS:
            raise ValueError(f"mesh: {block.type} cells: biref pictures plane stress; export a plane-stress model, "
                             "or a section in the x-y plane")
        data = _np.asarray(block.data, dtype=_np.uint64)
        types += [_MESHIO_CELLS[block.type]] * len(data)
        conn.append(data.reshape(-1))
    if not types:
        raise ValueError("mesh: no plane cells (triangle, triangle6, quad, quad8, quad9)")
    xy = _np.ascontiguousarray(pts[:, :2] * lengths[length_unit])
    st = _np.ascontiguousarray(_mesh_stress(mesh, stress) * stresses[stress_unit])
    if len(st) != len(xy):
        raise ValueError("stress: one value per point expected")
    tp = _np.ascontiguousarray(types, dtype=_np.int32)
    cn = _np.ascontiguousarray(_np.concatenate(conn))
    el = _ffi.new("biref_pe_elements *")
    el.nodes, el.elements = len(xy), len(tp)
    el.xy = _ffi.cast("const double *", _ffi.from_buffer(xy))
    el.stress = _ffi.cast("const double *", _ffi.from_buffer(st))
    el.type = _ffi.cast("const int *", _ffi.from_buffer(tp))
    el.conn = _ffi.cast("const size_t *", _ffi.from_buffer(cn))
    out = _ffi.new("biref_pe_mesh **")
    _call("mesh", _lib.biref_pe_mesh_from_elements, el, out)
    return _ffi.gc(out[0], _lib.biref_pe_mesh_destroy)


def _pe_field(preset, stress_grid, mesh, thickness_mm, geometry, msg, mesh_args):
    """The stress field (and the grid or mesh it keeps alive) of photoelastic()'s specimen."""
    given = [n for n, v in (("preset", preset), ("stress_grid", stress_grid), ("mesh", mesh)) if v is not None]
    if len(given) > 1:
        raise ValueError(f"{given[0]} and {given[1]} exclude each other")
    specimen = "mesh" if mesh is not None else "stress_grid" if stress_grid is not None else "disk" if preset is None else preset
    if specimen not in ("stress_grid", "mesh") and specimen not in _PRESETS:
        raise ValueError(f"preset: expected disk, hole or beam (or stress_grid), got {preset!r}")
    for name, v in geometry.items():
        if v is not None and specimen not in _GEOMETRY[name][1]:
            raise ValueError(f"{name} does not apply to {specimen}")
    g = {name: _GEOMETRY[name][0] if v is None else float(v) for name, v in geometry.items()}
    mm = 1e-3
    fld = _ffi.new("biref_pe_field *")
    grid = None
    h = ((3.0 if specimen == "hole" else 6.0) if thickness_mm is None else float(thickness_mm)) * mm
    if specimen == "mesh":
        grid = _mesh_from_meshio(mesh, *mesh_args)  # kept alive with the field
        s = _lib.biref_pe_field_nodes(fld, grid, h, msg, _MSG)
        if s == _lib.BIREF_OK:
            d = 0.05 * max(fld.frame[1] - fld.frame[0], fld.frame[3] - fld.frame[2])
            fld.frame = [fld.frame[0] - d, fld.frame[1] + d, fld.frame[2] - d, fld.frame[3] + d]
    elif specimen == "stress_grid":
        gp = _ffi.new("biref_pe_grid **")
        s = _lib.biref_pe_grid_load(str(stress_grid).encode(), gp, msg, _MSG)
        if s != _lib.BIREF_OK:
            _msg_error(s, msg)
        grid = _ffi.gc(gp[0], _lib.biref_pe_grid_destroy)
        s = _lib.biref_pe_field_grid(fld, grid, h, msg, _MSG)
    elif specimen == "disk":
        r = 25.0 if g["radius_mm"] is None else g["radius_mm"]
        s = _lib.biref_pe_field_disk(fld, r * mm, h, g["load_N"], msg, _MSG)
    elif specimen == "hole":
        r = 5.0 if g["radius_mm"] is None else g["radius_mm"]
        w = g["width_mm"]
        s = _lib.biref_pe_field_hole(fld, r * mm, w * mm, (w if g["height_mm"] is None else g["height_mm"]) * mm, h,
                                     g["stress_MPa"] * 1e6, g["tension_deg"] * _math.pi / 180.0, msg, _MSG)
    else:
        s = _lib.biref_pe_field_beam(fld, g["length_mm"] * mm, g["depth_mm"] * mm, h, g["moment_Nmm"] * 1e-3, msg, _MSG)
    if s != _lib.BIREF_OK:
        _msg_error(s, msg)
    return fld, grid, h


def photoelastic(preset=None, stress_grid=None, thickness_mm=None, radius_mm=None, load_N=None, stress_MPa=None,
                 width_mm=None, height_mm=None, tension_deg=None, length_mm=None, depth_mm=None, moment_Nmm=None,
                 material="polycarbonate", n0=None, C_brewster=None, dispersion_alpha=None, eta_i=1.0,
                 polariscope="circular",
                 field="dark", polarizer_deg=0.0, light="white", lambda_nm=None, size=512, supersample=2,
                 tilt_deg=0.0, exposure=1.0, threads=0, space="linear_srgb", antialias="prefilter", mesh=None,
                 stress=None, length_unit="mm", stress_unit="MPa"):
    """A stressed plate in a polariscope, like ``biref photoelastic -o``: a numpy float array of
    shape (height, width, 3) whose longer side has ``size`` pixels.

    antialias "prefilter" (default; a normal view averages each sample's fringes over its
    footprint) or "none" (the fringes at the sample points), as ``--antialias``.
    dispersion_alpha: C(λ) = C (546.1 nm / λ)^alpha, as ``--dispersion-alpha`` (default: the
    material's, 0 for every preset: no dispersion of birefringence).

    preset "disk" (the default; radius_mm 25, load_N 500), "hole" (radius_mm 5, width_mm 60,
    height_mm, stress_MPa 4, tension_deg 0) or "beam" (length_mm 100, depth_mm 20, moment_Nmm
    2000); or stress_grid, a CSV file with columns x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa; or mesh, a
    meshio mesh (any format meshio reads) with plane cells (triangle, triangle6, quad, quad8, quad9)
    and nodal stresses, interpolated inside each element as ``biref photoelastic --fea``: stress
    names the point-data tensor (3, 6 or 9 components) or is a tuple of three scalar arrays (sxx,
    syy, txy); by default the names the command line tries. length_unit mm|m, stress_unit MPa|Pa
    (a mesh gets the 5 % margin of --margin-pct). Units, defaults and refusals as on the command
    line: a geometry argument of another specimen, two specimens, lambda_nm (default 589) without
    light "mono" are errors, and the picture's ranges are the library's.
    """
    if space not in _SPACES:
        raise ValueError(f"space: expected one of {', '.join(_SPACES)}, got {space!r}")
    if antialias not in ("prefilter", "none"):
        raise ValueError(f"antialias: expected prefilter or none, got {antialias!r}")
    if lambda_nm is not None and light != "mono":
        raise ValueError("lambda_nm needs light 'mono' (white-light fringe orders are quoted at 550 nm)")
    setup = _ffi.new("biref_pe_setup *")
    if _lib.biref_pe_material_preset(str(material).encode(), _ffi.addressof(setup, "material")) != _lib.BIREF_OK:
        names = [_ffi.string(_lib.biref_pe_material_at(i).name).decode() for i in range(_lib.biref_pe_material_count())]
        raise ValueError(f"material: expected one of {', '.join(names)}, got {material!r}")
    keep = []
    if n0 is not None or C_brewster is not None:
        keep += [_ffi.new("char[]", b"custom"), _ffi.new("char[]", b"user")]
        setup.material.name, setup.material.source = keep
        if n0 is not None:
            setup.material.n0 = float(n0)
        if C_brewster is not None:
            setup.material.C_per_Pa = float(C_brewster) * 1e-12
    if dispersion_alpha is not None:
        setup.material.dispersion_alpha = float(dispersion_alpha)
    msg = _ffi.new("char[]", _MSG)
    s = _lib.biref_pe_material_check(_ffi.addressof(setup, "material"), msg, _MSG)
    if s != _lib.BIREF_OK:
        raise ValueError("material: " + _ffi.string(msg).decode())
    geometry = dict(radius_mm=radius_mm, load_N=load_N, stress_MPa=stress_MPa, width_mm=width_mm, height_mm=height_mm,
                    tension_deg=tension_deg, length_mm=length_mm, depth_mm=depth_mm, moment_Nmm=moment_Nmm)
    fld, grid, h = _pe_field(preset, stress_grid, mesh, thickness_mm, geometry, msg,
                             (stress, length_unit, stress_unit))
    kinds = {"plane": _lib.BIREF_PE_PLANE, "circular": _lib.BIREF_PE_CIRCULAR}
    fields = {"dark": _lib.BIREF_PE_DARK, "light": _lib.BIREF_PE_LIGHT}
    lights = {"white": _lib.BIREF_PE_WHITE, "mono": _lib.BIREF_PE_MONO}
    for name, v, table in (("polariscope", polariscope, kinds), ("field", field, fields), ("light", light, lights)):
        if v not in table:
            raise ValueError(f"{name}: expected {' or '.join(table)}, got {v!r}")
    if not 0 < float(exposure) <= 1e30:  # as --exposure; the rest is checked by the library
        raise ValueError(f"exposure: must be positive and at most 1e30, got {exposure!r}")
    size = _int("size", size)
    if not 1 <= size <= 8192:  # as --size; the picture's own size is the library's check
        raise ValueError(f"size: must be between 1 and 8192, got {size}")
    setup.thickness = h
    setup.eta_i = float(eta_i)
    setup.light = lights[light]
    setup.lambda_nm = 589.0 if lambda_nm is None else float(lambda_nm)
    _lib.biref_pe_polariscope_make(kinds[polariscope], fields[field], float(polarizer_deg) * _math.pi / 180.0,
                                   _ffi.addressof(setup, "pol"))
    io = _ffi.new("biref_pe_image_opts *")
    io.supersample = max(-1, min(_int("supersample", supersample), 1 << 30))
    io.threads = max(-1, min(_int("threads", threads), 1 << 30))
    io.tint = [exposure] * 3
    io.tilt = float(tilt_deg) * _math.pi / 180.0
    fw, fh = fld.frame[1] - fld.frame[0], (fld.frame[3] - fld.frame[2]) * _math.cos(io.tilt)
    io.width = int(size) if fw >= fh else max(1, round(size * fw / fh))
    io.height = max(1, round(size * fh / fw)) if fw >= fh else int(size)
    sp = _default_sp() if light == "white" else _ffi.NULL
    n = io.width * io.height
    xyz = _ffi.new("float[]", n * 3)
    render = _lib.biref_pe_render_prefiltered if antialias == "prefilter" else _lib.biref_pe_render
    _call("photoelastic render", render, setup, sp, fld, io, xyz)
    img = _convert(xyz, n, "xyz")
    if light == "white" and exposure != 1.0:
        img = img * exposure
    if space != "xyz":
        buf = _ffi.new("float[]", n * 3)
        _ffi.buffer(buf)[:] = img.astype(_np.float32).tobytes()
        img = _convert(buf, n, space)
    return img.reshape(io.height, io.width, 3)
