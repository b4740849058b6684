#!/usr/bin/python3
"""contact_surface.py <results directory> [<results of the same scene>]

Reads the contact surface output of the last written step back
(contact_surface.pvd -> its last .pvtu -> every rank's .vtu piece, with
scripts/vtu_reader.py) and checks it against statistics.csv, for a scene
whose contact force is normal to a flat rigid master (a plane), so that the
force on the master of pair 1 equals the integral of the contact pressure
over the slave surface:
 - every slave face is written once (no face in two pieces);
 - statistics.csv's per-pair columns: contact_force_1_normal equals
   |contact force| (1e-6); the closed area (contact_area_1, in 2D
   contact_length_1) lies between the area of the faces closed at every
   node (not with statuses per node) and of those closed at some node;
 - the integral of the nodal contact_pressure (interpolated linearly on
   each written face: segments in 2D, bilinear quadrilaterals in 3D) equals
   |contact force of pair 1| of the same step to 1e-5 (the pressures are
   written as 32-bit floats);
 - the status agrees with the pressure: a node with pressure above 1e-8 of
   the largest is closed (status > 0), an open node (status 0) carries no
   pressure;
 - the contact CSV of that step has one row per slave node: the same
   nodes as the surface VTU, each once, with the VTU's pressure (to 1e-6
   of the largest) and x_deformed - x equal to the VTU's displacement (to
   1e-6 of the largest);
 - with a second directory (the same scene on another number of ranks):
   the same faces, with the same nodal pressures to 1e-6 of the largest.
Prints the numbers; exit code 1 on failure.
"""
import csv
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..", "scripts"))
from vtu_reader import read_series  # noqa: E402

fails = []


def face_integral(x, p):
    """(integral of p, area) over a segment or a bilinear quadrilateral."""
    if len(x) == 2:
        length = math.dist(x[0], x[1])
        return 0.5 * (p[0] + p[1]) * length, length
    # deal.II's VTU quadrilateral (VTK node order), 2x2 Gauss points.
    g = 0.5 / math.sqrt(3)
    integral = area = 0.0
    for s in (0.5 - g, 0.5 + g):
        for t in (0.5 - g, 0.5 + g):
            N = [(1 - s) * (1 - t), s * (1 - t), s * t, (1 - s) * t]
            dNs = [-(1 - t), 1 - t, t, -t]
            dNt = [-(1 - s), -s, s, 1 - s]
            xs = [sum(dNs[k] * x[k][d] for k in range(4)) for d in range(3)]
            xt = [sum(dNt[k] * x[k][d] for k in range(4)) for d in range(3)]
            J = math.sqrt((xs[1] * xt[2] - xs[2] * xt[1]) ** 2 +
                          (xs[2] * xt[0] - xs[0] * xt[2]) ** 2 +
                          (xs[0] * xt[1] - xs[1] * xt[0]) ** 2)
            integral += 0.25 * J * sum(N[k] * p[k] for k in range(4))
            area += 0.25 * J
    return integral, area


def node_statuses(directory):
    """True if pair 1 decides its statuses per node (parameters.prm echo:
    a meshed master and an integration-point rule, i.e. not nodal)."""
    with open(os.path.join(directory, "parameters.prm")) as f:
        settings = dict(line.strip()[4:].split("=", 1) for line in f
                        if line.strip().startswith("set ") and "=" in line)
    settings = {k.strip(): v.strip() for k, v in settings.items()}
    return (settings.get("Master") == "body" and
            settings.get("Integration rule") != "nodal")


def check_csv(directory, pieces):
    """The last contact_NNNN.csv against the surface VTU: one row per
    written node, the same pressure and displacement."""
    name = sorted(f for f in os.listdir(directory)
                  if f.startswith("contact_") and f.endswith(".csv"))[-1]
    with open(os.path.join(directory, name)) as f:
        rows = list(csv.DictReader(f))
    points = [x for piece in pieces for x in piece["points"]]
    scale = max(abs(c) for x in points for c in x) or 1.0
    dim = 3 if "z" in rows[0] else 2

    def key(x):
        return tuple(round(c / scale, 5) for c in x[:dim])

    vtu = {}
    for piece in pieces:
        data = piece["point_data"]
        for i, x in enumerate(piece["points"]):
            vtu[key(x)] = (data["contact_pressure"][i], data["displacement"][i])
    p_max = max(abs(p) for p, _ in vtu.values())
    u_max = max(abs(c) for _, u in vtu.values() for c in u[:dim]) or 1.0
    keys = [key([float(r[a]) for a in "xyz"[:dim]]) for r in rows]
    dp = du = 0.0
    for r, k in zip(rows, keys):
        if k not in vtu:
            fails.append("%s: the node %s is not in the surface VTU" % (name, k))
            return
        p, u = vtu[k]
        dp = max(dp, abs(float(r["p"]) - p))
        for d, a in enumerate("xyz"[:dim]):
            du = max(du, abs(float(r[a + "_deformed"]) - float(r[a]) - u[d]))
    print("%s: %d rows, %d surface VTU nodes; pressure within %.2e, "
          "x_deformed - x within %.2e of the largest (tolerance 1e-6)" % (
              name, len(rows), len(vtu), dp / p_max, du / u_max))
    if len(set(keys)) != len(keys) or len(keys) != len(vtu):
        fails.append("%s: %d rows for %d nodes (%d distinct)" % (
            name, len(keys), len(vtu), len(set(keys))))
    if dp > 1e-6 * p_max or du > 1e-6 * u_max:
        fails.append("%s: values differ from the surface VTU" % name)


def read_run(directory):
    """{face centre: its nodal pressures}, integral, area, |force|, ..."""
    pieces, pvtu_name = read_series(directory, "contact_surface")
    with open(os.path.join(directory, "statistics.csv")) as f:
        stats = list(csv.DictReader(f))[-1]
    force = [float(stats["contact_force_1_" + axis]) for axis in "xyz"
             if "contact_force_1_" + axis in stats]
    faces, integral, area, nodes = {}, 0.0, 0.0, []
    # The area of the faces with every node closed and of those with some
    # node closed: the closed area of statistics.csv lies between them.
    all_closed = some_closed = 0.0
    for k, piece in enumerate(pieces):
        p = piece["point_data"]["contact_pressure"]
        nodes += zip(p, piece["point_data"]["status"])
        for cell in piece["cells"]:
            x = [piece["points"][i] for i in cell]
            centre = tuple(round(sum(y[d] for y in x) / len(x), 12) for d in range(3))
            if centre in faces:
                fails.append("piece %d: the face at %s is written twice" % (k, centre))
            faces[centre] = sorted(p[i] for i in cell)
            df, da = face_integral(x, [p[i] for i in cell])
            integral += df
            area += da
            closed = [piece["point_data"]["status"][i] > 0 for i in cell]
            all_closed += da if all(closed) else 0.0
            some_closed += da if any(closed) else 0.0
    p_max = max(p for p, _ in nodes)
    check_csv(directory, pieces)
    for p, s in nodes:
        if p > 1e-8 * p_max and s <= 0:
            fails.append("a node with pressure %.6g is open (status %g)" % (p, s))
            break
        if s == 0 and abs(p) > 1e-8 * p_max:
            fails.append("an open node carries pressure %.6g" % p)
            break
    print("%s: %d faces in %d piece(s), surface area %.6g, largest nodal "
          "pressure %.6g" % (pvtu_name, len(faces), len(pieces), area, p_max))
    # The per-pair columns: the normal force in the contact frames equals
    # |contact force| on a flat master; the closed area (length in 2D)
    # lies between the areas of the faces closed at all and at some nodes.
    closed_area = float(stats.get("contact_area_1", stats.get("contact_length_1", "nan")))
    normal = float(stats["contact_force_1_normal"])
    norm = math.sqrt(sum(f * f for f in force))
    print("statistics.csv: normal force %.8g (|contact force| %.8g), closed "
          "area %.6g, between %.6g and %.6g (faces closed at every node, at "
          "some node)" % (normal, norm, closed_area, all_closed, some_closed))
    if abs(normal - norm) > 1e-6 * norm:
        fails.append("contact_force_1_normal differs from |contact force|")
    # With statuses per node (an integration-point rule on a meshed master)
    # a node may close for a sliver of its faces that faces the master:
    # only the upper bound holds there.
    lower = 0.0 if node_statuses(directory) else all_closed
    if not lower * (1 - 1e-6) <= closed_area <= some_closed * (1 + 1e-6):
        fails.append("the closed area of statistics.csv is outside the closed faces' bounds")
    return faces, integral, norm, p_max


faces, integral, force_norm, p_max = read_run(sys.argv[1])
error = abs(integral - force_norm) / force_norm
print("integral of the pressure %.8g, |contact force| %.8g, relative "
      "difference %.2e (tolerance 1e-5)" % (integral, force_norm, error))
if error > 1e-5:
    fails.append("the integral of the written pressure differs from the contact force")
if len(sys.argv) > 2:
    other = read_run(sys.argv[2])[0]
    if set(other) != set(faces):
        fails.append("%d faces, %d in %s; %d differ" % (
            len(faces), len(other), sys.argv[2], len(set(other) ^ set(faces))))
    else:
        largest = max(abs(a - b) for c in faces for a, b in zip(faces[c], other[c]))
        print("against %s: the same %d faces, nodal pressures within %.2e of "
              "the largest (tolerance 1e-6)" % (sys.argv[2], len(faces), largest / p_max))
        if largest > 1e-6 * p_max:
            fails.append("the nodal pressures differ from %s" % sys.argv[2])
for f in fails[:10]:
    print("FAIL: " + f)
if fails:
    sys.exit(1)
print("PASS")
