#!/usr/bin/env bash
# The example scripts write where they are told, by default under out/, never into tracked files:
# examples/photoelastic/figures.sh, run from a copy of its directory, writes its pictures below
# out/photoelastic of that copy when given no arguments, and only below OUTDIR when given one.
set -u
. "$(dirname "$0")/lib.sh"
src="$(cd "$(dirname "$0")/../.." && pwd)"
mkdir -p "$tmpdir/repo/examples"
cp -r "$src/examples/photoelastic" "$tmpdir/repo/examples/"
cat >"$tmpdir/fake-biref" <<'STUB'
#!/usr/bin/env bash
# Records the -o argument of every call.
while [ $# -gt 0 ]; do
  if [ "$1" = -o ] || [ "$1" = --output ]; then echo "$2" >>"$FAKE_LOG"; fi
  shift
done
STUB
chmod +x "$tmpdir/fake-biref"

check_outputs() { # DESCRIPTION EXPECTED-DIR
  local n
  n=$(wc -l <"$FAKE_LOG")
  if [ "$n" -lt 10 ]; then
    echo "FAIL ($1): only $n outputs recorded"
    fails=$((fails + 1))
  fi
  while read -r path; do
    case "$(realpath -m "$path")" in
    "$(realpath -m "$2")"/*) ;;
    *) echo "FAIL ($1): writes $path, outside $2"; fails=$((fails + 1)) ;;
    esac
  done <"$FAKE_LOG"
}

# With no arguments at all, in a copy whose build/biref is the command under test: every picture
# appears under out/photoelastic and nothing else in the copy changes. Under BIREF_TEST_QUICK (the
# sanitizer build, too slow for twenty pictures) build/biref is the stand-in below, which records
# the output paths instead.
mkdir -p "$tmpdir/repo/build" "$tmpdir/repo/docs/figures/photoelastic"
export FAKE_LOG="$tmpdir/default.log"
: >"$FAKE_LOG"
if [ -n "${BIREF_TEST_QUICK:-}" ]; then
  ln -s "$tmpdir/fake-biref" "$tmpdir/repo/build/biref"
else
  ln -s "$(realpath "$BIREF")" "$tmpdir/repo/build/biref"
fi
before=$(cd "$tmpdir/repo" && find . -path ./out -prune -o -type f -print | sort | xargs md5sum)
if ! (cd / && bash "$tmpdir/repo/examples/photoelastic/figures.sh" >/dev/null 2>"$tmpdir/err"); then
  echo "FAIL (figures.sh without arguments): non-zero exit"
  sed 's/^/  stderr: /' "$tmpdir/err" | head -5
  fails=$((fails + 1))
fi
after=$(cd "$tmpdir/repo" && find . -path ./out -prune -o -type f -print | sort | xargs md5sum)
if [ "$before" != "$after" ]; then
  echo "FAIL (figures.sh without arguments): changed files outside out/"
  diff <(echo "$before") <(echo "$after") | head -5
  fails=$((fails + 1))
fi
if [ -n "${BIREF_TEST_QUICK:-}" ]; then
  check_outputs "figures.sh without arguments" "$tmpdir/repo/out/photoelastic"
else
  n=$(find "$tmpdir/repo/out/photoelastic" -name '*.png' 2>/dev/null | wc -l)
  if [ "$n" -lt 15 ]; then
    echo "FAIL (figures.sh without arguments): $n pictures in out/photoelastic"
    fails=$((fails + 1))
  fi
fi

# With an OUTDIR, every output goes below it (a stand-in biref records the paths).
export FAKE_LOG="$tmpdir/given.log"
: >"$FAKE_LOG"
bash "$tmpdir/repo/examples/photoelastic/figures.sh" "$tmpdir/fake-biref" "$tmpdir/given" >/dev/null 2>&1
check_outputs "figures.sh, given directory" "$tmpdir/given"

if ! bash "$src/examples/photoelastic/figures.sh" --help | grep -q "out/photoelastic"; then
  echo "FAIL (figures.sh --help does not name its default directory)"
  fails=$((fails + 1))
fi
finish
