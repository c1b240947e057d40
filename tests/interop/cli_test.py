#!/usr/bin/python3
"""The command line as CI and people use it: --help and --version on every subcommand, results
on stdout and errors on stderr, no colour or progress in pipes, JUnit XML that parses, --json
results that validate against schema/results.schema.json, transaction logs, validate, diagram.

usage: cli_test.py ENDATSIM SOURCE_DIR WORKDIR
"""
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import jsonschema

endatsim, source, work = sys.argv[1:]
os.makedirs(work, exist_ok=True)
bundled = os.path.join(source, "scenarios", "bundled")
clean = os.path.join(bundled, "endat21_1mhz_10m.json")
uncompensated = os.path.join(bundled, "endat22_2mhz_100m_uncompensated.json")
failures = []


def run(*args, env=None):
    return subprocess.run([endatsim, *args], capture_output=True, text=True, timeout=300, env=env)


def check(condition, what, r=None):
    if not condition:
        failures.append(what + ("" if r is None else "\n  exit %d\n  stdout: %s\n  stderr: %s" % (r.returncode, r.stdout[:2000], r.stderr[:2000])))


def path(name):
    return os.path.join(work, name)


# --help and --version everywhere, on stdout, exit 0.
for command in ("run", "sweep", "merge", "validate", "diagram"):
    r = run(command, "--help")
    check(r.returncode == 0 and r.stdout.startswith("usage: endatsim " + command) and r.stderr == "", command + " --help", r)
    r = run(command, "--version")
    check(r.returncode == 0 and r.stdout.startswith("endatsim ") and r.stderr == "", command + " --version", r)
r = run("--help")
check(r.returncode == 0 and all(c in r.stdout for c in ("run:", "sweep:", "validate:", "diagram:", "Exit status")), "--help", r)
# Each command's --quiet says what it leaves out there, not what it does for another command.
for command in ("run", "sweep", "merge", "validate", "diagram", "check", "checks", "parameters"):
    r = run(command, "--help")
    quiet = " ".join(r.stdout[r.stdout.find("-q [ --quiet ]"):].split("\n  -")[0].split())
    mentions = [other for other in ("scenarios", "sweep", "point", "caption", "capture") if other in quiet]
    expected = {"run": ["scenarios"], "sweep": ["point"], "merge": [], "validate": [], "diagram": ["caption"],
                "check": ["capture"], "checks": [], "parameters": []}[command]
    check(r.returncode == 0 and mentions == expected, command + " --help: --quiet says " + repr(quiet), r)

# Usage errors: stderr, exit 2, nothing on stdout.
r = run("run", clean, "--grid", "/x=1")
check(r.returncode == 2 and "--grid is not an option of run (it is one of sweep)" in r.stderr and r.stdout == "", "foreign option", r)
r = run("run", clean, "--verbose", "--quiet")
check(r.returncode == 2 and "exclude each other" in r.stderr and r.stdout == "", "--verbose --quiet", r)
r = run("run", clean, "--color", "sometimes")
check(r.returncode == 2 and "--color expects auto, always or never" in r.stderr, "--color value", r)
r = run("run", path("missing.json"))
check(r.returncode == 2 and "missing.json: cannot open the file" in r.stderr and r.stdout == "", "missing file", r)

# In a pipe: no colour, no progress; with --color always the verdicts are coloured.
r = run("run", clean, uncompensated)
check(r.returncode == 0 and "\033" not in r.stdout and r.stderr == "", "pipe: no colour, no progress", r)
r = run("run", clean, "--color", "always")
check(r.returncode == 0 and "\033[32mPASS\033[0m endat21_1mhz_10m" in r.stdout, "--color always", r)

# On a terminal (script(1) gives the command a pty): a progress line and coloured verdicts;
# NO_COLOR turns the colour off, not the progress.
def on_terminal(args, no_color=False, interrupt_after=None):
    env = dict(os.environ)
    env.pop("NO_COLOR", None)
    if no_color:
        env["NO_COLOR"] = "1"
    command = " ".join("'" + a + "'" for a in [endatsim, *args])
    if interrupt_after is not None:
        # Ctrl-C after that many seconds, once, as a user would press it: with --foreground the
        # signal goes to the command alone (without, timeout signals the command and then its
        # process group, and a second SIGINT ends a run before it can finish its outputs).
        command = "timeout --foreground --preserve-status -s INT %g %s" % (interrupt_after, command)
    return subprocess.run(["script", "-qec", command, "/dev/null"], capture_output=True, text=True, timeout=300, env=env)


r = on_terminal(["run", clean, uncompensated])
check(r.returncode == 0 and "[1/2] endat21_1mhz_10m" in r.stdout and "[2/2] endat22_2mhz_100m_uncompensated" in r.stdout
      and "\033[32mPASS\033[0m endat21_1mhz_10m" in r.stdout, "terminal: progress and colour", r)
r = on_terminal(["run", clean], no_color=True)
check(r.returncode == 0 and "[1/1] endat21_1mhz_10m" in r.stdout and "\033[32m" not in r.stdout, "terminal with NO_COLOR", r)
r = on_terminal(["run", clean, "--quiet"])
check(r.returncode == 0 and "[1/1]" not in r.stdout, "terminal with --quiet: no progress", r)
# A run longer than a second: simulated time, frames, wall time and the time left at most.
with open(os.path.join(source, "bench", "scenarios", "additional_data_loop_1s.json")) as f:
    loop = json.load(f)
loop.update({"name": "loop_20s", "max_time": "20 s", "expect": {}})
loop.pop("$schema")
loop["script"][-1]["count"] = 320000
with open(path("loop_20s.json"), "w") as f:
    json.dump(loop, f)
# Interrupted after 2.5 s of wall time, whatever the build's speed (every edge an event, the run
# takes several seconds in a release build, minutes under the sanitizers): the progress line was
# shown by then.
r = on_terminal(["run", path("loop_20s.json"), "--engine", "event", "--max-kernel-events", "1000000000",
                 "--max-records", "4000000", "--max-script-frames", "400000"], interrupt_after=2.5)
check(" of 20 s simulated, " in r.stdout and " frames, " in r.stdout and " s left" in r.stdout,
      "terminal: progress of a long run", r)
check(r.returncode == 130 and "incomplete: loop_20s: interrupted by SIGINT" in r.stdout,
      "terminal: a run stopped by Ctrl-C says so and exits 130", r)

# JUnit, JSON results, transaction logs.
failing = path("failing.json")
with open(failing, "w") as f:
    json.dump({"name": "failing", "line": {"cable_length_m": 1}, "master": {"f_c": "1 MHz"},
               "script": [{"op": "read_position"}], "expect": {"outcomes": {"ok": 2}}}, f)
r = run("run", clean, uncompensated, failing, "--quiet", "--junit", path("junit.xml"), "--json", path("results.json"),
        "--log", "-", "--log-json", path("log.jsonl"))
check(r.returncode == 1, "a failing scenario exits 1", r)
root = ET.parse(path("junit.xml")).getroot()
suite = root.find("testsuite")
cases = suite.findall("testcase")
check(root.tag == "testsuites" and suite.get("tests") == "3" and suite.get("failures") == "1" and len(cases) == 3,
      "JUnit: three test cases, one failure")
failed = [c for c in cases if c.find("failure") is not None]
check(len(failed) == 1 and failed[0].get("name") == "failing" and
      failed[0].find("failure").get("message") == "outcomes.ok: 1 (expected 2)", "JUnit: the failure names the expectation")
check([c.get("classname") for c in cases] == ["endatsim.bundled", "endatsim.bundled", "endatsim.cli"],
      "JUnit: the class is the scenario's folder")
results = json.load(open(path("results.json")))
schema = json.load(open(os.path.join(source, "schema", "results.schema.json")))
try:
    jsonschema.validate(results, schema, cls=jsonschema.Draft202012Validator)
except jsonschema.ValidationError as e:
    failures.append("results.json does not validate against schema/results.schema.json: %s at %s" % (e.message, list(e.absolute_path)))
# The safety and diagnosis sections validate too.
r7 = run("run", os.path.join(bundled, "diagnosis_service_read.json"),
         os.path.join(source, "scenarios", "safety", "01_error_messages.json"), "--quiet", "--json", path("results7.json"))
check(r7.returncode == 0, "the diagnosis and safety scenarios pass", r7)
results7 = json.load(open(path("results7.json")))
try:
    jsonschema.validate(results7, schema, cls=jsonschema.Draft202012Validator)
except jsonschema.ValidationError as e:
    failures.append("results7.json does not validate: %s at %s" % (e.message, list(e.absolute_path)))
check("diagnosis" in results7["scenarios"][0] and results7["scenarios"][0]["diagnosis"]["notes"] and
      results7["scenarios"][1]["safety"]["findings"], "--json: the diagnosis notes and the safety findings are there")
frames = sum(len(s["frames"]) for s in results["scenarios"])
log_lines = [l for l in r.stdout.splitlines() if not l.startswith("#") and "  sent: " in l]
check(len(log_lines) == frames, "--log -: one line per frame (%d lines, %d frames)" % (len(log_lines), frames), r)
records = [json.loads(l) for l in open(path("log.jsonl"))]
check(len(records) == frames and {"time_ps", "command", "sent", "received", "crc_ok", "additional", "violations"} <= set(records[0]),
      "--log-json: one record per frame with the documented keys")
check(any(rec["crc_ok"] is False and rec["violations"] for rec in records), "--log-json: the CRC errors with their violations")

# check --json: a verdict undecided at the capture's resolution validates as "undecided" against the
# schema's verdict, which still refuses anything else.
vcd = path("compensated.vcd")
r = run("run", os.path.join(bundled, "endat22_8mhz_100m_compensated.json"), "--quiet", "--vcd", vcd)
check(r.returncode == 0, "run --vcd", r)
r = run("check", vcd, "--clock", "encoder_clock", "--data", "encoder_data", "--cable", "100", "--resolution", "10ns",
        "--json", path("check.json"))
check(r.returncode == 1, "check of an undecided capture exits 1", r)
verdict = json.load(open(path("check.json")))["verdict"]
verdict_schema = {"$ref": "#/$defs/verdict", "$defs": schema["$defs"]}
try:
    jsonschema.validate(verdict, verdict_schema, cls=jsonschema.Draft202012Validator)
except jsonschema.ValidationError as e:
    failures.append("check's verdict does not validate against the schema's verdict: %s" % e.message)
check(verdict == {"spec_envelope": "undecided", "this_encoder": "undecided"}, "check --json: the verdict is undecided")
check(not jsonschema.Draft202012Validator(verdict_schema).is_valid({"spec_envelope": "maybe", "this_encoder": True}),
      "the schema's verdict refuses a value other than a boolean or \"undecided\"")

# validate: stdout for good files, stderr for bad ones.
bad = path("bad.json")
with open(bad, "w") as f:
    f.write('{"name": "bad", "line": {"cable_length_m": 1}, "master": {"f_c": "1 MHz"}, "script": [{"op": "jump"}]}')
r = run("validate", clean, bad)
check(r.returncode == 2 and r.stdout == "valid %s (endat21_1mhz_10m)\n" % clean and bad + ": at /script/0/op" in r.stderr,
      "validate", r)

# diagram: an SVG that parses; bad requests are usage errors.
r = run("diagram", uncompensated, "--svg", path("frame.svg"))
check(r.returncode == 0 and "t_D on the wires 1.06 us" in r.stdout, "diagram", r)
svg = ET.parse(path("frame.svg")).getroot()
check(svg.tag == "{http://www.w3.org/2000/svg}svg", "diagram: an SVG document")
r = run("diagram", uncompensated, "--svg", path("frame2.svg"), "--frame", "99")
check(r.returncode == 2 and "frame 99: the run has 4 frames" in r.stderr, "diagram --frame 99", r)
r = run("diagram", uncompensated)
check(r.returncode == 2 and "--svg PATH" in r.stderr, "diagram without --svg", r)
r = run("diagram", uncompensated, "--svg", path("w.svg"), "--from", "10 us", "--to", "5 us")
check(r.returncode == 2 and "--to must be later than --from" in r.stderr, "diagram window", r)

# sweep --verbose lists the points.
r = run("sweep", clean, "--grid", "/line/cable_length_m=1,2", "--verbose", "--jobs", "1")
check(r.returncode == 0 and "clean /line/cable_length_m=1" in r.stdout and "2 points" in r.stdout, "sweep --verbose", r)

# "-" is standard output for every output, which then holds that output alone (the summary goes
# to stderr); two outputs cannot share it.
with open(path("stdout_ref.vcd"), "w"):
    pass
r = run("run", clean, "--vcd", path("stdout_ref.vcd"), "--quiet")
with open(path("stdout_ref.vcd")) as f:
    reference_vcd = f.read()
r = run("run", clean, "--vcd", "-")
check(r.returncode == 0 and r.stdout == reference_vcd and "PASS endat21_1mhz_10m" in r.stderr, "run --vcd -", r)
check(not os.path.exists("-") and not os.path.exists(path("-")), "run --vcd - makes no file named -")
r = run("run", clean, "--json", "-")
check(r.returncode == 0 and json.loads(r.stdout)["passed"] is True and "PASS" in r.stderr, "run --json -", r)
r = run("run", clean, "--junit", "-")
check(r.returncode == 0 and ET.fromstring(r.stdout).get("tests") == "1" and "PASS" in r.stderr, "run --junit -", r)
r = run("run", clean, "--log-json", "-")
check(r.returncode == 0 and all(json.loads(l)["scenario"] for l in r.stdout.splitlines()), "run --log-json -", r)
r = run("sweep", clean, "--grid", "/line/cable_length_m=1,2", "--csv", "-", "--jobs", "1")
check(r.returncode == 0 and r.stdout.startswith("/line/cable_length_m,clean,") and "2 points" in r.stderr, "sweep --csv -", r)
r = run("sweep", clean, "--grid", "/line/cable_length_m=1,2", "--json", "-", "--jobs", "1")
check(r.returncode == 0 and len(json.loads(r.stdout)["points"]) == 2, "sweep --json -", r)
r = run("diagram", clean, "--svg", "-")
check(r.returncode == 0 and r.stdout.startswith("<svg") and r.stdout.rstrip().endswith("</svg>") and r.stderr != "", "diagram --svg -", r)
r = run("run", clean, "--vcd", "-", "--json", "-")
check(r.returncode == 2 and "--vcd - and --json -: only one output can go to standard output" in r.stderr and r.stdout == "",
      "two outputs to stdout", r)
r = run("run", clean, uncompensated, "--vcd", "-")
check(r.returncode == 2 and "--vcd -: several files cannot go to standard output" in r.stderr and r.stdout == "",
      "--vcd - with several scenarios", r)
r = run("run", clean, "--vcd", "-", "--gtkw")
check(r.returncode == 2 and "--gtkw" in r.stderr and r.stdout == "", "--vcd - --gtkw", r)

# --vcd DIR is a folder whenever it exists or ends in "/", also for one scenario.
os.makedirs(path("vcd_folder"), exist_ok=True)
r = run("run", clean, "--vcd", path("vcd_folder"), "--quiet")
check(r.returncode == 0 and os.path.isfile(path("vcd_folder/endat21_1mhz_10m.vcd")), "--vcd existing folder", r)
r = run("run", clean, "--vcd", path("new_vcd_folder") + "/", "--quiet")
check(r.returncode == 0 and os.path.isfile(path("new_vcd_folder/endat21_1mhz_10m.vcd")), "--vcd folder/", r)

# A folder as input stands for every scenario under it, in path order.
r = run("validate", os.path.join(source, "scenarios"))
lines = r.stdout.splitlines()
files = [l.split(" ")[1] for l in lines]
check(r.returncode == 0 and len(lines) >= 80 and files == sorted(files) and
      any("/field/" in f for f in files) and any("/sweeps/" in f for f in files), "validate FOLDER", r)
r = run("run", bundled, "--quiet", "--json", path("folder.json"))
with open(path("folder.json")) as f:
    ran = json.load(f)["scenarios"]
check(r.returncode == 0 and len(ran) == len([n for n in os.listdir(bundled) if n.endswith(".json")]), "run FOLDER", r)
os.makedirs(path("empty_folder"), exist_ok=True)
r = run("run", path("empty_folder"))
check(r.returncode == 2 and "a folder with no scenario (*.json) in it" in r.stderr, "run EMPTY_FOLDER", r)

# Did you mean: subcommands and options.
r = run("rnu", clean)
check(r.returncode == 2 and 'unknown command "rnu"; did you mean "run"?' in r.stderr, "did you mean: command", r)
r = run("run", clean, "--jsn", path("x.json"))
check(r.returncode == 2 and "did you mean --json?" in r.stderr, "did you mean: option", r)
# --engine: the fast path by default, every edge with event, the count of frames played with fast.
r = run("run", clean, "--engine", "warp")
check(r.returncode == 2 and "--engine expects auto, event or fast, got 'warp'" in r.stderr, "run --engine: an unknown name", r)
r = run("sweep", clean, "--grid", "/line/cable_length_m=1,2", "--engine", "", "--jobs", "1")
check(r.returncode == 2 and "endatsim sweep: --engine expects auto, event or fast, got ''" in r.stderr, "sweep --engine: no name", r)
r = run("run", clean, "--engine", "fast", "--quiet")
check(r.returncode == 0 and "endat21_1mhz_10m: " in r.stderr and " frames played from recordings" in r.stderr,
      "run --engine fast says how many frames it played", r)
event = run("run", clean, "--engine", "event", "--log", "-")
auto = run("run", clean, "--log", "-")
check(event.returncode == 0 and event.stdout == auto.stdout and event.stdout != "", "run --engine event: the same log as auto", event)
r = run("sweep", clean, "--gird", "/x=1")
check(r.returncode == 2 and "did you mean --grid?" in r.stderr, "did you mean: sweep option", r)
r = run("run", clean, "--frobnicate")
check(r.returncode == 2 and "did you mean" not in r.stderr, "no guess far off", r)

# Bad input found after the output paths were checked: an earlier run's outputs go, so that none
# looks like this run's; an output that is an input is refused before anything is removed.
for name in ("stale.xml", "stale.csv", "stale.svg"):
    with open(path(name), "w") as f:
        f.write("from an earlier run\n")
bad_scenario = path("bad_late.json")
with open(bad_scenario, "w") as f:
    json.dump({"name": "bad", "master": {"f_c": "1 MHz"}, "script": [{"op": "read_position"}]}, f)
r = run("run", clean, bad_scenario, "--junit", path("stale.xml"))
check(r.returncode == 2 and not os.path.exists(path("stale.xml")) and "removed the earlier" in r.stderr,
      "run: bad input removes an earlier --junit file", r)
r = run("sweep", clean, "--grid", "/line/cable_length_m=1,-5", "--csv", path("stale.csv"), "--jobs", "1")
check(r.returncode == 2 and not os.path.exists(path("stale.csv")), "sweep: a bad grid point removes an earlier --csv file", r)
r = run("diagram", clean, "--svg", path("stale.svg"), "--frame", "99")
check(r.returncode == 2 and not os.path.exists(path("stale.svg")), "diagram: a bad frame removes an earlier --svg file", r)
r = run("run", bad_scenario, "--json", bad_scenario)
check(r.returncode == 2 and os.path.exists(bad_scenario), "an output that is an input is refused, not removed", r)

# A VCD with the --gtkw text trace is still a capture for check: the text variable is read past.
r = run("run", clean, "--vcd", path("with_text.vcd"), "--gtkw", "--quiet")
r = run("check", path("with_text.vcd"), "--clock", "encoder_clock", "--data", "encoder_data", "--quiet")
check(r.returncode == 0, "check reads a VCD with a text trace", r)

# --junit-cases expectation: a test case per group of each scenario's expectations, its class the
# folder and the scenario, so that a CI server lists which expectation broke.
r = run("run", clean, failing, "--quiet", "--junit", path("cases.xml"), "--junit-cases", "expectation")
cases = ET.parse(path("cases.xml")).getroot().find("testsuite").findall("testcase")
broken = [(c.get("classname"), c.get("name")) for c in cases if c.find("failure") is not None]
check(r.returncode == 1 and broken == [("endatsim.cli.failing", "outcomes")] and
      ("endatsim.bundled.endat21_1mhz_10m", "outcomes") in [(c.get("classname"), c.get("name")) for c in cases],
      "--junit-cases expectation", r)
r = run("run", clean, "--junit", path("cases.xml"), "--junit-cases", "rows")
check(r.returncode == 2 and "--junit-cases expects scenario or expectation" in r.stderr, "--junit-cases value", r)

if failures:
    print("FAIL:\n" + "\n".join(failures), file=sys.stderr)
    sys.exit(1)
print("command line: all checks hold")
