"""Common evaluator of the peers benchmark (issue 32): the 2D Hertz errors
from nodal contact pressures, the same for GetFEM and Signorini.

evaluate(x, p, force_half) takes the reference x of the contact-surface
nodes, their contact pressures p (> 0 in compression) and the vertical
contact force of the half model per unit thickness, and returns the Hertz
values at that force and the errors:
  p0_error  |max p - p0| / p0
  a_error   |a_h - a| / a, a_h the midpoint between the last node in
            contact (p > 1 % of p0: moves a_h by at most 5e-5 a on a Hertz
            profile, ignores the weak multiplier's small values beyond the
            edge) and the next node along x
  h_c       the spacing of those two nodes (a_h resolves a to +-h_c/2)
  l2_error  ||p_h - p_Hertz|| / ||p_Hertz|| over the surface, p_h linear
            between the nodes, a composite trapezoidal rule on 20000
            intervals of [0, 1.5 max(a, a_h)]
"""
import math

import numpy as np

E, NU, R = 2.1e11, 0.3, 0.1


def hertz(force_half):
    f = 2.0 * force_half  # F' of the whole cylinder per unit thickness
    e_star = E / (1.0 - NU * NU)
    a = math.sqrt(4.0 * f * R / (math.pi * e_star))
    return a, 2.0 * f / (math.pi * a)


def evaluate(x, p, force_half):
    x = np.asarray(x, dtype=float)
    p = np.asarray(p, dtype=float)
    order = np.argsort(x, kind="stable")
    x, p = x[order], p[order]
    a, p0 = hertz(abs(force_half))
    closed = np.nonzero(p > 0.01 * p0)[0]
    last = closed[-1]
    nxt = min(last + 1, len(x) - 1)
    a_h = 0.5 * (x[last] + x[nxt])
    h_c = x[nxt] - x[last]
    end = 1.5 * max(a, a_h)
    s = np.linspace(0.0, end, 20001)
    ph = np.interp(s, x, p, right=0.0)
    pe = np.where(s < a, p0 * np.sqrt(np.clip(1.0 - (s / a) ** 2, 0.0, None)), 0.0)
    l2 = math.sqrt(np.trapz((ph - pe) ** 2, s) / np.trapz(pe ** 2, s))
    return {
        "force_half": abs(force_half), "a": a, "p0": p0,
        "p_max": float(p.max()), "a_h": a_h, "h_c": h_c,
        "p0_error": abs(p.max() - p0) / p0, "a_error": abs(a_h - a) / a,
        "l2_error": l2, "contact_nodes": int(len(closed)),
    }


def read_xp(path):
    """x and p columns of a CSV with a header line (Signorini's
    contact_NNNN.csv or the GetFEM script's)."""
    with open(path) as f:
        head = f.readline().strip().split(",")
        ix, ip = head.index("x"), head.index("p")
        xs, ps = [], []
        for line in f:
            cols = line.strip().split(",")
            if len(cols) > max(ix, ip):
                xs.append(float(cols[ix]))
                ps.append(float(cols[ip]))
    return np.array(xs), np.array(ps)


if __name__ == "__main__":
    import sys
    xs, ps = read_xp(sys.argv[1])
    print(evaluate(xs, ps, float(sys.argv[2])))
