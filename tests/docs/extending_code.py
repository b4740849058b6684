#!/usr/bin/python3
# Every C++ block of doc/extending.md is code of the repository: its lines,
# stripped of leading and trailing blanks and without empty lines, appear
# as a contiguous run in one file under tests/, source/ or include/ (the
# examples are the test programs tests/*_plugin.cc). A line with "..."
# stands for lines the guide leaves out: the runs between such lines must
# appear in that order in the same file. A block that no file holds means
# the guide and the code have drifted apart.
import glob, re, sys

top = sys.argv[1]
guide = open(top + "/doc/extending.md").read()
blocks = re.findall(r"```cpp\n(.*?)```", guide, re.S)


def lines(text):
    return [l.strip() for l in text.split("\n") if l.strip()]


files = {}
for pattern in ("tests/**/*.cc", "source/**/*.cc", "source/**/*.h",
                "include/**/*.h"):
    for f in glob.glob(top + "/" + pattern, recursive=True):
        files[f[len(top) + 1:]] = lines(open(f).read())


def holds(text, block):
    # The runs of the block between "..." lines, in order.
    runs, run = [], []
    for line in block:
        if "..." in line:
            runs.append(run)
            run = []
        else:
            run.append(line)
    runs.append(run)
    start = 0
    for run in (r for r in runs if r):
        n = len(run)
        found = next((i for i in range(start, len(text) - n + 1)
                      if text[i:i + n] == run), None)
        if found is None:
            return False
        start = found + n
    return True


failed = 0
for k, block in enumerate(blocks, 1):
    b = lines(block)
    where = [f for f, text in files.items() if holds(text, b)]
    if where:
        print("block %d (%d lines): in %s" % (k, len(b), where[0]))
    else:
        failed += 1
        print("block %d (%d lines) is in no file; it starts with: %s"
              % (k, len(b), b[0] if b else ""))
print("%d of %d C++ blocks of doc/extending.md found in the code"
      % (len(blocks) - failed, len(blocks)))
sys.exit(1 if failed else 0)
