# Helpers for command-line tests. Source from a test script; $BIREF is the CLI under test.
BIREF=${1:?usage: script.sh path/to/biref}
fails=0
tmpdir=$(mktemp -d)
trap 'rm -rf "$tmpdir"' EXIT

# expect_error DESCRIPTION ARGS...: non-zero exit, exactly one line on stderr, nothing on stdout.
expect_error() {
  local what=$1; shift
  local rc=0
  "$BIREF" "$@" >"$tmpdir/out" 2>"$tmpdir/err" || rc=$?
  local lines
  lines=$(wc -l <"$tmpdir/err")
  if [ "$rc" -eq 0 ] || [ "$lines" -ne 1 ] || [ -s "$tmpdir/out" ] || [ "$rc" -gt 2 ]; then
    echo "FAIL ($what): rc=$rc stderr-lines=$lines stdout-bytes=$(wc -c <"$tmpdir/out")"
    sed 's/^/  stderr: /' "$tmpdir/err" | head -5
    fails=$((fails + 1))
  fi
}

# expect_ok DESCRIPTION ARGS...: zero exit; stdout saved in $tmpdir/out.
expect_ok() {
  local what=$1; shift
  if ! "$BIREF" "$@" >"$tmpdir/out" 2>"$tmpdir/err"; then
    echo "FAIL ($what): non-zero exit"
    sed 's/^/  stderr: /' "$tmpdir/err" | head -5
    fails=$((fails + 1))
  fi
}

# expect_grep DESCRIPTION PATTERN: the last expect_ok output matches the extended regex.
expect_grep() {
  if ! grep -Eq -e "$2" "$tmpdir/out"; then
    echo "FAIL ($1): output does not match /$2/"
    fails=$((fails + 1))
  fi
}

# json_num KEY FILE: the first number under KEY in cJSON's formatted (one key per line) output.
json_num() { sed -n "s/^[[:space:]]*\"$1\":[[:space:]]*\\([-0-9.eE+]*\\),*\$/\\1/p" "$2" | head -1; }

finish() {
  if [ "$fails" -ne 0 ]; then
    echo "$fails failure(s)"
    exit 1
  fi
  echo "all passed"
}
