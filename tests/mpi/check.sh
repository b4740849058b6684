#!/usr/bin/env bash
# check.sh <signorini> <file.prm> <mpiexec> <ranks>...
# Serial = parallel: runs the scene on one rank and on each given rank count
# and compares, against the one-rank run,
#  - statistics.csv: every count (Newton iterations, step cuts, cycles,
#    frozen points, closed / stick / slip points) exactly, every force and
#    displacement to 1e-6 of the largest force or displacement;
#  - the contact CSV of every step: the same points (positions to 1e-6 of
#    the largest coordinate), the same statuses, pressures and tractions to
#    1e-6 of the largest pressure.
# Why 1e-6 and not 1e-15: the distributed direct solver rounds differently
# with the partition (and from run to run: MUMPS on several ranks is not
# bit-reproducible); on these stiff saddle-point systems that moves the
# solution by up to a few 1e-8 relative (measured: 3.8e-8 of p_max between
# two 2-rank runs of the hemispheres). A status or point that differs moves
# the numbers by far more than 1e-6.
# Arguments after '--' are entries set in a derived scene (scripts/prm-set:
# 'Subsection/Entry=value'), e.g. a coarser mesh for a shipped example.
set -u
exe="$1"; prm="$2"; mpiexec="$3"; shift 3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
top="$(mktemp -d)"
trap 'rm -rf "$top"' EXIT
ranks=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do ranks+=("$1"); shift; done
if [ $# -gt 0 ]; then
  shift
  prm_set="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../scripts" && pwd)/prm-set"
  /usr/bin/python3 "$prm_set" "$prm" "$@" > "$top/scene.prm" || exit 1
  prm="$top/scene.prm"
fi
set -- "${ranks[@]}"
status=0
for np in 1 "$@"; do
  mkdir -p "$top/np$np"
  (cd "$top/np$np" && "$mpiexec" -n "$np" --allow-run-as-root "$exe" "$prm" > out.txt 2>&1)
  rc=$?
  if [ $rc -ne 0 ]; then
    echo "FAIL: the run on $np rank(s) exited with code $rc"; tail -5 "$top/np$np/out.txt"; status=1
  fi
done
[ $status -eq 0 ] || exit 1
results() { sed -n 's/^ *set Directory *= *//p' "$prm" | tail -1; }
dir="$(results)"; dir="${dir:-results}"
for np in "$@"; do
  /usr/bin/python3 - "$top/np1/$dir" "$top/np$np/$dir" "$np" <<'PY' || status=1
import bisect, csv, glob, os, sys
a_dir, b_dir, np = sys.argv[1], sys.argv[2], sys.argv[3]
fails = []
def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))
# statistics.csv
A, B = rows(os.path.join(a_dir, "statistics.csv")), rows(os.path.join(b_dir, "statistics.csv"))
if len(A) != len(B):
    fails.append("statistics.csv: %d steps on 1 rank, %d on %s" % (len(A), len(B), np))
counts = ("step", "newton_iterations", "step_cuts", "cycle_detections", "points_frozen")
# Forces compare against the largest force of the run, displacements
# against the largest displacement: a component that is round-off on one
# rank (a transverse reaction) is round-off on the others too.
def family(col):
    return "force" if col.startswith(("reaction", "contact_force")) else col if col == "time" else "length"
scales = {}
for col in A[0].keys() if A else []:
    if col not in counts and not col.startswith("contact_points"):
        f = family(col)
        scales[f] = max([scales.get(f, 0.0)] + [abs(float(r[col])) for r in A])
for col in A[0].keys() if A else []:
    if col not in B[0]:
        fails.append("statistics.csv: column %s missing on %s ranks" % (col, np)); continue
    exact = col in counts or col.startswith("contact_points")
    scale = 0.0 if exact else (scales[family(col)] or 1.0)
    for ra, rb in zip(A, B):
        va, vb = float(ra[col]), float(rb[col])
        if (exact and va != vb) or (not exact and abs(va - vb) > 1e-6 * scale):
            fails.append("statistics.csv step %s, %s: %s on 1 rank, %s on %s ranks" % (ra["step"], col, ra[col], rb[col], np))
            break
# contact CSVs
files = sorted(glob.glob(os.path.join(a_dir, "contact_*.csv")))
n_points = 0
for fa in files:
    fb = os.path.join(b_dir, os.path.basename(fa))
    if not os.path.exists(fb):
        fails.append("%s missing on %s ranks" % (os.path.basename(fa), np)); continue
    PA, PB = rows(fa), rows(fb)
    axes = [c for c in ("x", "y", "z") if c in PA[0]] if PA else []
    xs = max([abs(float(r[c])) for r in PA for c in axes] or [1.0])
    if len(PA) != len(PB):
        fails.append("%s: %d points on 1 rank, %d on %s" % (os.path.basename(fa), len(PA), len(PB), np)); continue
    n_points += len(PA)
    # Each point matched to the nearest unused point of the other run
    # within 1e-6 of the extent (positions agree to the round-off of the
    # converged state, about 1e-8 of the extent: a plain sort by
    # coordinates swaps points of nearly the same x).
    pos = lambda r: [float(r[c]) for c in axes]
    PB.sort(key=lambda r: pos(r)[0]); xb = [pos(r)[0] for r in PB]
    used = [False] * len(PB); matched = []
    for ra in PA:
        a = pos(ra); best, bi = None, -1
        for j in range(bisect.bisect_left(xb, a[0] - 1e-6 * xs), bisect.bisect_right(xb, a[0] + 1e-6 * xs)):
            if used[j]: continue
            d = max(abs(u - v) for u, v in zip(a, pos(PB[j])))
            if best is None or d < best: best, bi = d, j
        if bi < 0: matched.append((ra, None)); continue
        used[bi] = True; matched.append((ra, PB[bi]))
    ps = max([abs(float(r["p"])) for r in PA] or [1.0]) or 1.0
    values = [c for c in PA[0].keys() if c == "p" or c.startswith("traction")] if PA else []
    bad = 0
    for ra, rb in matched:
        if rb is None:
            bad += 1
            if bad == 1:
                first = (ra, {"no point within 1e-6 of the extent": ""})
            continue
        if any(abs(float(ra[c]) - float(rb[c])) > 1e-6 * xs for c in axes) or ra["status"] != rb["status"] \
           or any(abs(float(ra[c]) - float(rb[c])) > 1e-6 * ps for c in values):
            bad += 1
            if bad == 1:
                first = (ra, rb)
    if bad:
        fails.append("%s: %d of %d points differ on %s ranks, first: %s | %s" % (os.path.basename(fa), bad, len(PA), np, dict(first[0]), dict(first[1])))
for f in fails[:10]:
    print("FAIL: " + f)
if fails:
    sys.exit(1)
print("PASS: %s ranks = 1 rank: %d steps (counts exact, forces to 1e-6), %d contact points in %d CSV files (statuses exact, p and tractions to 1e-6 of max p)" % (np, len(A), n_points, len(files)))
PY
done
exit $status
