#!/usr/bin/env bash
# The sources under src/ keep their shape: no file over 600 lines, no function over 120 lines, no
# cycle between modules or files through includes or (from the objects built next to BIREF)
# through calls; today's offenders are an explicit allow-list that may only shrink
# (source_shape.py; `source_shape.py . build/biref --list` prints every offender).
# Debian's python3 (standard library only) and binutils' nm.
exec /usr/bin/python3 "$(dirname "$0")/source_shape.py" "$(dirname "$0")/../.." "${1:?usage: source_shape.sh path/to/biref}"
