"""The shape of the library's sources under src/ (the layout rules of the project):

  1. no file (.c, .h, .inc) over MAX_FILE_LINES lines;
  2. no function over MAX_FUNCTION_LINES lines;
  3. no include cycle between modules (a module is a directory directly under src/; files
     directly in src/ form the module "."), and no include cycle between files.

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

ALLOWED lists today's offenders with their sizes. The check fails when an allowed entry grows
(or a new file or function goes over a limit, or a new cycle appears), and tells when an entry
has shrunk within the limit or disappeared, so that it can be removed: the list only shrinks.

usage: /usr/bin/python3 source_shape.py REPO_ROOT [--list]   (--list: print every offender)
Standard library only; Debian's python3.
"""
import os
import re
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 120

# Today's offenders, each at its size when the check was written. Remove an entry once the
# check says it is within the limit (it fails until the entry is removed, so that the list
# stays the list of offenders); never raise a number.
ALLOWED_FILES = {
    # path under src/: lines
    "spectral/analytic_packet_kernel.inc": 858,
}
ALLOWED_FUNCTIONS = {
    # (path under src/, function): lines from its opening to its closing brace
}
ALLOWED_MODULE_CYCLES = {
    # a cycle as the sorted tuple of its modules
}
ALLOWED_FILE_CYCLES = {
    # a cycle as the sorted tuple of its files
}

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


def module_of(path):
    return path.split("/")[0] if "/" in path else "."


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
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

    if listing:
        for p, n in sorted(big_files.items(), key=lambda x: -x[1]):
            print(f"file     {n:5d}  src/{p}")
        for (p, name), n in sorted(big_functions.items(), key=lambda x: -x[1]):
            print(f"function {n:5d}  src/{p}: {name}")
        for c in sorted(module_cycles):
            print("module cycle: " + " -> ".join(c))
        for c in sorted(file_cycles):
            print("file cycle: " + " -> ".join(c))
        return 0

    fails = 0

    def fail(msg):
        nonlocal fails
        print("FAIL: " + msg)
        fails += 1

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
    for c in sorted(module_cycles):
        if c not in ALLOWED_MODULE_CYCLES:
            fail("include cycle between modules: " + " -> ".join(c))
    for c in sorted(ALLOWED_MODULE_CYCLES):
        if c not in module_cycles:
            fail("module cycle " + " -> ".join(c) + " is gone: remove it from ALLOWED_MODULE_CYCLES")
    for c in sorted(file_cycles):
        if c not in ALLOWED_FILE_CYCLES:
            fail("include cycle between files: " + " -> ".join(c))
    for c in sorted(ALLOWED_FILE_CYCLES):
        if c not in file_cycles:
            fail("file cycle " + " -> ".join(c) + " is gone: remove it from ALLOWED_FILE_CYCLES")
    if fails:
        print(f"{fails} failure(s)")
        return 1
    print(f"all passed ({len(files)} files; allowed for now: {len(ALLOWED_FILES)} files, "
          f"{len(ALLOWED_FUNCTIONS)} functions, {len(ALLOWED_MODULE_CYCLES)} module cycles)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
