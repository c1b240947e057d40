#!/usr/bin/python3
"""bench/compare on stand-ins for benchmark binaries: scripts that print Google Benchmark's JSON
with the time written into their own file, so that every copy of a build reports the same. Checks
the medians, the copies' range and the ratio it prints, and the exit status 2 with a message for
what it must refuse.

usage: bench_compare_test.py SOURCE_DIR WORKDIR
"""
import os
import shutil
import subprocess
import sys

source, work = sys.argv[1:]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
compare = os.path.join(source, "bench", "compare")
failures = []

STAND_IN = """#!/usr/bin/python3
import json, sys
filt = [a for a in sys.argv if a.startswith("--benchmark_filter=")][0].split("=", 1)[1]
runs = [{"name": "BM_A/no_vcd/real_time", "run_type": "iteration", "real_time": %(a)s, "time_unit": "us"},
        {"name": "BM_B/vcd/real_time", "run_type": "iteration", "real_time": %(b)s, "time_unit": "ms"},
        {"name": "BM_B/vcd/real_time_median", "run_type": "aggregate", "real_time": 1, "time_unit": "ms"}]
print(json.dumps({"benchmarks": [r for r in runs if filt in ("all", r["name"][3])]}))
"""


def stand_in(name, a_us, b_ms):
    path = os.path.join(work, name)
    with open(path, "w") as f:
        f.write(STAND_IN % {"a": a_us, "b": b_ms})
    os.chmod(path, 0o755)
    return path


def check(condition, what, r):
    if not condition:
        failures.append("%s\n  exit %d\n  stdout: %s\n  stderr: %s" % (what, r.returncode, r.stdout, r.stderr))


def run(*args):
    return subprocess.run([sys.executable, compare, *args], capture_output=True, text=True, timeout=120)


old = stand_in("old", 40000, 60)
new = stand_in("new", 30000, 66)
r = run("--copies", "2", "--rounds", "2", "--filter", "all", old, new)
check(r.returncode == 0, "two builds compared", r)
lines = r.stdout.splitlines()
check(lines[0] == "real time in ms: median of 2 copies x 2 rounds [the copies' medians from .. to]", "the heading", r)
check("BM_A/no_vcd/real_time" in lines and "BM_B/vcd/real_time" in lines, "both benchmarks, the aggregate left out", r)
check(not any("_median" in line for line in lines), "no aggregate row", r)
a = lines.index("BM_A/no_vcd/real_time")
check(lines[a + 1].split() == [old, "40.00", "[40.00", "..", "40.00]"], "the first build: microseconds in ms, no ratio", r)
check(lines[a + 2].split() == [new, "30.00", "[30.00", "..", "30.00]", "0.750x"], "the second build's ratio to the first", r)
b = lines.index("BM_B/vcd/real_time")
check(lines[b + 2].split()[-1] == "1.100x", "milliseconds kept as they are", r)

r = run("--filter", "B", old)
check(r.returncode == 0 and "BM_A/no_vcd/real_time" not in r.stdout and "BM_B/vcd/real_time" in r.stdout,
      "the filter is handed to the binaries", r)

for args, message in [
    ((os.path.join(work, "missing"),), "is not an executable file"),
    (("--filter", "nothing", old), "no benchmark matches --filter 'nothing'"),
    (("--copies", "0", old), "expected a whole number of at least 1, got '0'"),
    (("--rounds", "x", old), "expected a whole number of at least 1, got 'x'"),
]:
    r = run(*args)
    check(r.returncode == 2 and message in r.stderr, "refused with exit 2: " + message, r)

broken = os.path.join(work, "broken")
with open(broken, "w") as f:
    f.write("#!/bin/sh\necho not json\n")
os.chmod(broken, 0o755)
r = run(broken)
check(r.returncode == 2 and "did not print Google Benchmark's JSON" in r.stderr, "a binary that prints no JSON", r)

# The copies live in a temporary folder that is gone afterwards, also after a refusal.
tmp = os.path.join(work, "tmp")
os.makedirs(tmp)
for args in [(old, new), (broken,)]:
    r = subprocess.run([sys.executable, compare, "--copies", "2", *args], capture_output=True, text=True, timeout=120,
                       env=dict(os.environ, TMPDIR=tmp))
    check(os.listdir(tmp) == [], "no copies left behind", r)

if failures:
    print("\n".join(failures))
    sys.exit(1)
print("bench/compare: all checks passed")
