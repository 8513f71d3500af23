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
