"""Contact pressure of the Hertz benchmarks against the Hertz solution, and
the Newton convergence history of the benchmark runs.

Usage: plot_contact.py RUN_DIRECTORY FIGURE_DIRECTORY
RUN_DIRECTORY holds one output directory per case (see scripts/plot). The
reference values are those of the prm files (doc/verification.md).
"""
import csv
import math
import sys
from pathlib import Path

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
}


def last_csv(directory):
    files = sorted(Path(directory).glob("contact_*.csv"))
    if not files:
        raise SystemExit(f"no contact_*.csv in {directory}")
    with open(files[-1]) as f:
        rows = []
        for row in csv.DictReader(f):
            rows.append({k: (v if k == "status" else float(v))
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
                ms=4, label="Signorini (contact points)")
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


if __name__ == "__main__":
    main()
    plot_newton_history(Path(sys.argv[1]), Path(sys.argv[2]))
