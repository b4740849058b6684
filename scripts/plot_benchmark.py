"""Work-precision plot of scripts/benchmark: error against wall time.

Usage: /usr/bin/python3 plot_benchmark.py benchmark.csv out.png
One panel per (case, error measure); one line per (strategy, rule) on one
rank, points ordered by resolution and labelled with the u DoFs.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    with open(csv_path) as f:
        rows = [r for r in csv.DictReader(f) if r["ranks"] == "1"]
    cases = sorted({r["case"] for r in rows})
    measures = [("p0_error", "peak pressure p0, relative error"),
                ("l2_error", "pressure, relative L2 error")]
    fig, axes = plt.subplots(len(cases), len(measures),
                             figsize=(11, 4.2 * len(cases)), squeeze=False)
    for i, case in enumerate(cases):
        for j, (key, title) in enumerate(measures):
            ax = axes[i][j]
            series = sorted({(r["strategy"], r["rule"]) for r in rows
                             if r["case"] == case})
            for strategy, rule in series:
                pts = [r for r in rows if r["case"] == case and
                       r["strategy"] == strategy and r["rule"] == rule and
                       r[key] and r["wall_s"]]
                pts.sort(key=lambda r: int(r["dofs"]))
                if not pts:
                    continue
                x = [float(r["wall_s"]) for r in pts]
                y = [max(float(r[key]), 1e-16) for r in pts]
                style = {"local": "-", "uniform": "--"}.get(strategy, ":")
                ax.loglog(x, y, style, marker="o",
                          label=f"{rule}, {strategy} refinement")
                for r, xx, yy in zip(pts, x, y):
                    ax.annotate(r["dofs"], (xx, yy), fontsize=6,
                                textcoords="offset points", xytext=(3, 3))
            ax.set_xlabel("wall time [s] (2-core machine, 1 rank)")
            ax.set_ylabel(title)
            ax.set_title(f"{case}: {title}")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)
    print(f"wrote {png_path}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
