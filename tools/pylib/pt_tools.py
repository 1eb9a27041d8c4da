"""What the Python tools in tools/ share: matplotlib (or how to get it), the
machine's description (lscpu), the error of an image against a reference
(pt-imgerr, docs/samplers.md), and a benchmark page's sections (write_section). Imported by tools/compare/pathtracer_compare.py,
tools/study/samplers/run_study.py and tools/study/compare_samplers/compare_samplers.py.
"""
import json
import os
import subprocess
import sys


def need_matplotlib():
    """True if matplotlib imports. Otherwise, if Debian's /usr/bin/python3 has it
    (a pyenv or venv interpreter often lacks it), re-executes this script with
    that one; else prints how to install it and returns False."""
    try:
        import matplotlib  # noqa: F401
        return True
    except ImportError:
        debian = "/usr/bin/python3"
        if os.path.realpath(sys.executable) != os.path.realpath(debian) and os.path.exists(debian):
            probe = subprocess.run([debian, "-c", "import matplotlib"], capture_output=True)
            if probe.returncode == 0:  # this interpreter lacks it, Debian's has it
                os.execv(debian, [debian] + sys.argv)
        print("error: matplotlib is missing: install it with `sudo apt-get install -y python3-matplotlib`"
              " (Debian 12) and run this tool with /usr/bin/python3", file=sys.stderr)
        return False


def lscpu():
    """The machine's `lscpu` text (every figure the tools write is stated with it)."""
    try:
        return subprocess.run(["lscpu"], capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return "(lscpu not available)"


def image_error(imgerr_exe, test, reference, rect=None):
    """pt-imgerr's {"mse", "rmse", "rel_mse", ...} of `test` against `reference`;
    raises RuntimeError with the tool's message when it fails (size mismatch...)."""
    cmd = [imgerr_exe, test, reference, "--json"] + (["--rect", rect] if rect else [])
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError((r.stderr or r.stdout).strip())
    return json.loads(r.stdout)


def write_section(doc_path, marker, title, text, runs_entry, heading="# Results"):
    """Writes `text` (a section starting "## TITLE") into the markdown page
    `doc_path` below `marker` (the page starts with `heading` if new): a rerun
    replaces its own section, the machine's lscpu goes last; and `runs_entry`
    under `title` into the page's JSON record beside it (same name, .json)."""
    doc = open(doc_path).read() if os.path.exists(doc_path) else heading + "\n\n" + marker + "\n"
    if marker not in doc:
        doc += "\n" + marker + "\n"
    head, tail = doc.split(marker, 1)
    parts = [p for p in ("\n" + tail).split("\n## ") if p.strip()]
    kept = ["## " + p.strip() for p in parts if not p.startswith(title + "\n") and not p.startswith("Machine")]
    machine = "## Machine\n\n```\n" + lscpu().strip() + "\n```"
    with open(doc_path, "w") as f:
        f.write(head + marker + "\n\n" + "\n\n".join(kept + [text.strip(), machine]) + "\n")
    runs = os.path.splitext(doc_path)[0] + ".json"
    data = json.load(open(runs)) if os.path.exists(runs) else {}
    data[title] = runs_entry
    with open(runs, "w") as f:
        json.dump(data, f, indent=1)
