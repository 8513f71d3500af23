#!/usr/bin/env bash
# The shared library exports exactly the public API: every symbol it defines is biref_*, and
# every function declared in include/biref carries BIREF_API (else it would be hidden).
# $1: libbiref.so, $2: the include directory.
set -euo pipefail
lib=$1 inc=$2
fail=0
# GCC emits named OpenMP critical sections as common symbols; ours are named biref_*.
bad=$(nm -D --defined-only "$lib" | awk '{print $NF}' | grep -v '^biref_' | grep -v '^\.gomp_critical_user_biref_' || true)
if [ -n "$bad" ]; then
  echo "FAIL: symbols outside the biref_ namespace exported from $lib:" >&2
  echo "$bad" >&2
  fail=1
fi
n=$(nm -D --defined-only "$lib" | awk '{print $NF}' | grep -c '^biref_' || true)
[ "$n" -ge 50 ] || { echo "FAIL: only $n biref_ symbols exported (visibility broken?)" >&2; fail=1; }
# Top-level declarations (a line starting with a type and naming biref_xxx( ) without BIREF_API.
missing=$(grep -nE '^[a-z][^;{]*\bbiref_[a-z0-9_]+\(' "$inc"/biref/*.h | grep -vE ':(typedef|BIREF_API) ' || true)
if [ -n "$missing" ]; then
  echo "FAIL: public declarations without BIREF_API (hidden from libbiref.so):" >&2
  echo "$missing" >&2
  fail=1
fi
# Every BIREF_API function is really exported.
exported=$(nm -D --defined-only "$lib" | awk '{print $NF}')
for f in $(grep -ohE '^BIREF_API [^;{]*\bbiref_[a-z0-9_]+\(' "$inc"/biref/*.h | grep -oE 'biref_[a-z0-9_]+\($' | tr -d '('); do
  grep -qx "$f" <<<"$exported" || { echo "FAIL: $f declared but not exported" >&2; fail=1; }
done
[ $fail -eq 0 ] && echo "ok: $n biref_ symbols exported, nothing else"
exit $fail
