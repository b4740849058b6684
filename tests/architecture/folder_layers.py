#!/usr/bin/python3
"""The folders of the library include one another downwards only: the
graph of '#include <signorini/<folder>/...>' between the folders of
include/signorini/ and source/ (include/ mirrors source/, so a folder's
header and source count as one) has no cycle. Prints the folders in an
order where each includes only folders before it, or the first cycle
found and the files that close it.

    folder_layers.py <source directory>
"""
import collections
import os
import re
import sys

top = sys.argv[1]
edges = collections.defaultdict(lambda: collections.defaultdict(list))
folders = set()
for root in ("include/signorini", "source"):
    for directory, _, names in os.walk(os.path.join(top, root)):
        for name in names:
            if not name.endswith((".h", ".cc")):
                continue
            path = os.path.join(directory, name)
            rel = os.path.relpath(path, os.path.join(top, root))
            if "/" not in rel:
                continue  # source/main.cc: the executable, not the library
            folder = rel.split("/")[0]
            folders.add(folder)
            for line in open(path):
                m = re.match(r"\s*#\s*include\s*<signorini/([a-z_]+)/", line)
                if m and m.group(1) != folder:
                    edges[folder][m.group(1)].append(os.path.relpath(path, top))

# Kahn's algorithm: a folder is placed once every folder it includes is.
order, placed = [], set()
while len(placed) < len(folders):
    ready = sorted(f for f in folders - placed if set(edges[f]) <= placed)
    if not ready:
        break
    order += ready
    placed |= set(ready)

if len(placed) < len(folders):
    # A cycle among the rest: walk includes until a folder repeats.
    rest = folders - placed
    f, path = sorted(rest)[0], []
    while f not in path:
        path.append(f)
        f = sorted(g for g in edges[f] if g in rest)[0]
    cycle = path[path.index(f):] + [f]
    print("FAIL: the folders include one another: " + " -> ".join(cycle))
    for a, b in zip(cycle, cycle[1:]):
        print("  %s -> %s: %s" % (a, b, ", ".join(edges[a][b][:3])))
    sys.exit(1)
print("folders in include order (each includes only folders before it):")
for f in order:
    print("  %-12s includes %s" % (f, ", ".join(sorted(edges[f])) or "none"))
print("PASS: no two folders include each other, directly or through others")
