#!/usr/bin/python3
"""kill_during_write.py <pid> <results directory> <steps> <ranks>

Waits until statistics.csv lists <steps> steps, then until a result file is
being written (a *.tmp file exists: the moment a kill used to leave a
truncated file behind), at most 2 s, and kills the run with SIGKILL: the
process <pid> itself on one rank; on several ranks (<pid> is mpirun) every
rank at once, then mpirun. Prints what it caught. Exit code 1 if the run
ended before it could be killed or statistics.csv never got the steps.
"""
import os
import signal
import sys
import time

pid, directory, steps, ranks = int(sys.argv[1]), sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
statistics = os.path.join(directory, "statistics.csv")


def alive():
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().split(") ")[-1].split()[0] != "Z"
    except OSError:
        return False


def children():
    """The processes whose parent is pid (mpirun's ranks)."""
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open("/proc/%s/stat" % entry) as f:
                    if int(f.read().split(") ")[-1].split()[1]) == pid:
                        found.append(int(entry))
            except (OSError, ValueError, IndexError):
                pass
    return found


def lines():
    try:
        with open(statistics, "rb") as f:
            return f.read().count(b"\n")
    except OSError:
        return 0


deadline = time.time() + 15
while lines() < steps + 1:
    if not alive() or time.time() > deadline:
        print("FAIL: the run %s before statistics.csv listed %d steps"
              % ("ended" if not alive() else "took too long", steps))
        sys.exit(1)
    time.sleep(0.005)
targets = children() if ranks > 1 else [pid]
if ranks > 1 and len(targets) != ranks:
    print("FAIL: mpirun %d has %d child processes, expected %d ranks" % (pid, len(targets), ranks))
    sys.exit(1)
caught = []
window = time.time() + 2
while not caught and time.time() < window:
    caught = [n for n in os.listdir(directory) if n.endswith(".tmp")]
for target in targets:
    os.kill(target, signal.SIGKILL)
if ranks > 1:
    time.sleep(0.2)
    try:
        os.kill(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
print("killed %s after %d steps in statistics.csv, %s"
      % ("the run" if ranks == 1 else "%d ranks" % ranks, lines() - 1,
         "while writing " + ", ".join(sorted(caught)) if caught else "between writes"))
