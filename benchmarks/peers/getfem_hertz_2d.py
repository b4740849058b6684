"""2D Hertz scene of the peers benchmark (issue 32) in GetFEM.

Usage: getfem_hertz_2d.py DEGREE GLOBAL H_FINE GRADING ZONE OUT.csv

A quarter cylinder (R = 0.1 m, centre (0, 0.1); x >= 0, y <= 0.1),
E = 210 GPa, nu = 0.3, plane strain, pressed on the rigid plane y = 0 by
u_y = -0.386e-3 m on its flat top (u_x free there), u_x = 0 on x = 0.
The same scene as benchmarks/peers/signorini_hertz_2d.prm.

Mesh: the quarter disc as three mapped patches (a square around the centre
and two curved quadrilaterals, as deal.II's quarter ball), each split into
2^GLOBAL x 2^GLOBAL quadrilaterals, each cut into two triangles. GetFEM's
conforming (Bank) refinement then refines every triangle whose longest edge
exceeds the size function max(H_FINE, GRADING * d), d the distance of its
centroid to the contact zone (the curved face where 0 <= x <= ZONE), until
none does. The
refinement runs on the straight-sided mesh; a radial map from the centre
then puts the curved face's vertices on the circle.
DEGREE 1: P1 triangles; DEGREE 2: P2 triangles on 6-node (GT_PK(2,2))
triangles whose curved-face midpoints lie on the circle.

Contact: the integral augmented Lagrangian brick with a rigid obstacle
(add_integral_contact_with_rigid_obstacle_brick, option 1: non-symmetric
Alart-Curnier), frictionless, the obstacle the signed distance y,
augmentation r = E / h (h the shortest contact face), a multiplier (the
contact traction along the obstacle normal) of degree DEGREE on the curved
face. The top and symmetry conditions are normal Dirichlet conditions with
multipliers. Newton (md.solve, GetFEM's default step control) with MUMPS.

Writes OUT.csv: x, y (reference) and the nodal pressure p at the
multiplier's nodes, sorted by x; prints one line 'RESULT dofs=..
lambda_dofs=.. newton=.. converged=.. force_half=.. h=..' with the
vertical contact force of the half model (N/m).
"""

import sys

import numpy as np
import getfem as gf

E, NU, R = 2.1e11, 0.3, 0.1
CENTRE = np.array([0.0, 0.1])
TOP_DISPLACEMENT = -0.386e-3


def patch(c00, c10, c11, c01, edge, n):
    """Coons patch over the unit square with straight edges except the
    edge v = 0 when edge is given (a function of u in [0, 1])."""
    u, v = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1), indexing="ij")
    c00, c10, c11, c01 = (np.asarray(c)[:, None, None] for c in (c00, c10, c11, c01))
    bottom = edge(u) if edge is not None else (1 - u) * c00 + u * c10
    top = (1 - u) * c01 + u * c11
    left = (1 - v) * c00 + v * c01
    right = (1 - v) * c10 + v * c11
    bilinear = ((1 - u) * (1 - v) * c00 + u * (1 - v) * c10
                + u * v * c11 + (1 - u) * v * c01)
    return (1 - v) * bottom + v * top + (1 - u) * left + u * right - bilinear


def coarse_triangles(n):
    """Vertices and triangles of the three patches, n x n quads each."""
    s = 0.5 * R  # half side of the centre square
    c = CENTRE
    d = R / np.sqrt(2.0)
    arc = lambda t0, t1: (lambda u: c[:, None, None] + R * np.stack(
        [np.cos(t0 + (t1 - t0) * u), np.sin(t0 + (t1 - t0) * u)]))
    patches = [
        # centre square
        patch(c, c + [s, 0], c + [s, -s], c + [0, -s], None, n),
        # bottom patch, holds the contact point (0, 0)
        patch(c + [0, -R], c + [d, -d], c + [s, -s], c + [0, -s],
              arc(-np.pi / 2, -np.pi / 4), n),
        # right patch
        patch(c + [d, -d], c + [R, 0], c + [s, 0], c + [s, -s],
              arc(-np.pi / 4, 0.0), n),
    ]
    tris = []
    for P in patches:
        for i in range(n):
            for j in range(n):
                p00, p10, p11, p01 = P[:, i, j], P[:, i + 1, j], P[:, i + 1, j + 1], P[:, i, j + 1]
                # the diagonal through the corner nearest the contact point
                if np.linalg.norm(p00) + np.linalg.norm(p11) < np.linalg.norm(p10) + np.linalg.norm(p01):
                    tris += [(p00, p10, p11), (p00, p11, p01)]
                else:
                    tris += [(p00, p10, p01), (p10, p11, p01)]
    return np.array(tris).transpose(2, 1, 0)  # 2 x 3 x ntri


def classify_faces(m):
    """Outer faces split into curved (arc), top (y = 0.1) and symmetry
    (x = 0) by their end points."""
    faces = m.outer_faces()
    arc, top, sym = [], [], []
    for k in range(faces.shape[1]):
        pid = m.pid_in_faces(faces[:, k:k + 1])
        P = m.pts(pid)
        if np.all(np.abs(P[0]) < 1e-12):
            sym.append(k)
        elif np.all(np.abs(P[1] - CENTRE[1]) < 1e-12):
            top.append(k)
        else:
            arc.append(k)
    return faces[:, arc], faces[:, top], faces[:, sym]


def onto_circle(P, arc_pts):
    """Radial map from the centre that takes the polygon of the coarse
    curved-face vertices arc_pts onto the circle: each ray is stretched by
    R / (distance to the chord it crosses). Points on the chords land on the
    circle; the map is smooth within each chord's sector and moves points
    by at most the chord's sag (1.2e-4 m on 3 global levels)."""
    t = np.sort(np.arctan2(arc_pts[1] - CENTRE[1], arc_pts[0] - CENTRE[0]))
    d = P - CENTRE[:, None]
    r = np.linalg.norm(d, axis=0)
    theta = np.arctan2(d[1], d[0])
    k = np.clip(np.searchsorted(t, theta) - 1, 0, len(t) - 2)
    half = 0.5 * (t[k + 1] - t[k])
    mid = 0.5 * (t[k + 1] + t[k])
    rho = R * np.cos(half) / np.cos(theta - mid)
    scale = np.where(r > 0, R / rho, 1.0)
    return CENTRE[:, None] + d * scale


def build_mesh(degree, global_level, h_fine, grading, zone):
    m = gf.Mesh("empty", 2)
    m.add_convex(gf.GeoTrans("GT_PK(2,1)"), coarse_triangles(2 ** global_level))
    arc, _, _ = classify_faces(m)
    coarse_arc = m.pts(np.unique(m.pid_in_faces(arc)))
    # Refine the straight-sided mesh (its curved face a polygon) until every
    # triangle is smaller than the size function, then map it onto the
    # circle: the new vertices on the face then lie on the circle.
    for _ in range(40):
        P = m.pts()
        cvs = m.cvid()
        tri = m.pid_from_cvid(cvs)[0].reshape(-1, 3)
        X = P[:, tri]  # 2 x ntri x 3
        size = np.max(np.linalg.norm(X - np.roll(X, 1, axis=2), axis=0), axis=1)
        # centroid on the final (circular) geometry, its depth below the
        # curved face and its distance to the contact zone
        c = onto_circle(X.mean(axis=2), coarse_arc)
        depth = R - np.linalg.norm(c - CENTRE[:, None], axis=0)
        dist = np.hypot(np.maximum(c[0] - zone, 0.0), depth)
        near = size > np.maximum(h_fine, grading * dist) * 1.0001
        if not near.any():
            break
        m.refine(cvs[near])
    m.set_pts(onto_circle(m.pts(), coarse_arc))
    m.optimize_structure()
    if degree == 1:
        return m
    # 6-node triangles: the edge midpoints, on the circle for curved faces
    P = m.pts()
    tri = m.pid_from_cvid(m.cvid())[0].reshape(-1, 3)
    arc, _, _ = classify_faces(m)
    arc_pts = set(m.pid_in_faces(arc).tolist())
    v0, v1, v2 = (P[:, tri[:, i]] for i in range(3))

    def mid(a, b, ia, ib):
        q = 0.5 * (a + b)
        on = np.array([i in arc_pts and j in arc_pts for i, j in zip(ia, ib)])
        d = q[:, on] - CENTRE[:, None]
        q[:, on] = CENTRE[:, None] + R * d / np.linalg.norm(d, axis=0)
        return q

    m01 = mid(v0, v1, tri[:, 0], tri[:, 1])
    m02 = mid(v0, v2, tri[:, 0], tri[:, 2])
    m12 = mid(v1, v2, tri[:, 1], tri[:, 2])
    m2 = gf.Mesh("empty", 2)
    m2.add_convex(gf.GeoTrans("GT_PK(2,2)"),
                  np.stack([v0, m01, v1, m02, m12, v2], axis=1))
    return m2


def main():
    degree, glevel = int(sys.argv[1]), int(sys.argv[2])
    h_fine, grading, zone = (float(a) for a in sys.argv[3:6])
    out = sys.argv[6]
    m = build_mesh(degree, glevel, h_fine, grading, zone)
    arc, top, sym = classify_faces(m)
    CONTACT, TOP, SYM = 1, 2, 3
    m.set_region(CONTACT, arc)
    m.set_region(TOP, top)
    m.set_region(SYM, sym)

    mfu = gf.MeshFem(m, 2)
    mfu.set_fem(gf.Fem("FEM_PK(2,%d)" % degree))
    mfd = gf.MeshFem(m, 1)
    mfd.set_fem(gf.Fem("FEM_PK(2,%d)" % degree))
    mfl = gf.MeshFem(m, 1)
    mfl.set_fem(gf.Fem("FEM_PK(2,%d)" % degree))
    ldofs = mfl.basic_dof_on_region(CONTACT)
    mfl_c = gf.MeshFem("partial", mfl, ldofs)
    mim = gf.MeshIm(m, gf.Integ("IM_TRIANGLE(%d)" % (2 * degree if degree > 1 else 2)))

    # Stresses in units of E (the solve uses E = 1): GetFEM's Newton test is
    # the L1 norm of the whole residual (force and displacement rows)
    # against 'max_res'; in Pa the round-off of the force rows (about 1e-12 E)
    # stays above every tolerance that still tells a converged state.
    lam = NU / ((1 + NU) * (1 - 2 * NU))  # plane strain Lame parameters / E
    mu = 1.0 / (2 * (1 + NU))
    md = gf.Model("real")
    md.add_fem_variable("u", mfu)
    md.add_initialized_data("lambda", [lam])
    md.add_initialized_data("mu", [mu])
    md.add_isotropic_linearized_elasticity_brick(mim, "u", "lambda", "mu")
    md.add_initialized_data("top", [TOP_DISPLACEMENT])
    md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", degree, TOP, "top")
    md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", degree, SYM)

    md.add_fem_variable("lambda_n", mfl_c)
    # augmentation parameter E / h, h the shortest contact face (chord)
    h = min(np.max(np.linalg.norm(q[:, :, None] - q[:, None, :], axis=0))
            for q in (m.pts(m.pid_in_faces(arc[:, k:k + 1])) for k in range(arc.shape[1])))
    md.add_initialized_data("r", [1.0 / h])
    md.add_initialized_fem_data("obstacle", mfd, mfd.eval("y"))
    md.add_integral_contact_with_rigid_obstacle_brick(
        mim, "u", "lambda_n", "obstacle", "r", CONTACT, 1)

    gf.util_trace_level(1)
    nit, converged = (md.solve("noisy", "max_iter", 40, "max_res", 1e-9, "lsolver", "mumps"))
    L = md.variable("lambda_n")
    # Nodal pressure = nodal contact force / nodal length, (M L)_i / (M 1)_i
    # with M the multiplier's mass matrix on the contact face. The
    # multiplier's own nodal values are its L2 projection, which rings
    # beyond the contact edge (alternating values of up to 0.4 % of p0).
    M = gf.asm_mass_matrix(mim, mfl_c, mfl_c, CONTACT)
    L = M.mult(L) / M.mult(np.ones(mfl_c.nbdof()))
    nodes = mfl.basic_dof_nodes(ldofs)
    # vertical contact force: the multiplier is the traction along the
    # obstacle's normal (0, 1), so the force is its integral
    force = E * gf.asm("generic", mim, 0, "lambda_n", CONTACT, md)
    order = np.argsort(nodes[0])
    with open(out, "w") as f:
        f.write("x,y,p\n")
        for k in order:
            f.write("%.12e,%.12e,%.12e\n" % (nodes[0, k], nodes[1, k], -E * L[k]))
    print("RESULT dofs=%d lambda_dofs=%d newton=%d converged=%d force_half=%.10e h=%.4e"
          % (mfu.nbdof(), mfl_c.nbdof(), nit, converged, abs(force), h))


if __name__ == "__main__":
    main()
