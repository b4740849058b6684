"""Contact pressure of the Hertz benchmarks against the Hertz solution, the
Newton convergence history of the benchmark runs, B2 at nu = 0.4999 with and
without the projected volumetric strain, and force-displacement
curves (Cattaneo-Mindlin load cycle, B4 ironing) from statistics.csv.

Usage: plot_contact.py RUN_DIRECTORY FIGURE_DIRECTORY
RUN_DIRECTORY holds one output directory per case (see scripts/plot). The
reference values are those of the prm files (doc/verification.md).
"""
import csv
import math
import sys
from pathlib import Path

from vtu_reader import read_series

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# case: (title, p0 [Pa], a [m], radial coordinate from a CSV row)
CASES = {
    "b2_hertz_2d": ("B2 Hertz 2D, elastic cylinder on block (mortar rule)", 3.585e9, 6.21e-3,
                    lambda r: abs(r["x"])),
    "hertz_2d_rigid": ("Hertz 2D, cylinder on rigid plane", 5.07e9, 4.39e-3,
                       lambda r: abs(r["x"])),
    "hertz_3d": ("Hertz 3D, sphere on block (mortar rule)", 7.2827e9, 9.914e-3,
                 lambda r: math.hypot(r["x"], r["z"])),
    "gmsh_hertz_2d": ("B2 Hertz 2D on a Gmsh mesh (two bodies, one file)",
                      3.585e9, 6.21e-3, lambda r: abs(r["x"])),
}


def last_csv(directory):
    files = sorted(Path(directory).glob("contact_*.csv"))
    if not files:
        raise SystemExit(f"no contact_*.csv in {directory}")
    with open(files[-1]) as f:
        rows = []
        for row in csv.DictReader(f):
            # An empty field is a missing value (the gap of a point with
            # no master face).
            rows.append({k: (v if k == "status" else
                             float(v) if v != "" else math.nan)
                         for k, v in row.items()})
    return rows


def main():
    runs, figures = Path(sys.argv[1]), Path(sys.argv[2])
    figures.mkdir(parents=True, exist_ok=True)
    for case, (title, p0, a, radius) in CASES.items():
        rows = last_csv(runs / case)
        points = sorted({(radius(r) * 1e3, r["p"] / 1e6) for r in rows
                         if radius(r) < 2.5 * a})
        r_exact = [2.5 * a * 1e3 * i / 400 for i in range(401)]
        p_exact = [p0 / 1e6 * math.sqrt(max(0.0, 1 - (r / (a * 1e3)) ** 2))
                   for r in r_exact]
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(r_exact, p_exact, "k-", label="Hertz")
        ax.plot([p[0] for p in points], [p[1] for p in points], "o",
                ms=4, label="Signorini (slave nodes)")
        ax.set_xlabel("distance from the first contact point [mm]")
        ax.set_ylabel("contact pressure p [MPa]")
        ax.set_title(title)
        ax.grid(alpha=0.3)
        ax.legend()
        fig.tight_layout()
        out = figures / f"{case}_pressure.png"
        fig.savefig(out, dpi=110)
        plt.close(fig)
        print("wrote", out)


def plot_newton_history(runs, figures):
    """Largest block residual |R|/|F| at every Newton iterate, one line per
    run, the iterates numbered through the run (geometric iterations and
    load steps one after the other); filled markers: converged iterates."""
    fig, ax = plt.subplots(figsize=(6, 4))
    for case in HISTORY:
        path = runs / case / "newton_history.csv"
        if not path.exists():
            continue
        with open(path) as f:
            rows = list(csv.DictReader(f))
        r = [max(float(x["r_u"]), float(x["r_lambda"]), float(x["r_Lambda"]),
                 1e-17) for x in rows]
        line, = ax.semilogy(range(len(r)), r, "-", marker="o", ms=3,
                            mfc="white", label=case)
        done = [i for i, x in enumerate(rows) if x["converged"] == "1"]
        ax.semilogy(done, [r[i] for i in done], "o", ms=5,
                    color=line.get_color())
    ax.set_xlabel("Newton iterate (through the run)")
    ax.set_ylabel("largest block residual |R| / |F|")
    ax.set_title("Newton convergence (filled: converged)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    out = figures / "newton_history.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print("wrote", out)


HISTORY = ["b2_hertz_2d", "hertz_2d_rigid", "b3_ssnv128", "hertz_3d"]


def statistics(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def plot_hysteresis(runs, figures):
    """Tangential force against the sideways displacement of the cylinder's
    top in the Cattaneo-Mindlin load cycle (prm/cattaneo_mindlin_2d.prm),
    with the stick-zone size of each step."""
    path = runs / "cattaneo_mindlin_2d" / "statistics.csv"
    if not path.exists():
        return
    rows = [r for r in statistics(path) if r["time"] >= 1.0]
    d = [r["displacement_1_x"] * 1e6 for r in rows]
    q = [r["reaction_1_x"] / 1e6 for r in rows]
    mu_p = [0.3 * abs(r["contact_force_1_y"]) / 1e6 for r in rows]
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
    ax.plot([0] + d, [0] + q, "o-", ms=4, label="Signorini (one point per load step)")
    ax.axhline(max(mu_p), color="k", ls="--", lw=0.8, label="full sliding, $\\pm\\mu P$")
    ax.axhline(-max(mu_p), color="k", ls="--", lw=0.8)
    ax.set_xlabel("sideways displacement of the cylinder top [$\\mu$m]")
    ax.set_ylabel("tangential force Q [MN/m]")
    ax.set_title("Cattaneo-Mindlin load cycle")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    # The loop is thin beside the elastic stiffness of the bodies: remove
    # the initial (all-stick) stiffness to show it.
    first = next(i for i, di in enumerate(d) if di != 0)
    k = q[first] / d[first]
    bx.plot([0] + d, [0] + [qi - k * di for qi, di in zip(q, d)], "o-", ms=4)
    bx.set_xlabel("sideways displacement of the cylinder top [$\\mu$m]")
    bx.set_ylabel("Q - k d [MN/m], k the all-stick stiffness")
    bx.set_title("the same, less the initial stiffness: hysteresis")
    bx.grid(alpha=0.3)
    fig.tight_layout()
    out = figures / "cattaneo_mindlin_hysteresis.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print("wrote", out)


def plot_mindlin_traction(runs, figures):
    """Tangential traction along the contact in the Cattaneo-Mindlin run at
    the first-loading step with Q/(mu P) closest to 0.6, against the
    analytic profile (Johnson 7.2) for the computed P and Q."""
    run = runs / "cattaneo_mindlin_2d"
    path = run / "statistics.csv"
    if not path.exists():
        return
    mu, R, E, nu = 0.3, 0.1, 2.1e11, 0.3
    rows = [r for r in statistics(path) if 1.0 < r["time"] <= 2.0]
    ratio = lambda r: abs(r["contact_force_1_x"]) / (mu * abs(r["contact_force_1_y"]))
    row = min(rows, key=lambda r: abs(ratio(r) - 0.6))
    P, Q = abs(row["contact_force_1_y"]), abs(row["contact_force_1_x"])
    e_star = E / (2 * (1 - nu ** 2))
    a = math.sqrt(4 * P * R / (math.pi * e_star))
    p0 = 2 * P / (math.pi * a)
    c = a * math.sqrt(1 - Q / (mu * P))

    def q_exact(x):
        q = mu * p0 * math.sqrt(max(0.0, 1 - (x / a) ** 2))
        if abs(x) < c:
            q -= mu * p0 * (c / a) * math.sqrt(1 - (x / c) ** 2)
        return q

    with open(run / f"contact_{int(row['step']):04d}.csv") as f:
        pts = [r for r in csv.DictReader(f) if r["status"] != "free"]
    xs = sorted({(float(r["x"]), abs(float(r["traction_t1"])), r["status"]) for r in pts})
    grid = [-1.3 * a + 2.6 * a * i / 400 for i in range(401)]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot([x * 1e3 for x in grid], [q_exact(x) / 1e6 for x in grid], "k-",
            label="Cattaneo-Mindlin (Hertz a, p0 for the computed P)")
    ax.plot([x * 1e3 for x in grid],
            [mu * p0 * math.sqrt(max(0.0, 1 - (x / a) ** 2)) / 1e6 for x in grid],
            "k:", lw=0.8, label="$\\mu p$ (Hertz)")
    for status, marker in (("stick", "o"), ("slip", "s")):
        sel = [(x, q) for x, q, st in xs if st == status]
        ax.plot([x * 1e3 for x, _ in sel], [q / 1e6 for _, q in sel], marker,
                ms=5, label=f"Signorini, {status} nodes")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("tangential traction |q| [MPa]")
    ax.set_title(f"Partial slip, Q/($\\mu$P) = {Q / (mu * P):.2f}: c/a = {c / a:.2f}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    out = figures / "cattaneo_mindlin_traction.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print("wrote", out)


def plot_ironing_forces(runs, figures):
    """Contact force components on the slab against the die's travel in B4
    (prm/b4_ironing.prm), small and finite strain."""
    path = runs / "b4_ironing" / "statistics.csv"
    if not path.exists():
        return
    rows = statistics(path)
    s = [r["obstacle_displacement_1_x"] for r in rows]
    fx = [abs(r["contact_force_1_x"]) for r in rows]
    fy = [abs(r["contact_force_1_y"]) for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4))
    press = [i for i, r in enumerate(rows) if r["time"] <= 1.0]
    ax.plot(s, fy, "o-", ms=3, label="$|F_y|$ (normal to the slab)")
    ax.plot(s, fx, "s-", ms=3, label="$|F_x|$ (along the slab)")
    ax.plot([s[i] for i in press], [fy[i] for i in press], "ko", ms=3,
            mfc="none", label="pressing steps (die travel 0)")
    # The same scene with a neo-Hookean slab at finite strain
    # (prm/b4_ironing_finite_strain.prm).
    finite = runs / "b4_ironing_finite_strain" / "statistics.csv"
    if finite.exists():
        rows = statistics(finite)
        s = [r["obstacle_displacement_1_x"] for r in rows]
        ax.plot(s, [abs(r["contact_force_1_y"]) for r in rows], "o--",
                ms=3, mfc="none", label="$|F_y|$, finite strain (neo-Hookean)")
        ax.plot(s, [abs(r["contact_force_1_x"]) for r in rows], "s--",
                ms=3, mfc="none", label="$|F_x|$, finite strain (neo-Hookean)")
    ax.set_xlabel("die travel along the slab")
    ax.set_ylabel("contact force on the slab")
    ax.set_title("B4 ironing: contact force per load step")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    out = figures / "b4_ironing_forces.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print("wrote", out)


def plot_locking(runs, figures):
    """B2 with nu = 0.4999 (prm/b2_hertz_2d_incompressible.prm): contact
    pressure with the projected (B-bar) and the pointwise volumetric strain
    against Hertz."""
    p0, a = 3.9489e9, 5.6425e-3
    runs_here = {"projected": "projected volumetric strain (B-bar)",
                 "full": "pointwise volumetric strain (locks)"}
    if not all((runs / f"b2_incompressible_{k}").exists() for k in runs_here):
        return
    fig, ax = plt.subplots(figsize=(6, 4))
    r_exact = [2.5 * a * 1e3 * i / 400 for i in range(401)]
    ax.plot(r_exact, [p0 / 1e6 * math.sqrt(max(0.0, 1 - (r / (a * 1e3)) ** 2))
                      for r in r_exact], "k-", label="Hertz")
    for (key, label), marker in zip(runs_here.items(), ["o", "s"]):
        rows = last_csv(runs / f"b2_incompressible_{key}")
        points = sorted({(abs(r["x"]) * 1e3, r["p"] / 1e6) for r in rows
                         if abs(r["x"]) < 2.5 * a})
        ax.plot([q[0] for q in points], [q[1] for q in points], marker,
                ms=4, mfc="white" if key == "full" else None, label=label)
    ax.set_xlabel("distance from the first contact point [mm]")
    ax.set_ylabel("contact pressure p [MPa]")
    ax.set_title("B2 Hertz 2D, nu = 0.4999, Q1 (mortar rule)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    out = figures / "b2_incompressible_pressure.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print("wrote", out)


def plot_contact_surface(runs, figures):
    """The 3D Hertz contact patch as the contact surface output gives it
    (contact_surface_NNNN.vtu of the last step, read back with
    vtu_reader.py), seen from below: the nodal contact pressure and the
    nodal status on the slave faces, with Hertz's radius a."""
    import matplotlib.tri as mtri
    from matplotlib.collections import PolyCollection

    directory = runs / "hertz_3d"
    if not (directory / "contact_surface.pvd").exists():
        return
    pieces, _ = read_series(directory, "contact_surface")
    a = CASES["hertz_3d"][2] * 1e3
    window = 1.6 * a
    xs, zs, ps, status, triangles, outlines = [], [], [], [], [], []
    for piece in pieces:
        base = len(xs)
        xs += [x[0] * 1e3 for x in piece["points"]]
        zs += [x[2] * 1e3 for x in piece["points"]]
        ps += [v / 1e6 for v in piece["point_data"]["contact_pressure"]]
        status += piece["point_data"]["status"]
        for cell in piece["cells"]:
            c = [base + i for i in cell]
            if min(math.hypot(xs[i], zs[i]) for i in c) > 1.5 * window:
                continue
            triangles += [[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
            outlines.append([(xs[i], zs[i]) for i in c])
    mesh = mtri.Triangulation(xs, zs, triangles)
    phi = [0.5 * math.pi * i / 100 for i in range(101)]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.4))
    image = axes[0].tripcolor(mesh, ps, shading="gouraud", cmap="viridis")
    fig.colorbar(image, ax=axes[0], label="contact_pressure [MPa]")
    closed = [i for i in range(len(xs)) if status[i] > 0]
    opened = [i for i in range(len(xs)) if status[i] == 0]
    axes[1].plot([xs[i] for i in closed], [zs[i] for i in closed], "o",
                 color="tab:red", ms=5, label="closed (status > 0)")
    axes[1].plot([xs[i] for i in opened], [zs[i] for i in opened], "o",
                 mfc="white", color="tab:gray", ms=5, label="open (status 0)")
    for ax, title in zip(axes, ("nodal contact pressure", "nodal status")):
        ax.add_collection(PolyCollection(outlines, facecolors="none",
                                         edgecolors="k", linewidths=0.3))
        ax.plot([a * math.cos(t) for t in phi], [a * math.sin(t) for t in phi],
                "--", color="white" if ax is axes[0] else "k", lw=1.5,
                label="Hertz: r = a")
        ax.set_xlim(0, window)
        ax.set_ylim(0, window)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("z [mm]")
        ax.set_title(title, fontsize=10)
        ax.legend(loc="upper right", fontsize=8)
    fig.suptitle("Hertz 3D (prm/hertz_3d.prm), the contact patch seen from "
                 "below: contact_surface_NNNN.vtu drawn with matplotlib", fontsize=10)
    fig.tight_layout()
    out = figures / "hertz_3d_contact_surface.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print("wrote", out)


if __name__ == "__main__":
    main()
    plot_contact_surface(Path(sys.argv[1]), Path(sys.argv[2]))
    plot_newton_history(Path(sys.argv[1]), Path(sys.argv[2]))
    plot_hysteresis(Path(sys.argv[1]), Path(sys.argv[2]))
    plot_mindlin_traction(Path(sys.argv[1]), Path(sys.argv[2]))
    plot_ironing_forces(Path(sys.argv[1]), Path(sys.argv[2]))
    plot_locking(Path(sys.argv[1]), Path(sys.argv[2]))
