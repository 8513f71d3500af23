#!/usr/bin/env bash
# One rule for every option (docs/CLI.md, "Grammar"): an option given twice (also under an old
# spelling) or two options that exclude each other is an error with one line, whatever their
# values; long names are spelt whole (no abbreviations); numbers are decimal, without blanks,
# hexadecimal, inf or nan.
set -u
. "$(dirname "$0")/lib.sh"
named() { # DESCRIPTION PATTERN: the last expect_error's message matches
  grep -Eq -e "$2" "$tmpdir/err" || { echo "FAIL ($1): message does not match /$2/"; sed 's/^/  stderr: /' "$tmpdir/err"; fails=$((fails + 1)); }
}

# Every option of every table (docs/CLI.md's, from `biref help --markdown`) given twice.
"$BIREF" help --markdown >"$tmpdir/options.md"
checked=0
cmd=()
while IFS= read -r line; do
  case $line in
  "### biref "*) read -r -a cmd <<<"${line#\#\#\# biref }"; continue ;;
  *) [[ " ${cmd[*]} " == *" --tfp "* ]] && continue ;; # a mode with its own parser (not walked yet)
esac
case $line in
  "| \`-h, --help\`"*) continue ;;
  "| \`-"*) ;;
  *) continue ;;
  esac
  label=${line#*\`}
  label=${label%%\`*}
  read -r -a words <<<"${label//\\|/|}"
  [[ ${words[0]} == -?, ]] && words=("${words[@]:1}")
  opt=${words[0]}
  [ "$opt" = --progress ] || [ "$opt" = --quiet ] && continue # main's, below
  val=()
  [ ${#words[@]} -gt 1 ] && val=(1)
  expect_error "${cmd[*]} $opt twice" "${cmd[@]}" "$opt" "${val[@]}" "$opt" "${val[@]}"
  named "${cmd[*]} $opt twice" "given twice"
  checked=$((checked + 1))
done <"$tmpdir/options.md"
[ "$checked" -gt 100 ] || { echo "FAIL: only $checked options checked"; fails=$((fails + 1)); }

# An old spelling and its new name are one option.
expect_error "render --samples and --spectral-samples" render x.json -o x.png --samples 8 --spectral-samples 8
named "old and new spelling" "--spectral-samples given twice"
expect_error "figure --out and -o" figure fig5 --out a -o b
expect_error "photoelastic --polarizer-deg and --polarizer" photoelastic --preset disk --polarizer-deg 3 \
  --polarizer linear:3 --profile 0,0,1,1
expect_error "-o and --output" render x.json -o a.png --output b.png
named "-o and --output" "^biref render: error: -o/--output given twice"
expect_error "--progress and --quiet" render x.json -o a.png --progress --quiet
expect_error "-q twice" render x.json -o a.png -q -q

# Options that exclude each other, in either order.
slab=(--eta-o 1.6 --eta-e 1.5 --axis 0,1,0 --theta-deg 20)
excl() { # DESCRIPTION A B ARGS...: A then B and B then A are both refused, naming both
  local what=$1 a=$2 b=$3; shift 3
  expect_error "$what" "$@" $a $b
  named "$what" "${a%% *} and ${b%% *} exclude each other"
  expect_error "$what (reversed)" "$@" $b $a
  named "$what (reversed)" "${b%% *} and ${a%% *} exclude each other"
}
excl "thickness units" "--thickness-mm 1" "--thickness-um 3" slab "${slab[@]}"
excl "thickness units (spectrum)" "--thickness-nm 1" "--thickness-um 3" spectrum "${slab[@]}"
excl "polarizer and stokes" "--polarizer circular:+1" "--stokes 1,0,0,1" spectrum "${slab[@]}" --thickness-um 3
excl "polarizer and polarization" "--polarizer circular:+1" "--polarization s" spectrum "${slab[@]}" --thickness-um 3
excl "stokes and polarization" "--stokes 1,0,0,1" "--polarization 0.5,0.5" spectrum "${slab[@]}" --thickness-um 3
excl "preset and stress-grid" "--preset disk" "--stress-grid examples/photoelastic/gradient.csv" photoelastic \
  --profile 0,0,1,1
excl "preset and stress-nodes" "--preset disk" "--stress-nodes examples/photoelastic/disk_nodes.csv" photoelastic \
  --profile 0,0,1,1
excl "map and phase-steps" "--map sigma1" "--phase-steps 4" photoelastic --preset disk --light mono -o x.pfm
excl "map and format" "--map sigma1" "--format pfm" photoelastic --preset disk -o x.pfm
excl "zero-order and order-at" "--zero-order 1,1" "--order-at 1,1,0" photoelastic demodulate a b c d -o maps

# Long names are spelt whole: getopt_long's prefixes (--jso for --json) are unknown options.
expect_error "--jso" slab "${slab[@]}" --thickness-um 3 --jso
named "--jso" "unknown option '--jso' \(did you mean --json\?"
expect_error "--thick" slab "${slab[@]}" --thick 3
expect_error "--he" render --he
expect_error "--out=" render x.json --out=x.png
expect_ok "whole names" slab "${slab[@]}" --thickness-um=3 --json

# Numbers: decimal only.
for v in 0x10 ' 1.5' '1.5 ' inf -inf nan 1e 1.5x '' . +-1 1,5 0x1p3 infinity; do
  expect_error "--eta-o '$v'" slab --eta-o "$v" --eta-e 1.5 --axis 0,1,0 --thickness-um 3
  named "--eta-o '$v'" "--eta-o: expected a finite decimal number"
done
for v in 1.5 +1.5 1.5e0 15E-1 .15e1 1.; do
  expect_ok "--eta-o $v" slab --eta-o "$v" --eta-e 1.5 --axis 0,1,0 --thickness-um 3
done
for v in 0x10 ' 4' 4.0 1e1 '4 '; do
  expect_error "--supersample '$v'" render x.json -o x.png --supersample "$v"
done
expect_error "--axis with a blank" slab --eta-o 1.6 --eta-e 1.5 --axis '0, 1,0' --thickness-um 3
expect_error "--axis hexadecimal" slab --eta-o 1.6 --eta-e 1.5 --axis 0,0x1,0 --thickness-um 3
expect_error "--sweep-delta-eps hexadecimal" accuracy --sweep-delta-eps 0x1
for p in 'linear:0x10' 'linear: 10' 'linear:inf' 'linear:10 '; do
  expect_error "--analyzer $p" spectrum "${slab[@]}" --thickness-um 3 --method numeric --analyzer "$p"
  expect_error "--polarizer $p" spectrum "${slab[@]}" --thickness-um 3 --method numeric --polarizer "$p"
done
finish
