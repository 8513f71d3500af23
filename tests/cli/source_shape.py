"""The shape of the library's sources under src/ (the layout rules of the project):

  1. no file (.c, .h, .inc) over MAX_FILE_LINES lines;
  2. no function over MAX_FUNCTION_LINES lines;
  3. no include cycle between modules (a module is a directory directly under src/; files
     directly in src/ form the module "."), and no include cycle between files;
  4. with the path of a built biref (the command-line tests' argument): no cycle between the
     library's modules through the functions they call (link level); cycles between files
     through calls are listed and checked against their allow-list, and fail only once
     FAIL_ON_CALL_FILE_CYCLES is set.

How a function is measured: this code base puts a function's opening brace alone at column 0
and its closing brace at column 0 (clang-format, BreakBeforeBraces: Linux), and nothing else
does. A function's length is the number of lines from the line of its opening brace to the line
of its closing brace, both included; its name is the identifier before the first "(" of the
signature above the brace (the lines from the last line that starts at column 0). Macro-made
names (NAME(x)(...)) are reported as the macro's name with its argument.

How includes are read: every `#include "..."` line (comments and conditionals are not parsed, so
an include inside #if counts as an edge, a conservative choice). "dir/file.h" resolves against
src/, then the including file's directory; "biref/..." (the public headers in include/) and
system headers are not part of the graph.

How calls are read (4): `nm` on the library's object files next to the given biref
(BUILD/CMakeFiles/biref.dir/src/...o, only those whose source still exists): file A depends on
file B when A's object leaves a symbol undefined that B's object defines. This sees the circles
an include graph cannot (a .c calling a function of another .c whose header it includes).

ALLOWED lists today's offenders with their sizes. The check fails when an allowed entry grows
(or a new file or function goes over a limit, or a new cycle appears), and tells when an entry
has shrunk within the limit or disappeared, so that it can be removed: the list only shrinks.
A cycle is allowed while its members are all in one allowed cycle (breaking part of a circle
passes); an allowed cycle with no cycle left among its members must be removed.

usage: /usr/bin/python3 source_shape.py REPO_ROOT [BIREF] [--list]   (--list: every offender)
Standard library only; Debian's python3.
"""
import os
import re
import subprocess
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 120

# Today's offenders, each at its size when the check was written. Remove an entry once the
# check says it is within the limit (it fails until the entry is removed, so that the list
# stays the list of offenders); never raise a number.
ALLOWED_FILES = {
    # path under src/: lines
}
ALLOWED_FUNCTIONS = {
    # (path under src/, function): lines from its opening to its closing brace
}
ALLOWED_MODULE_CYCLES = [
    # include level: a cycle as the sorted tuple of its modules (none today)
]
ALLOWED_FILE_CYCLES = [
    # include level: a cycle as the sorted tuple of its files (none today)
]
ALLOWED_CALL_MODULE_CYCLES = [
    # link level, modules (none today)
]
# Cycles between files through calls are reported (with the allow-list's verdicts as notes) but
# fail the check only once this is True (the renderer's circle hit_frames -> render -> shade is
# broken; turn it on once the list below holds only circles that are meant to stay).
FAIL_ON_CALL_FILE_CYCLES = False
ALLOWED_CALL_FILE_CYCLES = [
    # link level, files: the sorted tuple of the files of one strongly connected set
    ("optics/material.c", "optics/material_table.c"),
    ("photoelastic/polariscope.c", "photoelastic/shade_integrated.c"),
    # dispersive materials: each method's file calls the other's entry points
    # (biref_spectrum_numeric_dispersive*, biref_integrate_material_closed_form*)
    ("spectral/analytic_dispersive.c", "spectral/numeric_dispersive.c"),
    # the spectral methods: numeric_jones.c asks analytic_packet.c which instruction sets the CPU
    # has (biref_simd_isa_supported), and analytic_packet.c falls back through coherent.c and
    # numeric.c to numeric_jones.c (and the lanes' dispersive look-ups through leg_dispersion.c);
    # the instruction-set choice in a file of its own breaks it
    ("spectral/analytic_packet.c", "spectral/analytic_packet_avx2.c", "spectral/analytic_packet_avx512.c",
     "spectral/analytic_packet_baseline.c", "spectral/analytic_packet_f32_avx2.c",
     "spectral/analytic_packet_f32_avx512.c", "spectral/analytic_packet_f32_pairs_avx2.c",
     "spectral/analytic_packet_f32_pairs_avx512.c", "spectral/analytic_packet_pairs_avx2.c",
     "spectral/analytic_packet_pairs_avx512.c", "spectral/analytic_packet_pairs_baseline.c",
     "spectral/coherent.c", "spectral/leg_dispersion.c", "spectral/numeric.c", "spectral/numeric_jones.c",
     "spectral/phase_prefilter.c", "spectral/spectral_context.c"),
]

SOURCE = re.compile(r"\.(c|h|inc)$")
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
NAME = re.compile(r"([A-Za-z_][A-Za-z_0-9]*)\s*(\([A-Za-z_0-9, ]*\))?\s*\(")
ATTRIBUTE = re.compile(r"__attribute__\s*\(\((?:[^()]|\([^()]*\))*\)\)")
KEYWORDS = {"if", "for", "while", "switch", "return", "sizeof", "defined"}


def sources(src):
    for top, dirs, files in os.walk(src):
        dirs.sort()
        for f in sorted(files):
            if SOURCE.search(f):
                yield os.path.relpath(os.path.join(top, f), src)


def functions(lines):
    """(name, length) of every function: opening brace at column 0 to closing brace at column 0."""
    out = []
    i = 0
    while i < len(lines):
        if lines[i].startswith("{"):
            start = i
            head = i - 1
            while head > 0 and (not lines[head].strip() or lines[head][0] in " \t)"):
                head -= 1
            signature = " ".join(l.strip() for l in lines[head:start])
            signature = ATTRIBUTE.sub(" ", signature)
            name = "?"
            for m in NAME.finditer(signature):
                if m.group(1) not in KEYWORDS:
                    name = m.group(1) + (m.group(2) or "")
                    break
            j = start + 1
            while j < len(lines) and not lines[j].startswith("}"):
                j += 1
            out.append((name, j - start + 1))
            i = j + 1
        else:
            i += 1
    return out


def cycles(graph):
    """Strongly connected components with more than one node (or a node including itself)."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1 or v in graph.get(v, ()):
                out.append(tuple(sorted(comp)))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def call_graph(src, biref):
    """File -> files whose functions or data it uses, from nm on the library's objects."""
    objdir = os.path.join(os.path.dirname(os.path.abspath(biref)), "CMakeFiles", "biref.dir", "src")
    if not os.path.isdir(objdir):
        return None
    defs, uses = {}, {}
    for top, _, files in os.walk(objdir):
        for f in files:
            if not f.endswith(".o"):
                continue
            path = os.path.relpath(os.path.join(top, f), objdir)[:-2]
            if not os.path.isfile(os.path.join(src, path)):
                continue  # a stale object of a removed source
            out = subprocess.run(["nm", os.path.join(top, f)], capture_output=True, text=True, check=True).stdout
            for line in out.splitlines():
                part = line.split()
                if len(part) == 3 and part[1] in "TDBRVW":
                    defs[part[2]] = path
                elif len(part) == 2 and part[0] == "U":
                    uses.setdefault(path, set()).add(part[1])
    graph = {}
    for path, names in uses.items():
        for name in names:
            if name in defs and defs[name] != path:
                graph.setdefault(path, set()).add(defs[name])
    return graph


def module_graph_of(graph):
    out = {}
    for a, targets in graph.items():
        for b in targets:
            if module_of(a) != module_of(b):
                out.setdefault(module_of(a), set()).add(module_of(b))
    return out


def check_cycles(found, allowed, what, listname, fail):
    """found: today's cycles; allowed: the list. Subsets of an allowed cycle pass."""
    for c in sorted(found):
        if not any(set(c) <= set(a) for a in allowed):
            fail(f"{what}: " + ", ".join(c))
    for a in allowed:
        if not any(set(c) <= set(a) for c in found):
            fail(f"{what} " + ", ".join(a) + f" is gone: remove it from {listname}")


def module_of(path):
    return path.split("/")[0] if "/" in path else "."


def main():
    args = [a for a in sys.argv[1:] if a != "--list"]
    root = os.path.abspath(args[0] if args else ".")
    biref = args[1] if len(args) > 1 else None
    listing = "--list" in sys.argv
    src = os.path.join(root, "src")
    files = list(sources(src))
    big_files, big_functions = {}, {}
    file_graph, module_graph = {}, {}
    for path in files:
        with open(os.path.join(src, path), encoding="utf-8") as f:
            lines = f.read().split("\n")
        if lines and lines[-1] == "":
            lines.pop()
        if len(lines) > MAX_FILE_LINES:
            big_files[path] = len(lines)
        for name, n in functions(lines):
            if n > MAX_FUNCTION_LINES:
                big_functions[(path, name)] = max(n, big_functions.get((path, name), 0))
        for line in lines:
            m = INCLUDE.match(line)
            if not m:
                continue
            target = None
            for base in (src, os.path.join(src, os.path.dirname(path))):
                candidate = os.path.normpath(os.path.join(base, m.group(1)))
                if os.path.isfile(candidate) and candidate.startswith(src + os.sep):
                    target = os.path.relpath(candidate, src)
                    break
            if target is None:
                continue  # a public header (include/biref/...) or a system header
            file_graph.setdefault(path, set()).add(target)
            a, b = module_of(path), module_of(target)
            if a != b:
                module_graph.setdefault(a, set()).add(b)
    module_cycles = set(cycles(module_graph))
    file_cycles = set(cycles(file_graph))
    calls = call_graph(src, biref) if biref else None
    if biref and calls is None:
        print(f"FAIL: no library objects next to {biref} (BUILD/CMakeFiles/biref.dir/src): cannot read the calls")
        return 1
    call_file_cycles = set(cycles(calls)) if calls else set()
    call_module_cycles = set(cycles(module_graph_of(calls))) if calls else set()

    if listing:
        for p, n in sorted(big_files.items(), key=lambda x: -x[1]):
            print(f"file     {n:5d}  src/{p}")
        for (p, name), n in sorted(big_functions.items(), key=lambda x: -x[1]):
            print(f"function {n:5d}  src/{p}: {name}")
        for c in sorted(module_cycles):
            print("modules in an include cycle: " + ", ".join(c))
        for c in sorted(file_cycles):
            print("files in an include cycle: " + ", ".join(c))
        for c in sorted(call_module_cycles):
            print("modules in a cycle through calls: " + ", ".join(c))
        for c in sorted(call_file_cycles):
            print("files in a cycle through calls: " + ", ".join(c))
        return 0

    fails = 0

    def fail(msg):
        nonlocal fails
        print("FAIL: " + msg)
        fails += 1

    def note(msg):
        print("note (not failed, FAIL_ON_CALL_FILE_CYCLES is off): " + msg)

    for p, n in sorted(big_files.items()):
        if p not in ALLOWED_FILES:
            fail(f"src/{p} has {n} lines (limit {MAX_FILE_LINES}): split it by concern")
        elif n > ALLOWED_FILES[p]:
            fail(f"src/{p} grew to {n} lines (allowed while it is being split: {ALLOWED_FILES[p]})")
    for p in sorted(ALLOWED_FILES):
        if p not in big_files:
            fail(f"src/{p} is within {MAX_FILE_LINES} lines or gone: remove it from ALLOWED_FILES")
    for key, n in sorted(big_functions.items()):
        p, name = key
        if key not in ALLOWED_FUNCTIONS:
            fail(f"src/{p}: {name} has {n} lines (limit {MAX_FUNCTION_LINES}): split it")
        elif n > ALLOWED_FUNCTIONS[key]:
            fail(f"src/{p}: {name} grew to {n} lines (allowed while it is being split: {ALLOWED_FUNCTIONS[key]})")
    for key in sorted(ALLOWED_FUNCTIONS):
        if key not in big_functions:
            fail(f"src/{key[0]}: {key[1]} is within {MAX_FUNCTION_LINES} lines or gone: remove it from ALLOWED_FUNCTIONS")
    check_cycles(module_cycles, ALLOWED_MODULE_CYCLES, "include cycle between modules", "ALLOWED_MODULE_CYCLES", fail)
    check_cycles(file_cycles, ALLOWED_FILE_CYCLES, "include cycle between files", "ALLOWED_FILE_CYCLES", fail)
    if calls is not None:
        check_cycles(call_module_cycles, ALLOWED_CALL_MODULE_CYCLES, "cycle between modules through calls",
                     "ALLOWED_CALL_MODULE_CYCLES", fail)
        check_cycles(call_file_cycles, ALLOWED_CALL_FILE_CYCLES, "cycle between files through calls",
                     "ALLOWED_CALL_FILE_CYCLES", fail if FAIL_ON_CALL_FILE_CYCLES else note)
    if fails:
        print(f"{fails} failure(s)")
        return 1
    print(f"all passed ({len(files)} files{'' if calls is not None else ', calls not read'}; allowed for now: "
          f"{len(ALLOWED_FILES)} files, {len(ALLOWED_FUNCTIONS)} functions, "
          f"{len(ALLOWED_MODULE_CYCLES) + len(ALLOWED_FILE_CYCLES)} include cycles, "
          f"{len(ALLOWED_CALL_MODULE_CYCLES) + len(ALLOWED_CALL_FILE_CYCLES)} call cycles)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
