"""Loading libbiref and its declarations through cffi (ABI mode: no compiler needed at run time).

The library is looked up in this order: $BIREF_LIBRARY (a path to libbiref.so); the copy the
CMake install put this package next to; the system's library search (ldconfig); pkg-config's
libdir. The C declarations (biref_cdef.h, generated from the public headers by the build) come
from $BIREF_CDEF, else from beside the library: <libdir>/../share/biref/ (installed) or
<libdir>/python/ (build tree).
"""
import ctypes.util
import os
import subprocess

import cffi

ffi = cffi.FFI()
_HERE = os.path.dirname(os.path.abspath(__file__))


def _library_candidates():
    env = os.environ.get("BIREF_LIBRARY")
    if env:
        yield env
        return
    try:
        from . import _install_paths  # written by the CMake install
        yield os.path.normpath(os.path.join(_HERE, _install_paths.LIBRARY))
    except ImportError:
        pass
    found = ctypes.util.find_library("biref")
    if found:
        yield found
    try:
        libdir = subprocess.run(["pkg-config", "--variable=libdir", "biref"], capture_output=True, text=True,
                                check=True).stdout.strip()
        if libdir:
            yield os.path.join(libdir, "libbiref.so")
    except (OSError, subprocess.CalledProcessError):
        pass


def _cdef_candidates(libpath):
    env = os.environ.get("BIREF_CDEF")
    if env:
        yield env
        return
    try:
        from . import _install_paths
        yield os.path.normpath(os.path.join(_HERE, _install_paths.CDEF))
    except ImportError:
        pass
    libdir = os.path.dirname(os.path.realpath(libpath)) if os.path.dirname(libpath) else None
    if libdir:
        yield os.path.join(libdir, os.pardir, "share", "biref", "biref_cdef.h")
        yield os.path.join(libdir, "python", "biref_cdef.h")
    for prefix in ("/usr/local", "/usr"):
        yield os.path.join(prefix, "share", "biref", "biref_cdef.h")


def _load():
    tried = []
    for path in _library_candidates():
        try:
            lib = ffi.dlopen(path)
        except OSError as e:
            tried.append(f"{path}: {e}")
            continue
        for cdef in _cdef_candidates(path):
            if os.path.isfile(cdef):
                with open(cdef, encoding="utf-8") as f:
                    ffi.cdef(f.read())
                return lib, path
            tried.append(f"{cdef}: no such file")
        raise ImportError("biref: found the library at %s but not its declarations (biref_cdef.h); "
                          "set BIREF_CDEF. Tried:\n  %s" % (path, "\n  ".join(tried)))
    raise ImportError("biref: libbiref.so not found; install biref (cmake --install) or set BIREF_LIBRARY. "
                      "Tried:\n  %s" % "\n  ".join(tried or ["(nothing found)"]))


lib, library_path = _load()
