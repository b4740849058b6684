#!/usr/bin/python3
"""The pairwise layer: every pair of feature levels in some checked scene.

    pairwise.py EXE MPIEXEC [--list] [--coverage] [--keep DIR]

The features (factors) and their levels:

  model        plane strain | plane stress | axisymmetric | 3D
  material     every registered 'Model' (asked from the program)
  kinematics   every 'Kinematics'
  volumetric   every 'Volumetric strain'
  degree       1 | 2
  rule         every 'Integration rule'
  master       every 'Master' (a meshed body or each registered obstacle)
  load         Dirichlet value | Dirichlet along the normal (a frame
               condition) | Neumann pressure | body force | obstacle motion
  friction     0 | 0.3
  stepping     one step | three steps | a list of times
  adaptivity   none | one cycle at the last step
  solver       every 'Linear solver/Type' the program takes with contact
  ranks        1 | 2
  invariant    units (the scene in mm, N, MPa) | turned (by 90 degrees
               about z, with the Dirichlet conditions given as directions)
               | ranks (the same scene on the other number of ranks)

The registered names come from the program itself (the message it gives
for an unknown value lists its pattern), so a material, rule or obstacle
registered in the library gains its rows here without an edit. Pairs the
program refuses (a model without finite strain, a rule without Q2, ...)
are found by probing it with a one-step scene that sets the two levels;
they are left out of the possible pairs and out of every row.

A greedy covering (deterministic) then picks rows until every possible pair
of levels is in some row. Each row is one scene: a block of 1 x 0.5 (x
0.5 in 3D) pressed onto a master below it, held by rollers on its x = 0
side (and z = 0 in 3D), the same rollers on a meshed master body whose
bottom is fixed; a sphere, cylinder or level-set master is curved (radius
5) and touches at x = 0, so the scene is a half (quarter) model. The
row's invariant is checked against a second run (tests/invariants/
invariant.py's comparison): forces, displacements, pressures and areas
to 2e-6 of their scale (statistics.csv has 7 digits), statuses exactly.

--list prints the rows, --coverage the pairs covered per factor pair (the
table of doc/verification.md); without them every row is run and the
script exits 1 if a row breaks its invariant or a run fails.
"""
import argparse
import itertools
import os
import random
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from invariant import compare, rotation, run_scene, to_base_frame  # noqa: E402
from prm_edit import edit_prm  # noqa: E402

TOLERANCE = 2e-6
LENGTH, HEIGHT, WIDTH, RADIUS = 1.0, 0.5, 0.5, 5.0
# J2: a prescribed displacement (stress about 4.4) yields the body, a
# force-driven load (stress about 2, its limit load is higher with the
# hardening) yields it where the contact concentrates the stress.
MODULUS, POISSON, YIELD, HARDENING = 1e3, 0.3, 3.0, 1e2
PRESS = 2e-3  # prescribed displacement of the top
PRESSURE = 2.0  # about the stress of that displacement
BODY_FORCE = PRESSURE / HEIGHT


def registered(exe, path, workdir):
    """The values the program allows for the entry at @path: its answer
    to an unknown value names the Selection pattern."""
    prm = os.path.join(workdir, "ask.prm")
    with open(prm, "w") as f:
        f.write("\n".join(edit_prm(["set Dimension = 2"], ["Contact/Number of contact pairs=1", path + "=not-a-value"])) + "\n")
    out = subprocess.run([exe, prm], capture_output=True, text=True, cwd=workdir)
    m = re.search(r"\[Selection ([^\]]*)\]", out.stdout + out.stderr)
    if not m:
        sys.exit("pairwise.py: the program did not name the values of " + path)
    return [v.strip() for v in m.group(1).split("|") if v.strip()]


def factors(exe, workdir):
    return [
        ("model", ["plane strain", "plane stress", "axisymmetric", "3D"]),
        ("material", registered(exe, "Materials/Material 1/Model", workdir)),
        ("kinematics", registered(exe, "Materials/Material 1/Kinematics", workdir)),
        ("volumetric", registered(exe, "Finite element/Volumetric strain", workdir)),
        ("degree", ["1", "2"]),
        ("rule", registered(exe, "Contact/Integration rule", workdir)),
        ("master", registered(exe, "Contact/Pair 1/Master", workdir)),
        ("load", ["Dirichlet", "Dirichlet normal", "pressure", "body force", "obstacle motion"]),
        ("friction", ["0", "0.3"]),
        ("stepping", ["one step", "three steps", "times"]),
        ("adaptivity", ["none", "one cycle"]),
        ("solver", registered(exe, "Linear solver/Type", workdir)),
        ("ranks", ["1", "2"]),
        ("invariant", ["units", "turned", "ranks"]),
    ]


# Pairs the scene itself cannot hold (not the program's choices): a frame
# turned about z is not axisymmetric.
def structural(a, la, b, lb):
    pair = {a: la, b: lb}
    if pair.get("model") == "axisymmetric" and pair.get("invariant") == "turned":
        return False
    return True


class Scene:
    """The parameter assignments of one row, in SI (scale 1) or mm, N, MPa
    (scale 1e3), in its frame or turned by 90 degrees about z."""

    def __init__(self, row, scale=1.0, turned=False, workdir="."):
        self.row, self.s, self.turned, self.workdir = row, scale, turned, workdir
        self.dim = 3 if row["model"] == "3D" else 2
        self.lines = []

    def set(self, path, value):
        self.lines.append("%s=%s" % (path, value))

    def numbers(self, v):
        """A vector in this frame (turned: (x, y) -> (-y, x))."""
        v = [float(x) for x in list(v)[: self.dim]]
        if self.turned:
            v[0], v[1] = -v[1], v[0]
        return v

    def vec(self, v):
        return ", ".join("%.17g" % x for x in self.numbers(v))

    def motion(self, v):
        """The vector @v times t, as Dimension expressions."""
        return "; ".join(("%.17g*t" % x) if x else "0" for x in self.numbers(v))

    def length(self, x):
        return "%.17g" % (x * self.s)

    def point(self, p):
        return self.vec([x * self.s for x in p])

    def dirichlet(self, k, ids, axis, value):
        """u . e_axis = value on @ids: Cartesian in the base frame, a
        direction condition in the turned one."""
        d = "Boundary conditions/Dirichlet %d/" % k
        self.set(d + "Boundary id", ids)
        if self.turned:
            e = [0.0] * 3
            e[axis] = 1.0
            self.set(d + "Components", "direction")
            self.set(d + "Direction", self.vec(e))
        else:
            self.set(d + "Components", "xyz"[axis])
        self.set(d + "Values", value)

    def build(self):
        r, dim, s = self.row, self.dim, self.s
        self.set("Dimension", dim)
        if r["model"] == "axisymmetric":
            self.set("Axisymmetric", "true")
        if r["model"] == "plane stress":
            self.set("Plane stress", "true")
        two = r["master"] == "body"
        slave = 2 if two else 1
        self.set("Geometry/Number of bodies", 2 if two else 1)
        top = [LENGTH, HEIGHT, WIDTH]
        cells = ["4", "2", "2"] if dim == 2 else ["2", "2", "2"]
        self.block(slave, [0, 0, 0], top, cells)
        if two:
            self.block(1, [0, -HEIGHT, 0], [LENGTH, 0, WIDTH], ["3", "2", "2"] if dim == 2 else ["3", "1", "3"])
        # Materials: one per body (ids 1 and 2 of the generated blocks).
        self.set("Materials/Number of materials", 2 if two else 1)
        for m in range(1, 3 if two else 2):
            self.material(m)
        self.set("Finite element/Degree", r["degree"])
        self.set("Finite element/Volumetric strain", r["volumetric"])
        self.conditions(slave, two)
        self.contact(slave, two)
        self.stepping()
        if r["adaptivity"] == "one cycle":
            self.set("Adaptive refinement/Cycles", 1)
            self.set("Adaptive refinement/Refinement fraction", 0.3)
        self.set("Linear solver/Type", r["solver"])
        self.set("Output/Timing summary", "false")
        return self.lines

    def block(self, b, lower, upper, cells):
        g = "Geometry/Body %d/" % b
        self.set(g + "Shape", "block")
        self.set(g + "Block/Lower corner", ", ".join(self.length(x) for x in lower[: self.dim]))
        self.set(g + "Block/Upper corner", ", ".join(self.length(x) for x in upper[: self.dim]))
        self.set(g + "Block/Subdivisions", ", ".join(cells[: self.dim]))
        if self.turned:
            self.set(g + "Rotation angle", 90)

    def material(self, m):
        r = self.row
        p = "Materials/Material %d/" % m
        self.set(p + "Material id", m)
        stress = 1.0 / self.s ** 2  # Pa -> MPa with lengths in mm
        # The master body twice as stiff: the contact's stiffer side.
        stiff = 2.0 if (r["master"] == "body" and m == 1) else 1.0
        self.set(p + "Young's modulus", "%.17g" % (stiff * MODULUS * stress))
        self.set(p + "Poisson's ratio", POISSON)
        self.set(p + "Model", r["material"])
        self.set(p + "Kinematics", r["kinematics"])
        if r["material"] == "J2 plasticity":
            self.set(p + "J2 plasticity/Yield stress", "%.17g" % (YIELD * stress))
            self.set(p + "J2 plasticity/Isotropic hardening modulus", "%.17g" % (HARDENING * stress))
        if r["load"] == "body force" and m == (2 if r["master"] == "body" else 1):
            f = [0.0, -BODY_FORCE * stress / self.s, 0.0]  # N/m^3 -> N/mm^3
            self.set(p + "Body force", "; ".join(("%.17g*t" % x) if x else "0" for x in self.numbers(f)))

    def conditions(self, slave, two):
        r, dim = self.row, self.dim
        load = r["load"]
        press = "%.17g*t" % (-PRESS * self.s)
        ids = ", ".join(str(10 * b) for b in ([1, 2] if two else [1]))
        dirichlet = [(ids, 0, "0")]  # rollers (the axis when axisymmetric)
        if dim == 3:
            dirichlet.append((", ".join(str(10 * b + 4) for b in ([1, 2] if two else [1])), 2, "0"))
        top = str(10 * slave + 3)
        if load == "Dirichlet":
            dirichlet.append((top, 1, press))
        elif load == "obstacle motion":
            dirichlet.append((top, 1, "0"))
        if two:  # the master body's bottom, fixed (or moving up)
            up = "%.17g*t" % (PRESS * self.s) if load == "obstacle motion" else "0"
            dirichlet.append(("12", 1, up))
        n_dirichlet = len(dirichlet) + (load == "Dirichlet normal")
        self.set("Boundary conditions/Number of Dirichlet conditions", n_dirichlet)
        for k, (i, axis, value) in enumerate(dirichlet, 1):
            self.dirichlet(k, i, axis, value)
        if load == "Dirichlet normal":
            # Along the top's outward normal, whatever the frame.
            d = "Boundary conditions/Dirichlet %d/" % n_dirichlet
            self.set(d + "Boundary id", top)
            self.set(d + "Components", "normal")
            self.set(d + "Values", self.motion([0, -PRESS * self.s, 0]))
        if load == "pressure":
            self.set("Boundary conditions/Number of Neumann conditions", 1)
            self.set("Boundary conditions/Neumann 1/Boundary id", top)
            self.set("Boundary conditions/Neumann 1/Type", "pressure")
            self.set("Boundary conditions/Neumann 1/Values", "%.17g*t" % (PRESSURE / self.s ** 2))

    def contact(self, slave, two):
        r, dim, s = self.row, self.dim, self.s
        c = "Contact/"
        self.set(c + "Number of contact pairs", 1)
        if (r["load"] in ("pressure", "body force") and r["model"] == "axisymmetric"
                and r["degree"] == "2" and r["master"] in ("sphere", "cylinder", "level set")):
            # A body held by the contact alone that a curved master touches
            # at one point on the axis: that node of quadratic faces has no
            # weight (int psi 2 pi r = 0) and carries no force, so the
            # body starts closed, as the run's message advises. (Elsewhere
            # the default 'penetrating': 'closed' pulls every point of a
            # curved master onto it at the first iterate, issue 62's open
            # defect 6; a 3D pressed block with friction then had a
            # singular tangent.)
            self.set(c + "Initial status", "closed")
        self.set(c + "Integration rule", r["rule"])
        if r["rule"] in ("gauss", "simpson", "newton-cotes"):
            self.set(c + "Integration order", int(r["degree"]) + 1)
        p = c + "Pair 1/"
        self.set(p + "Slave boundary id", 10 * slave + 2)
        self.set(p + "Master", r["master"])
        self.set(p + "Friction coefficient", r["friction"])
        if two:
            self.set(p + "Master boundary id", 13)
            return
        if r["load"] == "obstacle motion":
            self.set(p + "Obstacle motion", self.motion([0, PRESS * s, 0]))
        master = r["master"]
        if master == "plane":
            self.set(p + "Plane/Point", self.point([0, 0, 0]))
            self.set(p + "Plane/Outward normal", self.vec([0, 1, 0]))
        elif master == "sphere":
            self.set(p + "Sphere/Centre", self.point([0, -RADIUS, 0]))
            self.set(p + "Sphere/Radius", self.length(RADIUS))
        elif master == "cylinder":
            self.set(p + "Cylinder/Axis point", self.point([0, -RADIUS, 0]))
            self.set(p + "Cylinder/Radius", self.length(RADIUS))
            if dim == 3:
                self.set(p + "Cylinder/Axis direction", self.vec([0, 0, 1]))
        elif master == "level set":
            # A paraboloid cap of radius of curvature RADIUS at the origin;
            # X, Y, Z the base frame's coordinates of the point.
            X, Y = ("(y)", "(-x)") if self.turned else ("(x)", "(y)")
            phi = "%s + (%s^2%s)/(2*R)" % (Y, X, " + z^2" if dim == 3 else "")
            self.set(p + "Level set/Function", phi)
            self.set(p + "Level set/Function constants", "R: %.17g" % (RADIUS * s))
        else:
            sys.exit("pairwise.py: no scene for the master '%s': add its "
                     "geometry to Scene.contact()" % master)

    def stepping(self):
        st = self.row["stepping"]
        if st == "one step":
            self.set("Load stepping/Number of steps", 1)
        elif st == "three steps":
            self.set("Load stepping/Number of steps", 3)
        else:
            self.set("Load stepping/Step times", "0.4, 1")


def prm_lines(row, scale=1.0, turned=False):
    return edit_prm([], Scene(row, scale, turned).build())


class Prober:
    """Asks the program which rows it takes ('signorini --check' on many
    files in one start: each input read and checked against its mesh and
    unknowns, nothing solved); answers cached."""

    def __init__(self, exe, workdir):
        self.exe, self.workdir, self.cache, self.runs = exe, workdir, {}, 0
        os.makedirs(workdir, exist_ok=True)

    @staticmethod
    def key(row):
        return tuple(sorted(row.items()))

    def ask(self, rows):
        """Caches the answers for @rows (one program start)."""
        todo = {self.key(r): r for r in rows if self.key(r) not in self.cache}
        if not todo:
            return
        files = []
        for n, row in enumerate(todo.values()):
            prm = os.path.join(self.workdir, "probe%04d.prm" % (len(self.cache) + n))
            lines = edit_prm(prm_lines(row), ["Output/Directory=" + os.path.join(self.workdir, "results")])
            with open(prm, "w") as f:
                f.write("\n".join(lines) + "\n")
            files.append(prm)
        p = subprocess.run([self.exe, "--check"] + files, capture_output=True, text=True, cwd=self.workdir)
        self.runs += 1
        text = p.stdout + p.stderr
        for prm, key in zip(files, todo):
            if ("the input of %s is complete" % prm) in text:
                self.cache[key] = True
            elif ("input error in %s:" % prm) in text:
                self.cache[key] = False
            else:
                sys.exit("pairwise.py: 'signorini --check' said nothing of %s:\n%s" % (prm, text[-2000:]))

    def takes(self, row):
        self.ask([row])
        return self.cache[self.key(row)]


def default_row(fs):
    return {name: levels[0] for name, levels in fs}


# The factor pairs the program may refuse (a model without finite strain,
# a rule without Q2, a solver without contact, ...); the others are taken
# as possible, and a row the program refuses all the same is not run.
PROBED = [("material", "kinematics"), ("material", "volumetric"), ("kinematics", "volumetric"),
          ("material", "model"), ("kinematics", "model"), ("volumetric", "model"), ("rule", "degree"), ("rule", "model"),
          ("master", "model"), ("master", "rule"), ("solver", "model"), ("solver", "friction"),
          ("solver", "master"), ("adaptivity", "rule")]


def possible_pairs(prober, fs):
    """Every pair of levels of two factors, less the structural ones and
    those the program refuses: a probed pair is possible if the program
    takes it in the default row or in the default row with one other
    factor at another level (neo-Hookean's 'finite strain' is refused with
    the default small-strain material and taken with J2 plasticity)."""
    levels = dict(fs)

    def rows_for(fixed):
        """The default row with @fixed, then with one other factor at
        another level."""
        row = default_row(fs)
        row.update(fixed)
        rows = [row]
        for name, values in fs:
            if name not in fixed:
                for value in values[1:]:
                    trial = dict(row)
                    trial[name] = value
                    rows.append(trial)
        return rows

    singles = [{name: value} for name, values in fs for value in values]
    doubles = [{a: la, b: lb} for a, b in PROBED for la in levels[a] for lb in levels[b]]
    # The default rows in one start, the alternatives of those refused in
    # a second.
    prober.ask([rows_for(f)[0] for f in singles + doubles])
    refused_first = [f for f in singles + doubles if not prober.takes(rows_for(f)[0])]
    prober.ask([r for f in refused_first for r in rows_for(f)[1:]])
    refused = set()
    for f in refused_first:
        if not any(prober.takes(r) for r in rows_for(f)):
            items = sorted(f.items(), key=lambda kv: [n for n, _ in fs].index(kv[0]))
            refused.add(items[0] if len(items) == 1 else (items[0], items[1]))
    # A pair with a refused level says nothing more.
    refused = {r for r in refused
               if isinstance(r[0], str) or not (r[0] in refused or r[1] in refused)}
    pairs = set()
    for (a, la_all), (b, lb_all) in itertools.combinations(fs, 2):
        for la in la_all:
            for lb in lb_all:
                if (a, la) in refused or (b, lb) in refused:
                    continue
                if ((a, la), (b, lb)) in refused or ((b, lb), (a, la)) in refused:
                    continue
                if not structural(a, la, b, lb):
                    continue
                pairs.add(((a, la), (b, lb)))
    return pairs, refused


def row_pairs(row, fs):
    names = [n for n, _ in fs]
    return {((a, row[a]), (b, row[b])) for a, b in itertools.combinations(names, 2)}


def cover(fs, possible, forbidden):
    """Greedy pairwise covering: each new row, among candidates grown
    factor by factor (the level covering most uncovered pairs with the
    levels chosen so far, ties at random with a fixed seed), the one
    covering most; only possible pairs in a row, no row of @forbidden."""
    rng = random.Random(62)
    uncovered = set(possible)
    rows = []
    names = [n for n, _ in fs]

    def allowed(row, name, level):
        for other, lo in row.items():
            key = ((other, lo), (name, level)) if names.index(other) < names.index(name) else ((name, level), (other, lo))
            if key not in possible:
                return False
        return True

    while uncovered:
        best, best_gain = None, -1
        for _ in range(40):
            # Start from an uncovered pair, then fill the other factors.
            first = rng.choice(sorted(uncovered))
            row = {first[0][0]: first[0][1], first[1][0]: first[1][1]}
            order = [n for n in names if n not in row]
            rng.shuffle(order)
            ok = True
            for name in order:
                choices = [lv for lv in dict(fs)[name] if allowed(row, name, lv)]
                if not choices:
                    ok = False
                    break
                gains = []
                for lv in choices:
                    trial = dict(row)
                    trial[name] = lv
                    gains.append(sum(1 for o, lo in row.items()
                                     if (((o, lo), (name, lv)) if names.index(o) < names.index(name)
                                         else ((name, lv), (o, lo))) in uncovered))
                top = max(gains)
                row[name] = rng.choice([lv for lv, g in zip(choices, gains) if g == top])
            if not ok:
                continue
            gain = len(row_pairs(row, fs) & uncovered)
            if gain > best_gain and Prober.key(row) not in forbidden:
                best, best_gain = row, gain
        if best is None or best_gain <= 0:
            break
        rows.append(best)
        uncovered -= row_pairs(best, fs)
    return rows, uncovered


def check_row(exe, mpiexec, row, directory):
    """Runs the row and its invariant's second run; prints the comparison."""
    np = int(row["ranks"])
    base_lines = prm_lines(row)
    inv = row["invariant"]
    dim = 3 if row["model"] == "3D" else 2
    if inv == "units":
        other, other_np = prm_lines(row, scale=1e3), np
    elif inv == "turned":
        other, other_np = prm_lines(row, turned=True), np
    else:
        other, other_np = base_lines, 3 - np
    code, text, base = run_scene(exe, mpiexec, base_lines, np, os.path.join(directory, "base"), "base")
    if code != 0:
        print("  FAIL: the scene exits with %d:\n%s" % (code, text))
        return False
    code, text, variant = run_scene(exe, mpiexec, other, other_np, os.path.join(directory, "variant"), "variant")
    if code != 0:
        print("  FAIL: its %s run exits with %d:\n%s" % (inv, code, text))
        return False
    skip = []
    if inv == "units":
        variant = to_base_frame(variant, dim, None, None, "mm", row["model"] == "axisymmetric")
    elif inv == "turned":
        variant = to_base_frame(variant, dim, rotation(90, [0, 0, 1], dim), None, None)
        skip = ["max_abs_u"]
    return compare(base, variant, TOLERANCE, False, True, (), skip)


# Defects this layer found that are still open: a row they match is run
# and must still fail (if it passes, the defect is gone: remove it here).
KNOWN = []


def known(row):
    for match, why in KNOWN:
        if match(row):
            return why
    return None


def describe(row):
    return ", ".join("%s=%s" % (k, v) for k, v in row.items())


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("exe")
    parser.add_argument("mpiexec")
    parser.add_argument("--list", action="store_true")
    parser.add_argument("--coverage", action="store_true")
    parser.add_argument("--keep", default="")
    parser.add_argument("--rows", default="", help="only these rows (comma-separated numbers)")
    a = parser.parse_args()
    top = a.keep or tempfile.mkdtemp(prefix="pairwise_")
    os.makedirs(top, exist_ok=True)
    fs = factors(a.exe, top)
    prober = Prober(a.exe, os.path.join(top, "probe"))
    possible, refused_pairs = possible_pairs(prober, fs)
    # Rows the program refuses as a whole (a triple it does not take) are
    # forbidden and the covering made again.
    forbidden = set()
    while True:
        rows, left = cover(fs, possible, forbidden)
        prober.ask(rows)
        refused_rows = [r for r in rows if not prober.takes(r)]
        if not refused_rows:
            break
        forbidden |= {Prober.key(r) for r in refused_rows}
    total = sum(len(l1) * len(l2) for (_, l1), (_, l2) in itertools.combinations(fs, 2))
    print("%d factors, %d level pairs, %d possible (%d refused by the program or the scene; "
          "%d probes), %d rows cover %d" % (len(fs), total, len(possible), total - len(possible),
                                            prober.runs, len(rows), len(possible) - len(left)))
    for r in sorted(str(x) for x in refused_pairs):
        print("  refused: %s" % r)
    if a.coverage:
        print("| factor | levels | level pairs with the other factors | possible | covered |")
        print("|---|---|---|---|---|")
        for name, levels in fs:
            all_pairs = sum(len(levels) * len(l2) for n2, l2 in fs if n2 != name)
            pos = [p for p in possible if name in (p[0][0], p[1][0])]
            cov = [p for p in pos if p not in left]
            print("| %s | %s | %d | %d | %d |" % (name, ", ".join(levels), all_pairs, len(pos), len(cov)))
        return
    if a.list:
        for k, row in enumerate(rows, 1):
            print("%2d: %s" % (k, describe(row)))
        return
    chosen = {int(x) for x in a.rows.split(",") if x}
    failed, known_broken = [], []
    for k, row in enumerate(rows, 1):
        if chosen and k not in chosen:
            continue
        print("row %d: %s" % (k, describe(row)))
        sys.stdout.flush()
        ok = check_row(a.exe, a.mpiexec, row, os.path.join(top, "row%02d" % k))
        why = known(row)
        if why and ok:
            print("  FAIL: the row passes, but it matches an open defect of KNOWN: %s. "
                  "If that defect is fixed, remove it from KNOWN." % why)
            failed.append(k)
        elif why:
            print("  KNOWN (open): %s" % why)
            known_broken.append(k)
        elif not ok:
            failed.append(k)
    print("%d rows, %d broken%s, %d broken by a known open defect%s" % (
        len(rows), len(failed), (": " + ", ".join(map(str, failed))) if failed else "",
        len(known_broken), (": " + ", ".join(map(str, known_broken))) if known_broken else ""))
    sys.exit(1 if failed or left else 0)


if __name__ == "__main__":
    main()
