"""Every default the documentation quotes agrees with the command's --help.

Three kinds of quotes are checked:
  1. automatically, every "`--option ...` ... (default V)" in docs/*.md and README.md: some
     command's --help must describe --option with the same default V;
  2. the defaults quoted in prose (e.g. "P = 500 N"), listed below in CLAIMS: the text must be in
     the document and the option's --help must state that default.
  3. the error messages quoted in MESSAGES: the command prints them.
A changed default or message therefore fails here until the documentation says the same.

usage: /usr/bin/python3 doc_defaults.py path/to/biref REPO_ROOT
"""
import glob
import json
import os
import re
import subprocess
import sys
import tempfile

BIREF, ROOT = sys.argv[1], os.path.abspath(sys.argv[2])
COMMANDS = ["slab", "spectrum", "accuracy", "render", "diff", "bench", "figure", "gl-data",
            "photoelastic", "photoelastic demodulate"]

# (document, text quoted in it, command, option, default in that option's --help)
CLAIMS = [
    ("PHOTOELASTICITY.md", "disk R = 25 mm", "photoelastic", "--radius-mm", "25"),
    ("PHOTOELASTICITY.md", "h = 6 mm, P = 500 N", "photoelastic", "--load-N", "500"),
    ("PHOTOELASTICITY.md", "hole a = 5 mm", "photoelastic", "--radius-mm", "5"),
    ("PHOTOELASTICITY.md", "in a 60 × 60 mm plate", "photoelastic", "--width-mm", "60"),
    ("PHOTOELASTICITY.md", "S = 4 MPa along x", "photoelastic", "--stress-MPa", "4"),
    ("PHOTOELASTICITY.md", "beam 100 × 20 mm", "photoelastic", "--length-mm", "100"),
    ("PHOTOELASTICITY.md", "beam 100 × 20 mm", "photoelastic", "--depth-mm", "20"),
    ("PHOTOELASTICITY.md", "M = 2000 N·mm", "photoelastic", "--moment-Nmm", "2000"),
    ("PHOTOELASTICITY.md", "(air by default; `--eta-i`", "photoelastic", "--eta-i", "1"),
    ("PHOTOELASTICITY.md", "`--stress-unit MPa|Pa` (default\nMPa)", "photoelastic", "--stress-unit", "MPa"),
    ("PHOTOELASTICITY.md", "(defaults `x, y, sxx, syy, txy`", "photoelastic", "--columns", "x, y, sxx, syy, txy"),
    ("ACCURACY.md", "`--check-samples N` its check\n(default 4N)", "accuracy", "--check-samples", "4x"),
    ("ACCURACY.md", "reference 262144 samples", "accuracy", "--reference-samples", "262144"),
    ("ACCURACY.md", "1° × 16 azimuths, 0–89°", "accuracy", "--theta-step-deg", "1"),
    ("ACCURACY.md", "1° × 16 azimuths, 0–89°", "accuracy", "--azimuths", "16"),
    ("ACCURACY.md", "1° × 16 azimuths, 0–89°", "accuracy", "--theta-max-deg", "89"),
    ("SCENES.md", "samples, default 64)", "render", "--spectral-samples", "64"),
    ("SCENES.md", "(default scene `examples/fig9a.json` at 1920 × 1080", "bench", "--scene", "examples/fig9a.json"),
    ("SCENES.md", "(default scene `examples/fig9a.json` at 1920 × 1080", "bench", "--width", "1920"),
    ("SCENES.md", "(default scene `examples/fig9a.json` at 1920 × 1080", "bench", "--height", "1080"),
    ("PERFORMANCE.md", "(default: `examples/fig9a.json` at 1920 × 1080", "bench", "--width", "1920"),
    ("GPU.md", "# default: --backend cpu", "render", "--backend", "cpu"),
    ("PHYSICS.md", "Defaults: tolerance 1e-3, cap 8", "render", "--tolerance", "1e-3"),
    ("PHYSICS.md", "default 380–700 nm", "accuracy", "--range-nm", "380,700"),
]

# (document, error message quoted in it, scene edit or None, biref arguments): the command, run in
# a scratch directory holding scene.json (examples/fig9a.json after the edit), must print the
# quoted line on stderr.
def zero_thickness(scene):
    slab = scene["slabs"][0]
    slab.pop("thickness_um", None)
    slab["thickness_mm"] = 0
    return scene


MESSAGES = [
    ("SCENES.md", "biref render: error: scene.json: slabs[0].thickness_mm: must be positive", zero_thickness,
     ["render", "scene.json", "-o", "out.png"]),
]


def check_messages():
    fails = 0
    with tempfile.TemporaryDirectory() as tmp:
        for doc, quoted, edit, args in MESSAGES:
            text = open(os.path.join(ROOT, "docs", doc), encoding="utf-8").read()
            if quoted not in re.sub(r"\s*\n\s*", " ", text):
                print(f"FAIL ({doc}): no longer quotes {quoted!r} (update this test's list with the doc)")
                fails += 1
            scene = json.load(open(os.path.join(ROOT, "examples", "fig9a.json"), encoding="utf-8"))
            with open(os.path.join(tmp, "scene.json"), "w", encoding="utf-8") as f:
                json.dump(edit(scene) if edit else scene, f)
            out = subprocess.run([os.path.abspath(BIREF)] + args, cwd=tmp, capture_output=True, text=True)
            if quoted not in out.stderr:
                print(f"FAIL ({doc}): quotes {quoted!r}, biref {' '.join(args[:1])} prints {out.stderr.strip()!r}")
                fails += 1
    return fails, len(MESSAGES)


def help_text(cmd):
    out = subprocess.run([BIREF] + cmd.split() + ["--help"], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"FAIL: biref {cmd} --help exited {out.returncode}")
    return out.stdout


def option_entries(text):
    """{option: [description, ...]}: an option's text runs to the next option of the same line
    (two or more spaces, then a dash) or of a later line, continuation lines included."""
    entries = {}
    current = []
    for line in text.splitlines():
        stripped = line.lstrip()
        if stripped.startswith("-") and len(line) - len(stripped) <= 8:
            current = []
            for chunk in re.split(r"\s{2,}(?=-)", stripped):
                names = re.findall(r"--[A-Za-z0-9][A-Za-z0-9-]*", chunk.split("  ")[0])
                current = [[n, chunk] for n in names]
                for n in current:
                    entries.setdefault(n[0], []).append(n)
        elif stripped and current and len(line) - len(stripped) > 8:
            for n in current:
                n[1] += " " + stripped
        else:
            current = []
    return {k: [d for _, d in v] for k, v in entries.items()}


def number(text):
    m = re.fullmatch(r"\s*([-+]?[0-9.]+(?:e[-+]?[0-9]+)?)\s*(%?)\s*", text)
    if not m:
        return None
    try:
        v = float(m.group(1))
    except ValueError:
        return None
    return v / 100 if m.group(2) else v


def same_default(doc_value, description):
    """The description says "default" followed by doc_value (numbers compare as numbers)."""
    doc_value = re.sub(r"^(\d+)N$", r"\1x", doc_value.replace("`", "").strip())  # "4N": 4x the reference
    if doc_value and re.search(re.escape(doc_value) + r" \(default[);,]", description):  # "cpu (default)"
        return True
    for m in re.finditer(r"default[:=]?\s*([^);]*)", description):
        said = m.group(1).strip()
        if re.match(re.escape(doc_value) + r"(?![0-9A-Za-z.])", said):
            return True
        a, b = number(doc_value), number(re.split(r"[ ,;]", said)[0] if said else "")
        if a is not None and b is not None and abs(a - b) <= 1e-12 * max(1.0, abs(a)):
            return True
        # "(default for `--method analytic` ...)": the first word decides.
        if doc_value.split()[:1] == said.split()[:1] == ["for"]:
            return True
    return False


def main():
    helps = {cmd: option_entries(help_text(cmd)) for cmd in COMMANDS}
    fails = 0
    checked = 0

    def described(option, cmds=None):
        out = []
        for cmd in cmds or COMMANDS:
            out += helps[cmd].get(option, [])
        return out

    # docs/CLI.md's option tables are printed from the tables --help comes from (grammar.sh checks).
    docs = sorted(p for p in glob.glob(os.path.join(ROOT, "docs", "*.md")) if not p.endswith("CLI.md"))
    docs += [os.path.join(ROOT, "README.md")]
    quote = re.compile(r"`(--[A-Za-z][A-Za-z0-9-]*)[^`]*`([^`(]{0,80}?)\(default[: ]+([^)]*)\)")
    for path in docs:
        text = open(path, encoding="utf-8").read()
        # Paragraphs as single lines, so a quote may wrap.
        flat = re.sub(r"(?<!\n)\n(?!\n)", " ", text)
        for m in quote.finditer(flat):
            option, value = m.group(1), m.group(3)
            descriptions = described(option)
            checked += 1
            if not descriptions:
                print(f"FAIL ({os.path.basename(path)}): {option} is in no command's --help")
                fails += 1
            elif not any(same_default(value, d) for d in descriptions):
                print(f"FAIL ({os.path.basename(path)}): {option} (default {value}) but --help says: "
                      + " | ".join(descriptions))
                fails += 1

    for doc, quoted, cmd, option, default in CLAIMS:
        checked += 1
        text = open(os.path.join(ROOT, "docs", doc), encoding="utf-8").read()
        if quoted.replace("\n", " ") not in re.sub(r"\s*\n\s*", " ", text):
            print(f"FAIL ({doc}): no longer says {quoted!r} (update this test's list with the doc)")
            fails += 1
        descriptions = described(option, [cmd])
        if not any(same_default(default, d) for d in descriptions):
            print(f"FAIL ({doc}): says {quoted!r}, but biref {cmd} --help on {option}: "
                  + (" | ".join(descriptions) or "not listed"))
            fails += 1

    f, n = check_messages()
    fails += f
    print(f"{checked} quoted defaults and {n} quoted messages checked")
    if fails:
        print(f"{fails} failure(s)")
        sys.exit(1)
    print("all passed")


main()
