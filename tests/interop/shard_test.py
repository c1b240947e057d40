#!/usr/bin/python3
"""Regressions and sweeps split across processes, as a CI matrix or a cluster runs them: every
shard is its own endatsim process, all running at once; `endatsim merge` joins their partials,
and the joined files must be byte-identical to what one unsharded process writes. Then what a
merge must refuse: a missing or doubled shard, partials of another run or other options, a
whole run's file, a cut or altered partial.

usage: shard_test.py ENDATSIM SOURCE_DIR WORKDIR
"""
import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import jsonschema

endatsim, source, work = sys.argv[1:]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
failures = []


def path(*names):
    return os.path.join(work, *names)


def run(*args):
    return subprocess.run([endatsim, *args], capture_output=True, text=True, timeout=600)


def check(condition, what, r=None):
    if not condition:
        failures.append(what + ("" if r is None else "\n  exit %d\n  stdout: %s\n  stderr: %s" % (r.returncode, r.stdout[:2000], r.stderr[:2000])))


def in_parallel(commands):
    """Starts every command at once, as separate processes, and waits for all."""
    procs = [subprocess.Popen([endatsim, *c], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for c in commands]
    results = []
    for p in procs:
        out, err = p.communicate(timeout=600)
        results.append(subprocess.CompletedProcess(p.args, p.returncode, out, err))
    return results


def same_bytes(a, b):
    with open(a, "rb") as x, open(b, "rb") as y:
        return x.read() == y.read()


# A failing scenario among passing ones, so that the verdict and the JUnit failures must add up.
failing = path("zz_failing.json")
with open(failing, "w") as f:
    f.write('{"name": "expects_two_reads", "line": {"cable_length_m": 1}, "master": {"f_c": "1 MHz"},'
            ' "script": [{"op": "read_position"}], "expect": {"outcomes": {"ok": 2}}}')
scenarios = [os.path.join(source, "scenarios", "field"), os.path.join(source, "scenarios", "safety"), failing]
outputs = {"json": "json", "junit": "xml", "log": "log", "log-json": "jsonl"}


def output_args(prefix):
    args = []
    for option, ext in outputs.items():
        args += ["--" + option, path("%s.%s" % (prefix, ext))]
    return args


whole = run("run", *scenarios, *output_args("whole"), "--junit-cases", "expectation", "--seed", "7")
check(whole.returncode == 1, "the whole run fails (one scenario expects two reads)", whole)

for n in (1, 3, 7):
    shards = in_parallel([["run", *scenarios, "--shard", "%d/%d" % (k, n), *output_args("n%d_k%d" % (n, k)),
                           "--junit-cases", "expectation", "--seed", "7"] for k in range(1, n + 1)])
    statuses = [r.returncode for r in shards]
    check(1 in statuses and set(statuses) <= {0, 1}, "%d shards: the one with the failing scenario exits 1, others 0: %s" % (n, statuses))
    for k, r in enumerate(shards, 1):
        check(("shard %d/%d: " % (k, n)) in r.stdout, "shard %d/%d names itself in its summary" % (k, n), r)
    partials = [path("n%d_k%d.%s" % (n, k, ext)) for k in range(n, 0, -1) for ext in outputs.values()]  # any order
    merged = run("merge", *partials, *output_args("merged%d" % n))
    check(merged.returncode == 1 and "some scenarios failed" in merged.stdout, "merge of %d shards gives the run's verdict" % n, merged)
    for ext in outputs.values():
        check(same_bytes(path("whole." + ext), path("merged%d.%s" % (n, ext))), "%d shards merged: .%s identical to the whole run" % (n, ext))

# Each partial is a valid file of its kind on its own: the results validate against the schema
# (with their "shard"), the JUnit parses, every JSON line parses.
schema = json.load(open(os.path.join(source, "schema", "results.schema.json")))
partial = json.load(open(path("n3_k2.json")))
try:
    jsonschema.validate(partial, schema, cls=jsonschema.Draft202012Validator)
except jsonschema.ValidationError as e:
    failures.append("a partial does not validate against the results schema: %s at %s" % (e.message, list(e.absolute_path)))
check(partial["shard"]["index"] == 2 and partial["shard"]["count"] == 3, "the partial's shard names it")
check("shard" not in json.load(open(path("merged3.json"))), "the merged results have no shard")
try:
    ET.parse(path("n3_k2.xml"))
except ET.ParseError as e:
    failures.append("a JUnit partial does not parse: %s" % e)
for line in open(path("n3_k2.jsonl")):
    json.loads(line)

# More shards than files: the empty shards write empty partials, and the merge is still the run.
few = [os.path.join(source, "scenarios", "bundled", "endat21_1mhz_10m.json"), failing]
run("run", *few, "--json", path("few.json"), "--log", path("few.log"))
shards = in_parallel([["run", *few, "--shard", "%d/4" % k, "--json", path("few%d.json" % k), "--log", path("few%d.log" % k)]
                      for k in range(1, 5)])
check(sum("no scenario file" in r.stdout for r in shards) == 2, "two of four shards have no file")
merged = run("merge", *[path("few%d.%s" % (k, e)) for k in range(1, 5) for e in ("json", "log")],
             "--json", path("few_merged.json"), "--log", path("few_merged.log"))
check(merged.returncode == 1 and same_bytes(path("few.json"), path("few_merged.json")) and
      same_bytes(path("few.log"), path("few_merged.log")), "empty shards merge to the run", merged)

# A limit that ends every run early: the merge is incomplete (exit 3) like the run.
limited = [os.path.join(source, "scenarios", "field")]
whole = run("run", *limited, "--max-kernel-events", "2000", "--json", path("lim.json"), "--log", path("lim.log"),
            "--log-json", path("lim.jsonl"))
check(whole.returncode == 3, "the limited run is incomplete", whole)
# Its JSON lines end with a record that says so, as its text log ends with "# incomplete".
with open(path("lim.jsonl")) as f:
    last = json.loads(f.read().splitlines()[-1])
check("incomplete" in last and isinstance(last.get("not_run"), list), "the JSON lines of an incomplete run say so")
in_parallel([["run", *limited, "--max-kernel-events", "2000", "--shard", "%d/2" % k, "--json", path("lim%d.json" % k),
              "--log", path("lim%d.log" % k), "--log-json", path("lim%d.jsonl" % k)] for k in (1, 2)])
merged = run("merge", *[path("lim%d.%s" % (k, e)) for k in (1, 2) for e in ("json", "log", "jsonl")],
             "--json", path("lim_merged.json"), "--log", path("lim_merged.log"), "--log-json", path("lim_merged.jsonl"))
check(merged.returncode == 3 and "incomplete: " in merged.stdout, "the merge of incomplete shards is incomplete", merged)
check(same_bytes(path("lim.json"), path("lim_merged.json")) and same_bytes(path("lim.log"), path("lim_merged.log")) and
      same_bytes(path("lim.jsonl"), path("lim_merged.jsonl")), "incomplete shards merge to the incomplete run")

# A sweep: grid points split across shards, merged into the same CSV, JSON, SVG and table.
sweep = os.path.join(source, "scenarios", "sweeps", "figure2.json")
grid = ["--grid", "/line/cable_length_m=0:150:50", "--grid", "/master/f_c=1 MHz,4 MHz,8 MHz", "--grid",
        "/master/delay_compensation=false,true"]
sweep_out = ["--maximize", "/master/f_c", "--csv", path("sweep.csv"), "--json", path("sweep.json"), "--svg", path("sweep.svg")]
whole = run("sweep", sweep, *grid, *sweep_out)
check(whole.returncode == 0, "the whole sweep runs", whole)
shards = in_parallel([["sweep", sweep, *grid, "--jobs", "1", "--shard", "%d/5" % k, "--json", path("sweep%d.json" % k)]
                      for k in range(1, 6)])
check(all(r.returncode == 0 for r in shards), "every sweep shard runs")
merged = run("merge", *[path("sweep%d.json" % k) for k in range(1, 6)], "--maximize", "/master/f_c", "--csv",
             path("sweep_merged.csv"), "--json", path("sweep_merged.json"), "--svg", path("sweep_merged.svg"))
check(merged.returncode == 0 and merged.stdout == whole.stdout, "the merge prints the sweep's count and table", merged)
for ext in ("csv", "json", "svg"):
    check(same_bytes(path("sweep." + ext), path("sweep_merged." + ext)), "sweep shards merged: .%s identical" % ext)
# More shards than points: a shard with none still carries the sweep's name (point 0's), so that
# the partials merge (before, it wrote "" and the merge refused the others).
small = ["--grid", "/line/cable_length_m=0,50"]
whole = run("sweep", sweep, *small, "--csv", path("small.csv"), "--json", path("small.json"))
check(whole.returncode == 0, "the two-point sweep runs", whole)
shards = [run("sweep", sweep, *small, "--jobs", "1", "--shard", "%d/3" % k, "--json", path("small%d.json" % k))
          for k in range(1, 4)]
check(all(r.returncode == 0 for r in shards), "every shard of the two-point sweep runs, one of them empty")
merged = run("merge", *[path("small%d.json" % k) for k in range(1, 4)], "--csv", path("small_merged.csv"), "--json",
             path("small_merged.json"))
check(merged.returncode == 0 and merged.stdout == whole.stdout, "three shards of two points merge", merged)
for ext in ("csv", "json"):
    check(same_bytes(path("small." + ext), path("small_merged." + ext)), "an empty shard merged: .%s identical" % ext)

# What a merge refuses, each with exit 2 and a message naming the partial and the reason.
def refused(what, expected, *args):
    r = run("merge", *args)
    check(r.returncode == 2 and expected in r.stderr and r.stdout == "", "merge refuses " + what, r)


k3 = [path("n3_k%d.json" % k) for k in (1, 2, 3)]
with open(path("x.json"), "w") as f:
    f.write("an earlier merge's results")
refused("a missing shard", "--json: 1 of 3 shards missing (2)", k3[0], k3[2], "--json", path("x.json"))
refused("a doubled sweep shard", "small2.json: is the sweep --json partial of shard 2/3, and so is",
        *[path("small%d.json" % k) for k in (1, 2, 2, 3)], "--csv", path("x.csv"))
refused("a doubled shard", "is the --json partial of shard 2/3, and so is", k3[0], k3[1], k3[1], k3[2], "--json", path("x.json"))
refused("shards of different splits", "one of 7 shards, not of 3", k3[0], path("n7_k2.json"), "--json", path("x.json"))
run("run", *few, "--shard", "2/3", "--json", path("other2.json"))
refused("another run's partials", "ran other scenario files", k3[0], path("other2.json"), k3[2], "--json", path("x.json"))
refused("a whole run's file", "not of a shard", path("whole.json"), "--json", path("x.json"))
refused("a whole run's log", "a log of a whole run has none", path("whole.log"), "--log", path("x.log"))
refused("sweep options on run partials", "--csv is for a sweep's partials", *k3, "--csv", path("x.csv"))
refused("run options on sweep partials", "--junit is an output of a run", path("sweep1.json"), "--junit", path("x.xml"))
refused("writing over a partial", "--json", *k3, "--json", k3[0])
run("run", *scenarios, "--shard", "2/3", "--json", path("seed8.json"), "--seed", "8")
refused("partials of other options", "ran with other options", k3[0], path("seed8.json"), k3[2], "--json", path("x.json"))
# A partial cut short, or with a scenario object torn out.
text = open(k3[1]).read()
with open(path("cut.json"), "w") as f:
    f.write(text[: len(text) // 2])
refused("a cut partial", "cut.json: not a JSON document", k3[0], path("cut.json"), k3[2], "--json", path("x.json"))
with open(path("torn.json"), "w") as f:
    start = text.index("\n    {\n")
    end = text.index("\n    },\n", start) + len("\n    },")
    f.write(text[:start] + text[end:])
refused("a partial missing a scenario", "where its shard has", k3[0], path("torn.json"), k3[2], "--json", path("x.json"))
log = open(path("n3_k2.log")).read()
with open(path("cut.log"), "w") as f:
    f.write(log[: len(log) - 10])
refused("a log cut short", "cut short", path("n3_k1.log"), path("cut.log"), path("n3_k3.log"), "--log", path("x.log"))
# A log with a whole scenario, or one frame line, taken out (before, both merged with exit 0).
lines = log.splitlines(keepends=True)
headers = [i for i, line in enumerate(lines) if line.startswith("# ") and not line.rstrip("\n").endswith(" frames")
           and not line.startswith("# shard")]
footers = [i for i, line in enumerate(lines) if line.startswith("# ") and line.rstrip("\n").endswith(" frames")]
check(len(headers) >= 2 and len(footers) >= 2, "the log partial holds two scenarios or more")
with open(path("torn.log"), "w") as f:
    f.write("".join(lines[: headers[0]] + lines[footers[0] + 1:]))
refused("a log missing a scenario", "scenarios and 0 not run, where its shard has", path("n3_k1.log"), path("torn.log"),
        path("n3_k3.log"), "--log", path("x.log"))
frame = next(h + 1 for h, f in zip(headers, footers) if f > h + 1)
with open(path("torn_frame.log"), "w") as f:
    f.write("".join(lines[:frame] + lines[frame + 1:]))
refused("a log missing a frame", "frames where its scenario lists", path("n3_k1.log"), path("torn_frame.log"),
        path("n3_k3.log"), "--log", path("x.log"))
# The JSON lines hold no "# N frames": each record must be the next frame of its scenario or
# frame 0 of the next one.
records = open(path("n3_k2.jsonl")).read().splitlines(keepends=True)
frames_of = [json.loads(r) for r in records[:-1]]  # the last record is the mark
middle = next(i for i in range(1, len(frames_of) - 1)
              if frames_of[i - 1]["scenario"] == frames_of[i]["scenario"] == frames_of[i + 1]["scenario"])
with open(path("torn_frame.jsonl"), "w") as f:
    f.write("".join(records[:middle] + records[middle + 1:]))
refused("JSON lines missing a frame", "a frame is missing", path("n3_k1.jsonl"), path("torn_frame.jsonl"),
        path("n3_k3.jsonl"), "--log-json", path("x.jsonl"))
with open(path("torn_first.jsonl"), "w") as f:
    f.write("".join(records[1:]))
refused("JSON lines missing a scenario's first frame", "follows nothing: a frame is missing", path("n3_k1.jsonl"),
        path("torn_first.jsonl"), path("n3_k3.jsonl"), "--log-json", path("x.jsonl"))
check(not os.path.exists(path("x.json")) and not os.path.exists(path("x.log")),
      "a refused merge writes nothing and removes what an earlier one left")

# --shard's own errors.
for bad in ("0/3", "4/3", "3", "1/0", "a/b", "1/100001"):
    r = run("run", failing, "--shard", bad)
    check(r.returncode == 2 and "--shard expects K/N" in r.stderr, "--shard " + bad + " is refused", r)
r = run("sweep", sweep, *grid, "--shard", "1/2", "--csv", path("y.csv"))
check(r.returncode == 2 and "endatsim merge writes --csv" in r.stderr, "sweep --shard with --csv is refused", r)
r = run("sweep", sweep, *grid, "--shard", "1/2")
check(r.returncode == 2 and "--shard needs --json PATH" in r.stderr, "sweep --shard without --json is refused", r)

if failures:
    print("\n".join("FAIL: " + f for f in failures))
    sys.exit(1)
print("shards merged byte for byte; bad partials refused")
