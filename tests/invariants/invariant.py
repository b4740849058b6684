#!/usr/bin/python3
"""The invariant layer: a scene and a variant of it that must agree.

    invariant.py EXE MPIEXEC BASE.prm [options]

Writes two parameter files derived from BASE.prm (--base-set and --set
change entries of the base and of the variant: 'Sub/Sub/Entry=value', a '*'
path part matching every numbered subsection, e.g. 'Materials/Material
*/Model=J2 plasticity'), runs both (--base-np, --np ranks), then compares
the physics columns of their statistics.csv at the times both have (the
last time only with --last):

  forces      reaction_*, contact_force_*             to --tol of the largest
  motion      displacement_*, max_abs_u, obstacle_*   base force / motion
  pressure    contact_pressure_*                      to --tol of its largest
  area        contact_area_* / contact_length_*       to --tol of its largest
  counts      contact_points_*                        equal (--counts=free: not)

A variant may live in another frame or unit system; its results are
mapped back before the comparison, by this script's own arithmetic:

  --rotate A [--axis a,b,c]  the variant is the base turned by A degrees
                             (2D: about z; 3D: about the axis): its vector
                             columns (x, y, z) are turned back by -A, and
                             max_abs_u (a largest component) is skipped
  --mirror x|y|z             the variant is the base mirrored: that
                             component of its vectors changes sign
  --units mm                 the variant is in mm, N, MPa where the base is
                             in m, N, Pa: lengths /1e3, pressures *1e6,
                             forces *1e3 in 2D (per unit thickness), areas
                             /1e6 in 3D
  --swap                     the variant swaps the slave and master sides
                             of its pairs (--set their boundary ids): the
                             force on the master changes sign
  --ignore KIND              a kind not compared (motion: a Dirichlet
                             value given instead as obstacle motion moves
                             the bodies by a rigid translation)

In --set values, '{R a, b}' is the vector (a, b) turned by --rotate, and
'{R e1; e2}' the turned vector of the expressions e1, e2 (a prescribed
displacement in the turned frame).

The solver counts (Newton iterations, cuts, cycles) are not compared:
the variants change the path, not the answer. --no-references drops the base's 'Output/Reference checks' (its
closed forms hold at the end of the path only, and the variant's path
differs) before the --base-set entries are applied. Prints every compared column with its largest difference and
exits 0 only if all are within bounds. The prm editing is the only thing
this script knows of the program: the quantities compared are the
program's results, the reference is the other run.
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from prm_edit import absolute_paths, edit_prm, remove_section  # noqa: E402


def run_scene(exe, mpiexec, prm_lines, np, directory, name):
    """Writes @prm_lines (results into @directory/results) and runs them on
    @np ranks; returns the exit code, the log's last lines and the
    statistics.csv rows (None unless the run exited with 0)."""
    os.makedirs(directory, exist_ok=True)
    out = os.path.join(directory, "results")
    prm = os.path.join(directory, name + ".prm")
    with open(prm, "w") as f:
        f.write("\n".join(edit_prm(prm_lines, ["Output/Directory=" + out])) + "\n")
    command = [exe, prm] if np == 1 else [mpiexec, "-n", str(np), "--allow-run-as-root", exe, prm]
    log = os.path.join(directory, name + ".log")
    with open(log, "w") as f:
        code = subprocess.call(command, stdout=f, stderr=subprocess.STDOUT, cwd=directory)
    tail = "".join(open(log).readlines()[-8:])
    if code != 0:
        return code, tail, None
    with open(os.path.join(out, "statistics.csv")) as f:
        return code, tail, list(csv.DictReader(f))


def run(exe, mpiexec, prm_lines, np, directory, name):
    code, tail, rows = run_scene(exe, mpiexec, prm_lines, np, directory, name)
    if code != 0:
        print("FAIL: the %s run (%d rank(s)) exited with code %d; its last lines:" % (name, np, code))
        print(tail)
        sys.exit(1)
    return rows


KIND = [
    ("counts", re.compile(r"contact_points_")),
    ("solver", re.compile(r"^(newton_iterations|step_cuts|cycle_detections|points_frozen)$")),
    ("forces", re.compile(r"^(reaction_|contact_force_)")),
    ("motion", re.compile(r"^(displacement_|max_abs_u|obstacle_displacement_)")),
    ("pressure", re.compile(r"^contact_pressure_")),
    ("area", re.compile(r"^contact_(area|length)_")),
]


def kind(column):
    for k, pattern in KIND:
        if pattern.search(column):
            return k
    return None


def rotation(angle, axis, dim):
    """The matrix turning by @angle degrees (2D: about z; 3D: about @axis,
    Rodrigues' formula)."""
    a = math.radians(angle)
    c, s = math.cos(a), math.sin(a)
    if dim == 2:
        return [[c, -s], [s, c]]
    n = math.sqrt(sum(x * x for x in axis))
    k = [x / n for x in axis]
    K = [[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]]
    KK = [[sum(K[i][m] * K[m][j] for m in range(3)) for j in range(3)] for i in range(3)]
    return [[(i == j) + s * K[i][j] + (1 - c) * KK[i][j] for j in range(3)] for i in range(3)]


def expand(value, R):
    """'{R a, b}' and '{R e1; e2}' in @value replaced by the turned vector."""
    def turn(m):
        text = m.group(1)
        sep = ";" if ";" in text else ","
        parts = [p.strip() for p in text.split(sep)]
        try:
            v = [float(p) for p in parts]
            return ", ".join(repr(sum(R[i][j] * v[j] for j in range(len(v)))) for i in range(len(v)))
        except ValueError:
            return "; ".join(" + ".join("(%r)*(%s)" % (R[i][j], parts[j]) for j in range(len(parts)))
                             for i in range(len(parts)))
    return re.sub(r"\{R ([^}]*)\}", turn, value)


AXES = "xyz"


def to_base_frame(rows, dim, R, mirror, units, axisymmetric=False, swap=False):
    """The variant's rows mapped back to the base's frame and units (an
    axisymmetric model's forces are totals [N], its areas areas), and to
    the base's sides of the pairs (@swap: the force on the master is the
    other body's)."""
    length = 1e-3 if units == "mm" else 1.0
    per_thickness = dim == 2 and not axisymmetric
    area_power = 2 if axisymmetric else dim - 1
    out = []
    for row in rows:
        row = dict(row)
        for column in list(row):
            k = kind(column)
            if swap and re.match(r"contact_force_\d+_[xyz]$", column):
                row[column] = -float(row[column])
            if k == "forces" and per_thickness:
                row[column] = float(row[column]) / length
            elif k == "motion":
                row[column] = float(row[column]) * length
            elif k == "pressure":
                row[column] = float(row[column]) / length ** 2
            elif k == "area":
                row[column] = float(row[column]) * length ** area_power
        stems = {c[:-2] for c in row if c[-2:] in ("_x", "_y", "_z")}
        for stem in stems:
            names = [stem + "_" + AXES[d] for d in range(dim)]
            if not all(n in row for n in names):
                continue
            v = [float(row[n]) for n in names]
            if R is not None:  # base = R^T variant
                v = [sum(R[j][i] * v[j] for j in range(dim)) for i in range(dim)]
            if mirror:
                v[AXES.index(mirror)] = -v[AXES.index(mirror)]
            for n, x in zip(names, v):
                row[n] = x
        out.append(row)
    return out


def compare(base, variant, tol, last, counts, ignore=(), skip=()):
    by_time = {round(float(r["time"]), 9): r for r in variant}
    pairs = [(b, by_time.get(round(float(b["time"]), 9))) for b in base]
    pairs = [(b, v) for b, v in pairs if v is not None]
    if last:
        pairs = pairs[-1:] if round(float(base[-1]["time"]), 9) in by_time else []
    if not pairs:
        print("FAIL: the runs share no time")
        return False
    scale = {}
    for b, _ in pairs:
        for column, value in b.items():
            k = kind(column)
            if k in ignore:
                continue
            if k in ("forces", "motion"):
                scale[k] = max(scale.get(k, 0), abs(float(value)))
            elif k in ("pressure", "area"):
                scale[column] = max(scale.get(column, 0), abs(float(value)))
    ok = True
    worst = {}
    for b, v in pairs:
        for column, value in b.items():
            k = kind(column)
            if k is None or k == "solver" or k in ignore or column in skip or (k == "counts" and not counts):
                continue
            if column not in v:
                print("FAIL: column %s missing in the variant" % column)
                return False
            if k == "counts":
                if int(value) != int(v[column]):
                    print("FAIL: %s at t = %s: %s against %s" % (column, b["time"], value, v[column]))
                    ok = False
                continue
            s = scale.get(k, scale.get(column, 0))
            d = abs(float(value) - float(v[column]))
            r = d / s if s > 0 else d
            worst[column] = max(worst.get(column, 0), r)
    for column, r in sorted(worst.items()):
        print("  %-36s largest difference %.2e of its scale" % (column, r))
        if r > tol:
            ok = False
    print("%d time(s) compared, worst %.2e (bar %.1e)" % (len(pairs), max(worst.values() or [0]), tol))
    return ok


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("exe")
    parser.add_argument("mpiexec")
    parser.add_argument("base")
    parser.add_argument("--base-set", action="append", default=[])
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--base-np", type=int, default=1)
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--tol", type=float, default=1e-8)
    parser.add_argument("--last", action="store_true")
    parser.add_argument("--counts", default="equal")
    parser.add_argument("--keep", default="")
    parser.add_argument("--no-references", action="store_true")
    parser.add_argument("--rotate", type=float, default=None)
    parser.add_argument("--axis", default="0, 0, 1")
    parser.add_argument("--mirror", choices=list(AXES), default=None)
    parser.add_argument("--units", choices=["mm"], default=None)
    parser.add_argument("--swap", action="store_true")
    parser.add_argument("--ignore", action="append", default=[], choices=[k for k, _ in KIND])
    a = parser.parse_args()
    base_dir = os.path.dirname(os.path.abspath(a.base))
    base_lines = absolute_paths(open(a.base).read().splitlines(), base_dir)
    if a.no_references:
        base_lines = remove_section(base_lines, "Output/Reference checks")
    base_lines = edit_prm(base_lines, a.base_set)
    dim = 2
    for line in base_lines:
        m = re.match(r"\s*set\s+Dimension\s*=\s*(\d)", line)
        if m:
            dim = int(m.group(1))
    axisymmetric = any(re.match(r"\s*set\s+Axisymmetric\s*=\s*true", line) for line in base_lines)
    R = None
    if a.rotate is not None:
        R = rotation(a.rotate, [float(x) for x in a.axis.split(",")], dim)
    variant_lines = edit_prm(base_lines, [expand(x, R) if R else x for x in a.set])
    top = a.keep or tempfile.mkdtemp(prefix="invariant_")
    base = run(a.exe, a.mpiexec, base_lines, a.base_np, os.path.join(top, "base"), "base")
    variant = run(a.exe, a.mpiexec, variant_lines, a.np, os.path.join(top, "variant"), "variant")
    if R is not None or a.mirror or a.units or a.swap:
        variant = to_base_frame(variant, dim, R, a.mirror, a.units, axisymmetric, a.swap)
    # max_abs_u, the largest nodal component, depends on the frame.
    skip = ["max_abs_u"] if R is not None else []
    ok = compare(base, variant, a.tol, a.last, a.counts == "equal", a.ignore, skip)
    print("PASS: invariant holds" if ok else "FAIL: invariant broken")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
