#!/usr/bin/python3
"""check_files.py <results directory> [steps]

Every result file in the directory is complete and parseable (the rule of
user_guide.md, "How output is kept"):
 - statistics.csv, newton_history.csv and every contact_NNNN.csv: a header
   and rows (maybe none) with the same number of fields, a complete last
   line, numbers where numbers belong;
 - every solution_NNNN.R.vtu and .pvtu (and contact_surface_NNNN.R.vtu and
   .pvtu): complete XML (a VTKFile element, ends with </VTKFile>);
 - solution.pvd (and contact_surface.pvd): complete XML listing only .pvtu
   files that exist and are complete, and each of those names only pieces
   that exist;
 - the steps agree: a step in statistics.csv has its contact CSV and its
   PVTU; the PVD lists steps 1..M, M at most one step ahead of statistics.
Temporary files (*.tmp, left by a kill) are not results and are skipped;
so are symbolic links (tests point some at /dev/full). With [steps], the
directory must hold exactly the results of a run of that many steps and no
temporary file. Prints what it checked; exit code 1 on the first failures.
"""
import csv
import os
import re
import sys
import xml.etree.ElementTree as ET

directory = sys.argv[1]
expected_steps = int(sys.argv[2]) if len(sys.argv) > 2 else None
fails = []


def regular(name):
    path = os.path.join(directory, name)
    return os.path.isfile(path) and not os.path.islink(path)


def read_text(name):
    with open(os.path.join(directory, name), "rb") as f:
        data = f.read()
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        fails.append("%s: not UTF-8 text" % name)
        return ""


def table(name, text_columns=(), may_be_empty=()):
    """The rows of a CSV file (header first) if it is complete, else None."""
    text = read_text(name)
    if not text.endswith("\n"):
        fails.append("%s: last line incomplete (no line end): %r" % (name, text[-80:]))
        return None
    rows = list(csv.reader(text.splitlines()))
    if not rows or not rows[0]:
        fails.append("%s: no header" % name)
        return None
    header = rows[0]
    for k, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            fails.append("%s line %d: %d fields, header has %d" % (name, k, len(row), len(header)))
            return None
        for column, value in zip(header, row):
            if column in text_columns:
                if not value:
                    fails.append("%s line %d: empty %s" % (name, k, column))
                    return None
                continue
            if column in may_be_empty and value == "":
                continue
            try:
                float(value)
            except ValueError:
                fails.append("%s line %d: %s = %r is not a number" % (name, k, column, value))
                return None
    return rows


def vtk_xml(name):
    """The root of a complete VTK XML file, else None."""
    text = read_text(name)
    if not text.rstrip().endswith("</VTKFile>"):
        fails.append("%s: incomplete, does not end with </VTKFile>" % name)
        return None
    try:
        root = ET.fromstring(text)
    except ET.ParseError as e:
        fails.append("%s: not well-formed XML: %s" % (name, e))
        return None
    if root.tag != "VTKFile":
        fails.append("%s: root element %s, expected VTKFile" % (name, root.tag))
        return None
    return root


names = sorted(n for n in os.listdir(directory) if regular(n) and not n.endswith(".tmp"))
temporaries = sorted(n for n in os.listdir(directory) if n.endswith(".tmp"))
checked = {"csv": 0, "vtu": 0, "pvtu": 0}

stat_steps = []
if "statistics.csv" in names:
    rows = table("statistics.csv")
    if rows:
        stat_steps = [int(r[0]) for r in rows[1:]]
        if stat_steps != list(range(1, len(stat_steps) + 1)):
            fails.append("statistics.csv: steps %s, expected 1, 2, ..." % stat_steps[:10])
history_steps = []
if "newton_history.csv" in names:
    rows = table("newton_history.csv")
    if rows:
        history_steps = sorted(set(int(r[0]) for r in rows[1:]))
for name in names:
    if re.fullmatch(r"contact_[0-9]+\.csv", name):
        # An empty gap: the point found no master face (user_guide.md).
        if table(name, text_columns=("status",), may_be_empty=("gap",)) is not None:
            checked["csv"] += 1
    elif re.fullmatch(r"(solution|contact_surface)_[0-9]+(\.[0-9]+\.vtu|\.pvtu)", name):
        root = vtk_xml(name)
        if root is not None:
            checked["vtu" if name.endswith(".vtu") else "pvtu"] += 1
        if root is not None and name.endswith(".pvtu"):
            for piece in root.iter("Piece"):
                if not regular(piece.get("Source", "")):
                    fails.append("%s: piece %s missing" % (name, piece.get("Source")))

def pvd_steps_of(stem):
    """The steps listed in STEM.pvd (all of whose files must exist)."""
    steps = []
    root = vtk_xml(stem + ".pvd")
    if root is not None:
        for dataset in root.iter("DataSet"):
            listed = dataset.get("file", "")
            match = re.fullmatch(stem + r"_([0-9]+)\.pvtu", listed)
            if not match or not regular(listed):
                fails.append("%s.pvd lists %r: missing" % (stem, listed))
                continue
            steps.append(int(match.group(1)))
        if steps != list(range(1, len(steps) + 1)):
            fails.append("%s.pvd: steps %s, expected 1, 2, ..." % (stem, steps[:10]))
    return steps


series = [stem for stem in ("solution", "contact_surface") if stem + ".pvd" in names]
listed = {stem: pvd_steps_of(stem) for stem in series}
pvd_steps = listed.get("solution", [])

# statistics.csv is written last in a step: its steps have all their files.
last = len(stat_steps)
kinds = [pattern for pattern in ("contact_%04d.csv", "solution_%04d.pvtu",
                                 "contact_surface_%04d.pvtu")
         if any(re.fullmatch(pattern.replace("%04d", "[0-9]+").replace(".", r"\."), n) for n in names)]
for step in stat_steps:
    for name in (pattern % step for pattern in kinds):
        if name not in names:
            fails.append("step %d is in statistics.csv but %s is missing" % (step, name))
for stem, steps in listed.items():
    if steps and not last <= len(steps) <= last + 1:
        fails.append("%s.pvd lists %d steps, statistics.csv %d" % (stem, len(steps), last))
if history_steps and history_steps[-1] > last + 1:
    fails.append("newton_history.csv has step %d, statistics.csv %d" % (history_steps[-1], last))

if expected_steps is not None:
    if temporaries:
        fails.append("temporary files left: %s" % temporaries)
    ranks = sorted(set(re.findall(r"solution_0001\.([0-9]+)\.vtu", " ".join(names))))
    want = {"statistics.csv", "newton_history.csv", "parameters.prm"}
    # Every scene writes the solution series; one with contact (contact
    # CSVs) also the contact surface series.
    expected_series = ["solution"]
    if any(re.fullmatch(r"contact_[0-9]+\.csv", n) for n in names):
        expected_series.append("contact_surface")
    want |= {stem + ".pvd" for stem in expected_series}
    for step in range(1, expected_steps + 1):
        want |= {"contact_%04d.csv" % step}
        for stem in expected_series:
            want |= {"%s_%04d.pvtu" % (stem, step)}
            want |= {"%s_%04d.%s.vtu" % (stem, step, r) for r in ranks}
    ours = {n for n in names if re.fullmatch(
        r"(solution|contact_surface)_[0-9]+\.[0-9]+\.vtu|"
        r"(solution|contact_surface)_[0-9]+\.pvtu|(solution|contact_surface)\.pvd|"
        r"contact_[0-9]+\.csv|statistics\.csv|newton_history\.csv|parameters\.prm", n)}
    if ours != want:
        fails.append("files of a %d-step run: missing %s, extra %s"
                     % (expected_steps, sorted(want - ours)[:6], sorted(ours - want)[:6]))

for f in fails[:10]:
    print("FAIL: " + f)
if fails:
    sys.exit(1)
print("PASS: %s complete: %d step(s) in statistics.csv, %d in solution.pvd, "
      "%d contact CSV, %d VTU, %d PVTU; %d temporary file(s) skipped"
      % (directory, last, len(pvd_steps), checked["csv"], checked["vtu"],
         checked["pvtu"], len(temporaries)))
