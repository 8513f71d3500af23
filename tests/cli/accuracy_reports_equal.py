"""accuracy_reports_equal.py A.json B.json: exits non-zero unless two `biref accuracy --json`
reports are equal apart from timing and thread count, and list materials. Needs only the standard
library (run by /usr/bin/python3 like the other test scripts)."""
import json
import sys


def strip(v):
    if isinstance(v, dict):
        return {k: strip(x) for k, x in v.items() if k not in ("elapsed_s", "threads")}
    if isinstance(v, list):
        return [strip(x) for x in v]
    return v


a, b = (strip(json.load(open(p))) for p in sys.argv[1:3])
if a != b:
    sys.exit("the two reports differ")
if not a.get("materials"):
    sys.exit("no materials in the report")
