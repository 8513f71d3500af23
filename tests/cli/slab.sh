#!/usr/bin/env bash
# biref slab: every bad input gives one error line and a non-zero exit; good input gives JSON.
set -u
. "$(dirname "$0")/lib.sh"
good=(--eta-o 1.5 --eta-e 1.6 --axis 0.3,0.5,0.8 --thickness-um 10 --theta-deg 30 --lambda-nm 550)

expect_ok "help" slab --help
expect_grep "help lists options" "--thickness-um"
expect_ok "json" slab "${good[@]}" --json
expect_grep "T.s.p present" '"T":'
expect_grep "jones_R present" '"jones_R":'
expect_grep "K_max present" '"K_max":'
expect_ok "tmm" slab "${good[@]}" --method tmm --json
expect_grep "tmm method" '"method":[[:space:]]*"tmm"'
expect_ok "table" slab "${good[@]}"
expect_grep "table energy" "Energy check"
expect_ok "huge but finite axis" slab --eta-o 1.5 --eta-e 1.6 --axis 1e300,0,1e300 --thickness-um 10 --json
expect_grep "huge axis normalised" '0.7071067811865'
expect_ok "thickness in mm" slab --eta-o 1.5 --eta-e 1.6 --axis 0,0,1 --thickness-mm 0.01 --json

base=(--eta-e 1.6 --axis 0.3,0.5,0.8 --thickness-um 10)
expect_error "NaN eta-o" slab --eta-o nan "${base[@]}"
expect_error "inf eta-o" slab --eta-o inf "${base[@]}"
expect_error "negative eta-o" slab --eta-o -1.5 "${base[@]}"
expect_error "zero eta-o" slab --eta-o 0 "${base[@]}"
expect_error "garbage eta-o" slab --eta-o 1.5x "${base[@]}"
expect_error "missing eta-o" slab "${base[@]}"
expect_error "zero eta-e" slab --eta-o 1.5 --eta-e 0 --axis 0,0,1 --thickness-um 1
expect_error "negative eta-i" slab "${good[@]}" --eta-i -1
expect_error "nan eta-i" slab "${good[@]}" --eta-i nan
expect_error "zero axis" slab --eta-o 1.5 --eta-e 1.6 --axis 0,0,0 --thickness-um 1
expect_error "nan axis" slab --eta-o 1.5 --eta-e 1.6 --axis nan,0,1 --thickness-um 1
expect_error "short axis" slab --eta-o 1.5 --eta-e 1.6 --axis 0,1 --thickness-um 1
expect_error "long axis" slab --eta-o 1.5 --eta-e 1.6 --axis 0,1,0,1 --thickness-um 1
expect_error "empty axis field" slab --eta-o 1.5 --eta-e 1.6 --axis 0,,1 --thickness-um 1
expect_error "zero thickness" slab --eta-o 1.5 --eta-e 1.6 --axis 0,0,1 --thickness-um 0
expect_error "negative thickness" slab --eta-o 1.5 --eta-e 1.6 --axis 0,0,1 --thickness-mm -1
expect_error "two thicknesses" slab --eta-o 1.5 --eta-e 1.6 --axis 0,0,1 --thickness-mm 1 --thickness-um 1
expect_error "missing thickness" slab --eta-o 1.5 --eta-e 1.6 --axis 0,0,1
expect_error "theta 90" slab "${good[@]}" --theta-deg 90
expect_error "theta negative" slab "${good[@]}" --theta-deg -1
expect_error "theta nan" slab "${good[@]}" --theta-deg nan
expect_error "lambda zero" slab "${good[@]}" --lambda-nm 0
expect_error "lambda negative" slab "${good[@]}" --lambda-nm -500
expect_error "unknown option" slab "${good[@]}" --frobnicate
expect_error "missing value" slab "${good[@]}" --lambda-nm
expect_error "unknown method" slab "${good[@]}" --method magic
expect_error "stray argument" slab "${good[@]}" extra
expect_error "unknown command" frobnicate
finish
