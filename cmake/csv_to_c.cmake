# Turns the CIE 1931 CSV (nm,X,Y,Z) into a C array so the library needs no data files at run time.
file(STRINGS ${IN} lines)
list(REMOVE_AT lines 0)
set(body "")
set(count 0)
foreach(line ${lines})
  string(STRIP "${line}" line)
  if(line STREQUAL "")
    continue()
  endif()
  string(APPEND body "    {${line}},\n")
  math(EXPR count "${count} + 1")
endforeach()
file(WRITE ${OUT} "/* Generated from data/cie1931_2deg_xyz_1nm.csv by cmake/csv_to_c.cmake. Do not edit. */\n"
  "#include \"color/cie1931_table.h\"\n"
  "const int biref_cie1931_rows = ${count};\n"
  "const double biref_cie1931_table[][4] = {\n${body}};\n")
