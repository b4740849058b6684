"""Peers benchmark (issue 32): the 2D Hertz scene in GetFEM and in Signorini.

Usage: /usr/bin/python3 run_peers.py SIGNORINI [quick]

Runs each mesh sequence below, level by level, the GetFEM and Signorini
runs of a level one after the other (paired: machine noise hits both),
PEERS_REPEATS times (default 3; quick: the three coarsest levels once, the
table printed and no file written).
The wall time of a run is that of the whole process (start to exit,
time.perf_counter around subprocess.run), the median of the repeats.
The errors come from one evaluator (evaluate.py) for both codes, from the
nodal contact pressures each code writes. Writes
benchmarks/results/peers.csv and doc/figures/peers_work_precision.png and
prints a Markdown table.
"""
import csv
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(TOP, "scripts"))
sys.dont_write_bytecode = True
import evaluate  # noqa: E402
from prm_edit import absolute_paths, edit_prm  # noqa: E402

PYTHON = "/usr/bin/python3"
ZONE = 0.0055  # contact zone of the GetFEM size function [m], 1.25 a

# (code, element, mesh description, list of level parameters)
VARIANTS = [
    ("GetFEM", "P1", "graded 0.05",
     [(3, h, 0.05) for h in (1.28e-3, 6.4e-4, 3.2e-4, 1.6e-4, 8e-5, 4e-5)]),
    ("Signorini", "Q1", "local, disc 12 mm",
     [(3, 3), (3, 4), (4, 4), (4, 5), (5, 5), (5, 6)]),
    ("Signorini", "Q1", "local, graded 6 mm",
     [(4, l) for l in (2, 3, 4, 5, 6, 7)]),
    ("GetFEM", "P2", "graded 0.4",
     [(3, h, 0.4) for h in (2.56e-3, 1.28e-3, 6.4e-4, 3.2e-4, 1.6e-4, 8e-5)]),
    ("Signorini", "Q2", "local, disc 5.5 mm",
     [(4, 1), (4, 2), (4, 3), (4, 4), (4, 5), (4, 6)]),
    ("Signorini", "Q2", "adaptive from G3",
     [(3, c) for c in (2, 3, 4, 5, 6, 7)]),
]
DISC = {"local, disc 12 mm": "0.012 - sqrt(x^2 + y^2)",
        "local, graded 6 mm": "0.006 + 0.04 / 2^cycle - sqrt(x^2 + y^2)",
        "local, disc 5.5 mm": "0.0055 - sqrt(x^2 + y^2)"}

P0_TARGET, A_TARGET = 5e-4, 5e-3


def timed(cmd, log):
    with open(log, "w") as f:
        t0 = time.perf_counter()
        rc = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT).returncode
        wall = time.perf_counter() - t0
    return wall, rc


def run_getfem(element, params, scratch):
    glevel, h_fine, grading = params
    out = os.path.join(scratch, "getfem_contact.csv")
    log = os.path.join(scratch, "getfem.log")
    wall, rc = timed([PYTHON, os.path.join(HERE, "getfem_hertz_2d.py"), element[1],
                      str(glevel), repr(h_fine), repr(grading), repr(ZONE), out], log)
    text = open(log).read()
    m = re.search(r"RESULT dofs=(\d+) lambda_dofs=(\d+) newton=(\d+) converged=(\d+) "
                  r"force_half=(\S+)", text)
    if rc != 0 or not m or m.group(4) != "1":
        raise RuntimeError("GetFEM run failed:\n" + text[-2000:])
    x, p = evaluate.read_xp(out)
    return wall, {"dofs": int(m.group(1)), "newton": int(m.group(3)),
                  "force": float(m.group(5)), "x": x, "p": p,
                  "mesh": "G%d h=%.3g g=%.2g" % params}


def run_signorini(binary, element, strategy, params, scratch):
    glevel, level = params
    outdir = os.path.join(scratch, "signorini_out")
    shutil.rmtree(outdir, ignore_errors=True)
    prm = os.path.join(scratch, "signorini.prm")
    log = os.path.join(scratch, "signorini.log")
    # The scene with each entry set once (the program refuses an entry set
    # twice): scripts/prm_edit.py, as scripts/prm-set.
    sets = ["Finite element/Degree=%s" % element[1],
            "Geometry/Global refinements=%d" % glevel]
    if strategy in DISC:
        sets += ["Geometry/Local refinements=%d" % level,
                 "Geometry/Refinement region=%s" % DISC[strategy]]
        mesh = "G%d L%d" % (glevel, level)
    else:
        sets += ["Geometry/Local refinements=0", "Adaptive refinement/Cycles=%d" % level]
        mesh = "G%d, %d cycles" % (glevel, level)
    sets.append("Output/Directory=%s" % outdir)
    lines = absolute_paths(open(os.path.join(HERE, "signorini_hertz_2d.prm")).read().splitlines(), HERE)
    with open(prm, "w") as f:
        f.write("\n".join(edit_prm(lines, sets)) + "\n")
    wall, rc = timed([binary, prm], log)
    text = open(log).read()
    if rc != 0:
        raise RuntimeError("Signorini run failed:\n" + text[-2000:])
    dofs = re.findall(r"^DoFs per block: u (\d+)", text, re.M)
    adapted = re.findall(r"adaptive refinement: .* (\d+) displacement DoFs", text)
    newton = sum(int(n) for n in re.findall(r"^  Newton iterations: (\d+)", text, re.M))
    with open(os.path.join(outdir, "statistics.csv")) as f:
        row = list(csv.DictReader(f))[-1]
    contact = sorted(n for n in os.listdir(outdir) if re.match(r"contact_\d+\.csv$", n))[-1]
    x, p = evaluate.read_xp(os.path.join(outdir, contact))
    return wall, {"dofs": int((adapted or dofs)[-1]), "newton": newton,
                  "force": abs(float(row["contact_force_1_y"])), "x": x, "p": p,
                  "mesh": mesh}


def main():
    if len(sys.argv) < 2:
        sys.exit("usage: run_peers.py SIGNORINI [quick]")
    binary = sys.argv[1]
    quick = len(sys.argv) > 2 and sys.argv[2] == "quick"
    repeats = 1 if quick else int(os.environ.get("PEERS_REPEATS", "3"))
    nlevels = 3 if quick else max(len(v[3]) for v in VARIANTS)
    results = {}
    scratch = tempfile.mkdtemp(prefix="peers.")
    try:
        for level in range(nlevels):
            for rep in range(repeats):
                for k, (code, element, strategy, levels) in enumerate(VARIANTS):
                    if level >= len(levels):
                        continue
                    if code == "GetFEM":
                        wall, r = run_getfem(element, levels[level], scratch)
                    else:
                        wall, r = run_signorini(binary, element, strategy, levels[level], scratch)
                    key = (k, level)
                    results.setdefault(key, {"walls": [], **r})["walls"].append(wall)
                    print("  %-9s %s %-18s level %d  %7d DoFs  %.2f s"
                          % (code, element, strategy, level + 1, r["dofs"], wall), flush=True)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)

    rows = []
    for (k, level), r in sorted(results.items()):
        code, element, strategy, _ = VARIANTS[k]
        e = evaluate.evaluate(r["x"], r["p"], r["force"])
        meets = (e["p0_error"] <= P0_TARGET and e["a_error"] <= A_TARGET
                 and e["h_c"] / 2 <= A_TARGET * e["a"])
        rows.append({
            "code": code, "element": element, "strategy": strategy, "level": level + 1,
            "mesh": r["mesh"], "dofs": r["dofs"], "h_c_um": "%.1f" % (1e6 * e["h_c"]),
            "newton": r["newton"], "wall_s": "%.3f" % statistics.median(r["walls"]),
            "wall_min_s": "%.3f" % min(r["walls"]), "repeats": len(r["walls"]),
            "force_half_N_per_m": "%.6e" % e["force_half"],
            "p0_error": "%.2e" % e["p0_error"], "a_error": "%.2e" % e["a_error"],
            "l2_error": "%.2e" % e["l2_error"], "target": "yes" if meets else "no"})

    if not quick:  # quick is a smoke test: the table only
        out = os.path.join(TOP, "benchmarks", "results")
        os.makedirs(out, exist_ok=True)
        with open(os.path.join(out, "peers.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)

    print()
    print("| code | element | mesh | level | u DoFs | h_c [um] | Newton | wall [s] "
          "| p0 error | a error | L2(p) error | target |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %s | %s | %s: %s | %d | %d | %s | %d | %s | %s | %s | %s | %s |"
              % (r["code"], r["element"], r["strategy"], r["mesh"], r["level"], r["dofs"],
                 r["h_c_um"], r["newton"], r["wall_s"], r["p0_error"], r["a_error"],
                 r["l2_error"], r["target"]))
    print()
    first = {}
    for r in rows:
        key = (r["code"], r["element"], r["strategy"])
        if r["target"] == "yes" and key not in first:
            first[key] = r
    for code, element, strategy, _ in VARIANTS:
        r = first.get((code, element, strategy))
        print("first level meeting p0 <= 0.05 %%, a <= 0.5 %%, h_c/2 <= 0.5 %% of a: "
              "%s %s %s: %s" % (code, element, strategy,
                                "level %d, %d DoFs, %s s" % (r["level"], r["dofs"], r["wall_s"])
                                if r else "none"))
    ref = first.get(("GetFEM", "P2", "graded 0.4"))
    if ref:
        for key, r in first.items():
            if key[0] == "Signorini":
                print("GetFEM P2 / Signorini %s %s wall time at the target: %.2f"
                      % (key[1], key[2], float(ref["wall_s"]) / float(r["wall_s"])))
    if not quick:
        plot(rows, os.path.join(TOP, "doc", "figures", "peers_work_precision.png"))


def plot(rows, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("python3-matplotlib missing: no plot", file=sys.stderr)
        return
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8))
    styles = {"GetFEM": ("s", "--"), "Signorini": ("o", "-")}
    for code, element, strategy, _ in VARIANTS:
        sel = [r for r in rows if (r["code"], r["element"], r["strategy"]) == (code, element, strategy)]
        if not sel:
            continue
        t = [float(r["wall_s"]) for r in sel]
        marker, line = styles[code]
        for ax, col in zip(axes, ("p0_error", "a_error", "l2_error")):
            ax.loglog(t, [float(r[col]) for r in sel], marker=marker, linestyle=line,
                      label="%s %s, %s" % (code, element, strategy))
    for ax, title, target in zip(axes, ("p0 relative error", "a relative error",
                                        "L2(p) relative error"), (P0_TARGET, A_TARGET, None)):
        if target:
            ax.axhline(target, color="grey", linewidth=0.8)
        ax.set_xlabel("whole-process wall time [s]")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("2D Hertz, rigid plane: GetFEM and Signorini (grey: issue 32 targets)")
    fig.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
