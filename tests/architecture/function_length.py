#!/usr/bin/python3
# A function fits on a screen or two: no function of source/ or include/
# is longer than LIMIT lines (from its opening to its closing brace, in
# clang-format's layout). The 9 functions that were longer when the rule
# came (issue 63) have been split; ALLOWED, the list of exceptions with
# their length, is empty and may only shrink: a listed function may not
# grow, and one that is gone or short enough must leave the list.
import glob, re, sys

LIMIT = 100
ALLOWED = {}

CONTROL = re.compile(r"^\s*(if|for|while|switch|else|catch|do|try)\b")


def functions(path):
    lines = open(path).read().split("\n")
    i = 0
    while i < len(lines):
        m = re.match(r"^(\s*)\{\s*$", lines[i])
        prev = lines[i - 1].rstrip() if i > 0 else ""
        if m and re.search(r"\)(\s*(const|override|noexcept|final))*$", prev):
            # the line that opens the parameter list
            k = i - 1
            depth = 0
            while k >= 0:
                depth += lines[k].count(")") - lines[k].count("(")
                if depth <= 0:
                    break
                k -= 1
            if k >= 0 and not CONTROL.match(lines[k]) and "=" not in lines[k].split("(")[0]:
                indent = m.group(1)
                j = i + 1
                while j < len(lines) and not re.match("^" + indent + r"\}", lines[j]):
                    j += 1
                name = re.sub(r"\s*\(.*", "", lines[k].strip())
                yield name, i + 1, j - i + 1
                i = j
        i += 1


top = sys.argv[1]
found, failures = {}, []
for pattern in ("source/**/*.cc", "source/**/*.h", "include/**/*.h"):
    for path in sorted(glob.glob(top + "/" + pattern, recursive=True)):
        rel = path[len(top) + 1:]
        for name, line, n in functions(path):
            if n > LIMIT:
                key = rel + ":" + name
                found[key] = n
                allowed = ALLOWED.get(key)
                if allowed is None:
                    failures.append(f"{rel}:{line}: {name} has {n} lines (at most {LIMIT}): split it")
                elif n > allowed:
                    failures.append(f"{rel}:{line}: {name} grew to {n} lines (listed at {allowed}): split it")
for key, n in ALLOWED.items():
    if key not in found:
        failures.append(f"{key}: listed at {n} lines, now at most {LIMIT} or gone: delete it from ALLOWED")
for key, n in sorted(found.items(), key=lambda x: -x[1]):
    print(f"{n:4d} {key}")
if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"every other function has at most {LIMIT} lines")
