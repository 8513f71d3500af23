#!/usr/bin/env bash
# The documentation speaks of the repository alone: no paths outside it, no tracker issue numbers,
# no development sessions, engineers or "this machine"; every relative link and every backquoted
# repository path (`docs/...`, `examples/...`, ...) names a file or directory that exists, and every
# backquoted test (`test_x`, `test_x case`) names a test program or case that exists.
# (The biref argument of the other command-line tests is accepted and unused.)
set -u
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root" || exit 1
fails=0
docs=(docs/*.md docs/history/*.md README.md)

if grep -n -i -E '\.\./shared|/work/|reading-notes|\bissues? ?#?[0-9]+\b|(^|[ (])#[0-9]+\b|\bengineers?\b|\bsessions?\b|\bthis machine\b' \
  "${docs[@]}"; then
  echo "FAIL: the lines above point outside the repository"
  fails=$((fails + 1))
fi

if ! /usr/bin/python3 - "${docs[@]}" <<'EOF'; then
import os, re, sys
bad = 0
top = "docs|examples|tests|scripts|tools|cli|src|include|bench|web|shaders|data|python|cmake"
for doc in sys.argv[1:]:
    text = open(doc, encoding="utf-8").read()
    for m in re.finditer(r"\]\(([^)#\s]+)(#[^)]*)?\)", text):
        target = m.group(1)
        if re.match(r"[a-z]+:", target):
            continue  # a web address
        if not os.path.exists(os.path.normpath(os.path.join(os.path.dirname(doc), target))):
            print(f"FAIL ({doc}): link to {target}, which does not exist")
            bad += 1
    for m in re.finditer(r"`((?:%s)/[A-Za-z0-9_./-]*)`" % top, text):
        path = m.group(1).rstrip("/.")
        if "*" not in path and not os.path.exists(path):
            print(f"FAIL ({doc}): names {path}, which does not exist")
            bad += 1
# A test named in backquotes (`test_x` or `test_x case_name`) is a test program or case that exists.
tests = ""
for name in sorted(os.listdir("tests")):
    if name.endswith((".c", ".cpp", ".h")):
        tests += open(os.path.join("tests", name), encoding="utf-8").read()
tests += open("CMakeLists.txt", encoding="utf-8").read()
for doc in sys.argv[1:]:
    if "/history/" in doc:
        continue  # the measurement logs quote tests as they were named then
    text = open(doc, encoding="utf-8").read()
    for m in re.finditer(r"`(test_[a-z0-9_]+)(?: ([a-z0-9_]+))?`", text):
        for name in filter(None, m.groups()):
            if not re.search(r"\b%s\b" % name, tests):
                print(f"FAIL ({doc}): names the test {name}, which does not exist")
                bad += 1
sys.exit(1 if bad else 0)
EOF
  fails=$((fails + 1))
fi

if [ "$fails" -ne 0 ]; then
  echo "$fails failure(s)"
  exit 1
fi
echo "all passed"
