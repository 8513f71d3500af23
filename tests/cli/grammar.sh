#!/usr/bin/env bash
# The shared command-line grammar (docs/CLI.md): biref --help lists every command and -V; every
# command answers --help; the old spellings give the same results as the new names.
set -u
. "$(dirname "$0")/lib.sh"

expect_ok "version" -V
expect_grep "version" '^biref [0-9]+\.[0-9]+\.[0-9]+$'
expect_ok "top-level help" --help
expect_grep "help lists -V" '-V, --version'
cmds=(slab spectrum accuracy render diff bench figure gl-data photoelastic)
for cmd in "${cmds[@]}"; do expect_grep "help lists $cmd" "^  $cmd "; done
for cmd in "${cmds[@]}"; do
  expect_ok "$cmd --help" $cmd --help
  expect_grep "$cmd --help lists -h" '-h, --help'
done
expect_ok "photoelastic demodulate --help" photoelastic demodulate --help

# docs/CLI.md carries the option tables that `biref help --markdown` prints from the tables that
# parse the options (not in a build without plots, whose figure has no options).
docs=$(dirname "$0")/../../docs/CLI.md
"$BIREF" help --markdown >"$tmpdir/options.md"
if "$BIREF" figure --help >/dev/null 2>&1; then
  sed -n '/^## Options of each command/,$p' "$docs" >"$tmpdir/docs_options.md"
  if ! cmp -s "$tmpdir/options.md" "$tmpdir/docs_options.md"; then
    echo "FAIL (docs/CLI.md): its option tables differ from 'biref help --markdown' (regenerate them):"
    diff "$tmpdir/docs_options.md" "$tmpdir/options.md" | head -10
    fails=$((fails + 1))
  fi
fi

# Every option of every table (and every old spelling) is accepted by its command: given with a
# value and followed by an unknown option, the error is about the unknown one (or about the
# value), never "unknown option" for the option itself. Each --help lists the option.
checked=0
check_option() { # CMD... -- OPTION [VALUE]
  local cmd=() opt val=()
  while [ "$1" != -- ]; do cmd+=("$1"); shift; done
  shift
  opt=$1
  [ $# -gt 1 ] && val=(1)
  local err
  err=$("$BIREF" "${cmd[@]}" "$opt" "${val[@]}" --no-such-option 2>&1 >/dev/null)
  if [ $? -ne 2 ] || grep -qF -- "unknown option '$opt'" <<<"$err" || grep -qF -- "needs a value" <<<"$err"; then
    echo "FAIL (${cmd[*]} $opt): not accepted: $err"
    fails=$((fails + 1))
  fi
  checked=$((checked + 1))
}
cmd=()
while IFS= read -r line; do
  case $line in
  "### biref "*)
    read -r -a cmd <<<"${line#\#\#\# biref }"
    "$BIREF" "${cmd[@]}" --help >"$tmpdir/help" || { echo "FAIL (${cmd[*]} --help)"; fails=$((fails + 1)); }
    continue ;;
  "| \`-h, --help\`"*) continue ;;
  "| \`-"*) old=0 ;;                      # | `-o, --output FILE` | meaning |
  "| "*" | \`-"*) old=1                   # | command | `--old VALUE` | `--new VALUE` |
    text=${line#| }
    read -r -a cmd <<<"${text%% |*}" ;;
  *) continue ;;
  esac
  label=${line#*\`}
  label=${label%%\`*}
  label=${label//\\|/|}
  read -r -a words <<<"$label"
  if [[ ${words[0]} == -?, ]]; then # a short name too
    check_option "${cmd[@]}" -- "${words[0]%,}" "${words[@]:2}"
    words=("${words[@]:1}")
  fi
  if [ $old = 0 ] && ! grep -qF -- "${words[0]}" "$tmpdir/help"; then
    echo "FAIL (${cmd[*]} --help does not list ${words[0]})"
    fails=$((fails + 1))
  fi
  check_option "${cmd[@]}" -- "${words[@]}"
done <"$tmpdir/options.md"
[ "$checked" -gt 100 ] || { echo "FAIL: only $checked options checked"; fails=$((fails + 1)); }

# Old spelling and new name: identical output.
same() {
  local what=$1 old=$2 new=$3
  shift 3
  local a b
  a=$("$BIREF" "$@" $old 2>&1) || { echo "FAIL ($what): old spelling '$old' refused: $a"; fails=$((fails + 1)); return; }
  b=$("$BIREF" "$@" $new 2>&1) || { echo "FAIL ($what): '$new' refused: $b"; fails=$((fails + 1)); return; }
  [ "$a" = "$b" ] || { echo "FAIL ($what): '$old' and '$new' differ"; fails=$((fails + 1)); }
}
slab=(--eta-o 1.6 --eta-e 1.5 --axis 0,1,0 --thickness-um 3 --theta-deg 20)
pe=(photoelastic --preset disk --light mono --profile 0,-20,0,20)
same "spectrum samples" "--samples 8" "--spectral-samples 8" spectrum "${slab[@]}" --method numeric --json
same "profile samples" "--samples 5" "--profile-points 5" "${pe[@]}"
same "polarizer-deg" "--polarizer-deg 30" "--polarizer linear:30" "${pe[@]}" --polariscope plane
same "view-mm" "--view-mm -10,20,-5,15" "--window-mm 20,15,-10,-5" "${pe[@]}" --json

# New rectangles are two corners: an empty one is refused.
expect_error "empty window" photoelastic --preset disk --window-mm 1,0,1,2 -o "$tmpdir/x.png"
expect_error "circular polariscope polarizer" photoelastic --preset disk --polarizer circular:+1 -o "$tmpdir/x.png"
expect_error "format" photoelastic --preset disk --format jpeg -o "$tmpdir/x.png"
finish
