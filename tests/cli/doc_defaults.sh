#!/usr/bin/env bash
# The defaults quoted in docs/ and README.md agree with the commands' --help (doc_defaults.py).
# Debian's python3 (standard library only).
exec /usr/bin/python3 "$(dirname "$0")/doc_defaults.py" "${1:?usage: doc_defaults.sh path/to/biref}" \
  "$(dirname "$0")/../.."
