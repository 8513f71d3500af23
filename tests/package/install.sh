#!/usr/bin/env bash
# Installs the built tree into a temporary prefix and uses it as a downstream project would:
# a C program built with pkg-config, a C++ program built with find_package(biref), both run
# against the installed shared library and compared with the installed CLI's `biref slab --json`;
# the installed CLI's commands that read example scenes run from an unrelated directory.
# $1: build directory, $2: source directory.
set -euo pipefail
build=$(cd "$1" && pwd) src=$(cd "$2" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null
libdir=$(dirname "$(find "$prefix" -name 'libbiref.so' | head -n1)")
[ -f "$libdir/pkgconfig/biref.pc" ] || { echo "FAIL: no biref.pc under $libdir" >&2; exit 1; }
for f in biref/biref.h biref/shading.h; do
  [ -f "$prefix/include/$f" ] || { echo "FAIL: $f not installed" >&2; exit 1; }
done

# Reference: the installed CLI, run from a directory without any biref files.
mkdir "$tmp/elsewhere"
cd "$tmp/elsewhere"
"$prefix/bin/biref" slab --eta-o 1.775 --eta-e 1.231 --axis 0.084,0.979,-0.187 --thickness-mm 1.15 \
  --theta-deg 30 --lambda-nm 550 --json >ref.json

# C through pkg-config (the .pc file is relocatable: found through PKG_CONFIG_PATH only).
export PKG_CONFIG_PATH=$libdir/pkgconfig
cc -std=c17 -Wall -Wextra -Werror "$src/examples/c/slab_colors.c" $(pkg-config --cflags --libs biref) \
  -Wl,-rpath,"$libdir" -o slab_colors
ldd ./slab_colors | grep -c "$libdir/libbiref.so" >/dev/null || { echo "FAIL: slab_colors not linked to the installed libbiref.so" >&2; exit 1; }
./slab_colors >c.json

# C++ through find_package(biref) -> biref::biref.
cmake -S "$src/examples/cpp" -B cpp -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_FLAGS="-Wall -Wextra -Werror" >/dev/null
cmake --build cpp >/dev/null
ldd cpp/shade_hit | grep -c "$libdir/libbiref.so" >/dev/null || { echo "FAIL: shade_hit not linked to the installed libbiref.so" >&2; exit 1; }
cpp/shade_hit >cpp.json
# The static archive through the package: its private dependencies come along as link-only.
cmake -S "$src/examples/cpp" -B cpp_static -DCMAKE_PREFIX_PATH="$prefix" -DUSE_STATIC_BIREF=ON \
  -DCMAKE_CXX_FLAGS="-Wall -Wextra -Werror" >/dev/null
cmake --build cpp_static >/dev/null
if ldd cpp_static/shade_hit | grep -c libbiref >/dev/null; then
  echo "FAIL: the static build of shade_hit loads libbiref.so" >&2; exit 1
fi
cpp_static/shade_hit >cpp_static.json

/usr/bin/python3 - ref.json c.json cpp.json cpp_static.json <<'PY'
import json, math, sys
ref = json.load(open(sys.argv[1]))
fail = 0
for path in sys.argv[2:]:
    got = json.load(open(path))
    for d in ("T", "R"):
        for i in "sp":
            for o in "sp":
                a, b = got[d][i][o], ref[d][i][o]
                if not abs(a - b) <= 1e-12:
                    print(f"FAIL {path}: {d}[{i}][{o}] = {a!r}, biref slab --json says {b!r}")
                    fail = 1
    for key, vals in got.items():
        if key.startswith(("srgb", "hit_srgb")) and not all(math.isfinite(v) for v in vals):
            print(f"FAIL {path}: {key} = {vals}")
            fail = 1
print("ok: C (pkg-config) and C++ (find_package, shared and static) programs agree with biref slab --json" if not fail else "")
sys.exit(fail)
PY

# Python: the package the install put where Debian's interpreter looks (here under the temporary
# prefix, so on PYTHONPATH), finding the installed library on its own.
pkgdir=$(dirname "$(dirname "$(find "$prefix" -path '*/biref/__init__.py' | head -n1)")")
[ -d "$pkgdir" ] || { echo "FAIL: the Python package was not installed" >&2; exit 1; }
env -u BIREF_LIBRARY -u BIREF_CDEF PYTHONPATH="$pkgdir" /usr/bin/python3 -c "
import json, biref
t = biref.slab(eta_o=1.775, eta_e=1.231, axis=(0.084, 0.979, -0.187), thickness_mm=1.15, theta_deg=30, lambda_nm=550)['T']
ref = json.load(open('ref.json'))['T']
assert biref.library_path.startswith('$prefix'), biref.library_path
bad = [(i, o) for i in 'sp' for o in 'sp' if abs(t[i][o] - ref[i][o]) > 1e-12]
assert not bad, (t, ref)
print('ok: installed Python package agrees with biref slab --json')
"

# pip install ./python (offline here: no index, dependencies already present), then the package
# finds the installed library through pkg-config alone.
# (From a copy: building writes build/ and *.egg-info next to pyproject.toml.)
cp -r "$src/python" "$tmp/python-src"
rm -rf "$tmp/python-src/build" "$tmp/python-src"/*.egg-info
/usr/bin/python3 -m pip install -q --no-build-isolation --no-deps --no-index --disable-pip-version-check \
  --target "$tmp/pip" "$tmp/python-src" 2>/dev/null
env -u BIREF_LIBRARY -u BIREF_CDEF PYTHONPATH="$tmp/pip" /usr/bin/python3 -c "
import biref
assert biref.library_path.startswith('$libdir'), biref.library_path
assert abs(biref.slab(eta_o=1.5, eta_e=1.6, axis=(0, 1, 0), thickness_um=1)['energy']['s'] - 1) < 1e-12
print('ok: pip install ./python works against the installed library')
"

# The README's library section as written: its C program, compiled by its own command line, and
# its Python one-liner.
/usr/bin/python3 - "$src/README.md" <<'PY'
import re, sys
text = open(sys.argv[1], encoding="utf-8").read()
lib = text[text.index("## Library"):]
lib = lib[:lib.index("\n## ", 1)]
open("app.c", "w").write(re.search(r"```c\n(.*?)```", lib, re.S).group(1))
sh = re.search(r"```sh\n(.*?)```", lib, re.S).group(1)
open("readme_cc.sh", "w").write(next(l for l in sh.splitlines() if l.startswith("cc ")) + "\n")
py = [l for b in re.findall(r"```sh\n(.*?)```", lib, re.S) for l in b.splitlines() if "import biref" in l]
open("readme_py.sh", "w").write(py[0] + "\n")
PY
bash readme_cc.sh
LD_LIBRARY_PATH=$libdir ./app >readme_app.txt
grep -q "^colour: T s->s XYZ" readme_app.txt || { echo "FAIL: the README's program printed:" >&2; cat readme_app.txt >&2; exit 1; }
env -u BIREF_LIBRARY -u BIREF_CDEF PYTHONPATH="$pkgdir" bash readme_py.sh >readme_py.txt
/usr/bin/python3 -c "
import ast, json
t = ast.literal_eval(open('readme_py.txt').read())
ref = json.load(open('ref.json'))['T']
assert all(abs(t[i][o] - ref[i][o]) <= 1e-12 for i in 'sp' for o in 'sp'), (t, ref)
"
echo "ok: the README's C program and Python line work as written"

# Commands that read example scenes work from any directory once installed.
"$prefix/bin/biref" bench --width 32 --height 18 --max-seconds 0.05 --methods analytic >/dev/null
"$prefix/bin/biref" render "$prefix/share/biref/examples/fig9a.json" --width 16 --height 9 -o img.png >/dev/null
[ -s img.png ] || { echo "FAIL: render from the installed examples wrote nothing" >&2; exit 1; }
echo "ok: installed biref bench runs from $(pwd | sed "s|$tmp|<tmp>|")"
