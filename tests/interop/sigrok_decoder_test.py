#!/usr/bin/python3
"""The EnDat decoder for sigrok (tools/sigrok/endat) against endatsim on every bundled scenario.

Each scenario runs to a VCD; `endatsim check` decodes the encoder's connector from it (--log,
--json) and sigrok-cli runs the decoder on the same VCD (read as a logic analyzer would, at a
sample period of about a tenth of the fastest CLOCK phase). The decoder must find the same frames
as the check's transaction log, line for line (command, payload, start bit, F1/F2, position, test
value or echo, CRC verdict, additional data with status and CRC, supplement, learnt width), at the
same FE1 within the sample period; its positions must be the master's where the master read
its frame without error; and the timing rows it judges must break where the check's do: every
row the check fails is failed or undecided by the decoder, and the decoder fails no row the check
passes. Variants of some bundled scenarios break the rows those keep (t_ST, the on-off ratio,
t_HI, t_LO, t_z, t_OE, the wait after an error handling, f_c with the short t_m): both must break
them. A wrong position width must break the comparison (the test can fail).

usage: sigrok_decoder_test.py ENDATSIM SIGROK_DECODERS_DIR SCENARIO_DIR WORKDIR
"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import time

# The rows the decoder judges from CLOCK, DATA and the encoder's driver enable.
JUDGED = {"f_c", "t_hi", "t_lo", "on_off_ratio", "t_st", "t_cal", "t_ac", "t_m_t_r", "t_m_short_f_c",
          "error_recovery", "t_b", "clock_count", "t_z", "t_oe", "busy_access"}
NICE_PERIODS_PS = [1000, 2000, 5000, 10000, 20000, 50000]


def fail(message):
    print("FAIL: " + message, file=sys.stderr)
    sys.exit(1)


def run(cmd, ok=(0,), env=None):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env)
    if r.returncode not in ok:
        fail("%s exited %d\nstdout:\n%s\nstderr:\n%s" % (" ".join(cmd), r.returncode, r.stdout[-3000:], r.stderr[-3000:]))
    return r


def vcd_vars(path):
    """[(scope, name, id)] in declaration order, and the shortest interval between changes of each id."""
    variables, scopes = [], []
    shortest, last, value = {}, {}, {}
    now = 0
    with open(path) as f:
        header = True
        for line in f:
            if header:
                tokens = line.split()
                if not tokens:
                    continue
                if tokens[0] == "$scope":
                    scopes.append(tokens[2])
                elif tokens[0] == "$upscope":
                    scopes.pop()
                elif tokens[0] == "$var":
                    variables.append((".".join(scopes), tokens[4], tokens[3]))
                elif tokens[0] == "$enddefinitions":
                    header = False
                continue
            for tok in line.split():
                if tok[0] == "#":
                    now = int(tok[1:])
                elif tok[0] in "01" and len(tok) > 1:
                    ident = tok[1:]
                    if value.get(ident) == tok[0]:
                        continue
                    value[ident] = tok[0]
                    if ident in last and now > last[ident]:
                        shortest[ident] = min(shortest.get(ident, now - last[ident]), now - last[ident])
                    last[ident] = now
    return variables, shortest


def sigrok_channel(variables, what):
    """sigrok drops the scopes: the name under which sigrok-cli finds the encoder's `what`; with
    names repeated across scopes sigrok-cli takes the first, which must then be the encoder's."""
    mine = [v for v in variables if (v[0].split(".")[-1] == "encoder" or v[1].startswith("encoder"))
            and re.sub(r"^encoder_?", "", v[1]) == what]
    if len(mine) != 1:
        fail("the VCD declares no single encoder %s: %s" % (what, variables))
    scope, name, ident = mine[0]
    first = next(v for v in variables if v[1] == name)
    if first != mine[0]:
        fail("sigrok-cli would take %s.%s for '%s', not the encoder's %s.%s" % (first[0], first[1], name, scope, name))
    return name, ident


def parse_time(text):
    number, unit = text.split()
    scale = {"ps": 1, "ns": 10**3, "us": 10**6, "ms": 10**9, "s": 10**12}[unit]
    return round(float(number) * scale)


def decode_with_sigrok(vcd, decoders, downsample, options, channels):
    env = dict(os.environ, SIGROKDECODE_DIR=decoders)
    pd = "endat:" + ":".join("%s=%s" % kv for kv in list(channels.items()) + list(options.items()))
    r = run(["sigrok-cli", "-i", vcd, "-I", "vcd:downsample=%d" % downsample, "-P", pd, "-A",
             "endat=frames:violations", "--protocol-decoder-samplenum"], env=env)
    if "Traceback" in r.stderr or "srd:" in r.stderr:
        fail("the decoder failed on %s:\n%s" % (vcd, r.stderr[-3000:]))
    frames, findings = [], []
    for line in r.stdout.splitlines():
        m = re.match(r"^(\d+)-(\d+) endat-1: (.*)$", line)
        if not m:
            fail("unexpected sigrok-cli output line: " + line)
        ss, text = int(m.group(1)), m.group(3)
        frame = re.match(r"^#(\d+) (.*)$", text)
        if frame:
            frames.append((int(frame.group(1)), ss * downsample, frame.group(2)))
        else:
            kind = "undecided" if text.startswith("undecided: ") else "warning" if text.startswith("warning: ") else "error"
            check = text.split(": ", 1)[1].split()[0] if kind != "error" else text.split()[0]
            findings.append((kind, check, ss * downsample, text))
    return frames, findings


def compare_frames(name, log_frames, json_frames, decoded, period):
    """Line for line against `endatsim check --log`; FE1 within the sample period."""
    problems = []
    if len(decoded) != len(log_frames):
        problems.append("%d frames decoded, the check's log has %d" % (len(decoded), len(log_frames)))
    for (index, fe1, text), (log_index, log_time, log_text), j in zip(decoded, log_frames, json_frames):
        if index != log_index or text != log_text:
            problems.append("frame #%d: decoder '%s'\n    check log #%d '%s'" % (index, text, log_index, log_text))
        elif abs(fe1 - j["fe1_ps"]) > 2 * period:
            problems.append("frame #%d: FE1 at %d ps, the check's at %d ps" % (index, fe1, j["fe1_ps"]))
        if len(problems) > 5:
            break
    return problems


def compare_with_master(master_frames, json_frames, decoded, cable_slack_ps):
    """Where the master read a frame without error, the wires show its command and position:
    the wire frame whose FE1 follows the master's start within the clock's path to the encoder."""
    problems, matched = [], 0
    by_index = {j["index"]: j for j in json_frames}
    starts = [(fe1, index) for index, fe1, _ in decoded]
    for f in master_frames:
        if f["outcome"] != "ok" or f.get("word", 0) != 0 or "position" not in f:
            continue
        near = [index for fe1, index in starts if 0 <= fe1 - f["start_ps"] <= cable_slack_ps]
        if len(near) != 1:
            continue  # frames the encoder saw as one (closer than its t_m), or none
        j = by_index[near[0]]
        matched += 1
        if not j.get("crc_ok"):
            continue  # disturbed on the wires at the encoder, read as the master's end shows it
        if j.get("command") != f["command"] or (j.get("position") != f["position"] and f["command"] != "encoder_send_test_values"):
            problems.append("master frame #%d (%s, position %s) is wire frame #%d (%s, position %s)" % (
                f["index"], f["command"], f.get("position"), j["index"], j.get("command"), j.get("position")))
    return problems, matched


def compare_rows(check_json, findings):
    """Rows the decoder judges: each row the check breaks is failed or undecided by the decoder, and
    the decoder fails no row that the check passes."""
    check_failed = {v["check"] for v in check_json["violations"] if v["severity"] == "error"} & JUDGED
    check_flagged = {v["check"] for v in check_json["violations"]} & JUDGED
    decoder_failed = {c for kind, c, _, _ in findings if kind == "error"}
    decoder_flagged = {c for _, c, _, _ in findings}
    problems = []
    for c in sorted(check_failed - decoder_flagged):
        problems.append("the check breaks %s, the decoder does not" % c)
    for c in sorted(decoder_failed - check_flagged):
        text = next(t for kind, ch, _, t in findings if kind == "error" and ch == c)
        problems.append("the decoder breaks %s, the check does not: %s" % (c, text))
    return problems


# Variants of bundled scenarios that break the rows the scenarios themselves keep, so that each row
# the decoder judges is seen broken at least once, and that decode frames no bundled scenario has:
# (base scenario, edits, rows the check and the decoder must both break).
MUTANTS = [
    ("endat22_8mhz_100m_compensated", {"master.t_st": "1.5 us"}, {"t_st"}),
    ("endat22_8mhz_100m_compensated", {"master.duty_cycle": 0.3}, {"on_off_ratio"}),
    ("endat22_8mhz_100m_compensated", {"encoder.output_delay": "200 ns"}, {"t_z", "t_oe"}),
    ("endat21_1mhz_10m", {"master.duty_cycle": 0.15}, {"t_hi"}),
    ("endat21_1mhz_10m", {"master.duty_cycle": 0.85}, {"t_lo"}),
    ("type1_corrupted_mode_command", {"master.error_wait": "25 us"}, {"error_recovery"}),
    ("short_recovery_time_word3", {"master.f_c": "500 kHz"}, {"t_m_short_f_c"}),
    # No pulse after the last bit: both read it half a period after the last rising edge.
    ("endat21_1mhz_10m", {"master.extra_clock_after_last_bit": False}, set()),
    ("endat22_8mhz_100m_compensated", {"master.extra_clock_after_last_bit": False}, set()),
]


def mutant(base, edits, path):
    scenario = json.load(open(base))
    scenario.pop("expect", None)
    scenario.pop("$schema", None)
    for key, value in edits.items():
        node = scenario
        *parents, leaf = key.split(".")
        for k in parents:
            node = node.setdefault(k, {})
        node[leaf] = value
    scenario["name"] = os.path.splitext(os.path.basename(path))[0]
    json.dump(scenario, open(path, "w"), indent=1)


class Suite:
    def __init__(self, endatsim, decoders, work):
        self.endatsim, self.decoders, self.work = endatsim, decoders, work
        self.frames = self.matched = 0
        self.failures = []
        self.sensitivity_checked = False

    def scenario(self, scenario, must_break=()):
        name = os.path.splitext(os.path.basename(scenario))[0]
        vcd = os.path.join(self.work, name + ".vcd")
        results, log, check_json = (os.path.join(self.work, name + s) for s in (".results.json", ".log", ".check.json"))
        run([self.endatsim, "run", scenario, "--vcd", vcd, "--json", results, "--quiet"], ok=(0, 1))
        variables, shortest = vcd_vars(vcd)
        clock, clock_id = sigrok_channel(variables, "clock")
        data, _ = sigrok_channel(variables, "data")
        enable, _ = sigrok_channel(variables, "data_driver_enable")
        run([self.endatsim, "check", vcd, "--clock", "encoder_clock", "--data", "encoder_data", "--data-enable",
             "encoder_data_driver_enable", "--encoder", scenario, "--log", log, "--json", check_json, "--quiet"], ok=(0, 1))
        checked = json.load(open(check_json))
        log_frames = []
        for line in open(log):
            m = re.match(r"^#(\d+) (\S+ \S+) (.*)$", line.rstrip("\n"))
            if not m:
                fail("%s: unexpected check log line: %s" % (name, line))
            log_frames.append((int(m.group(1)), parse_time(m.group(2)), m.group(3)))
        if not log_frames:
            fail("%s: the check decoded no frame" % name)
        # About ten samples per shortest CLOCK phase, as a logic analyzer would be set.
        period = max([p for p in NICE_PERIODS_PS if p * 10 <= shortest[clock_id]] or [NICE_PERIODS_PS[0]])
        declared = checked["declared"]
        options = {"position_bits": declared["position_bits"], "clock_to_data_ns": declared["clock_to_data_ps"] / 1000.0,
                   "t_m_us": declared["t_m_ps"] / 1e6, "t_m_short_us": (declared["t_m_short_ps"] or 0) / 1e6,
                   "short_t_m": "yes" if declared["short_t_m_selected"] else "no",
                   "t_r_ns": declared["t_r_ps"] / 1000.0, "cable_m": float(checked["cable_m"] or 0)}
        channels = {"clk": clock, "data": data, "de": enable}
        decoded, findings = decode_with_sigrok(vcd, self.decoders, period, options, channels)
        problems = compare_frames(name, log_frames, checked["frames"], decoded, period)
        master_frames = json.load(open(results))["scenarios"][0]["frames"]
        more, matched = compare_with_master(master_frames, checked["frames"], decoded, 5 * 10**6)
        problems += more
        if any(f["outcome"] == "ok" and "position" in f for f in master_frames) and matched == 0:
            problems.append("no frame of the master's matched a wire frame")
        problems += compare_rows(checked, findings)
        for row in sorted(must_break):
            if not any(v["check"] == row and v["severity"] == "error" for v in checked["violations"]):
                problems.append("the check does not break %s: the variant no longer shows the row" % row)
            if not any(kind == "error" and c == row for kind, c, _, _ in findings):
                problems.append("the decoder does not break %s" % row)
        self.frames += len(decoded)
        self.matched += matched
        print("%s: %d frames at %d ps samples, %d matched with the master's, %d timing findings" % (
            name, len(decoded), period, matched, len(findings)))
        if problems:
            self.failures.append("%s:\n  %s" % (name, "\n  ".join(problems)))
        # The comparison notices a decoder that reads the position with the wrong width.
        if not self.sensitivity_checked and not problems and declared["position_bits"] > 2 and \
                any(", position " in text for _, _, text in decoded):
            wrong = dict(options, position_bits=declared["position_bits"] - 1)
            off, _ = decode_with_sigrok(vcd, self.decoders, period, wrong, channels)
            if not compare_frames(name, log_frames, checked["frames"], off, period):
                self.failures.append("%s: a decoder reading %d position bits still matched the check's log" %
                                     (name, wrong["position_bits"]))
            # Without the optional driver enable the frames are the same.
            without, _ = decode_with_sigrok(vcd, self.decoders, period, options, {"clk": clock, "data": data})
            self.failures += ["%s without DE: %s" % (name, p) for p in
                              compare_frames(name, log_frames, checked["frames"], without, period)]
            self.sensitivity_checked = True
        for path in (vcd, results, log, check_json):
            os.remove(path)


def main():
    if len(sys.argv) != 5:
        fail(__doc__)
    endatsim, decoders, scenario_dir, work = sys.argv[1:]
    if shutil.which("sigrok-cli") is None:
        fail("sigrok-cli is not installed (tools/quickstart installs it)")
    os.makedirs(work, exist_ok=True)
    scenarios = sorted(glob.glob(os.path.join(scenario_dir, "*.json")))
    if not scenarios:
        fail("no scenarios in " + scenario_dir)
    started = time.time()
    suite = Suite(endatsim, decoders, work)
    for scenario in scenarios:
        suite.scenario(scenario)
    variants = 0
    for i, (base, edits, rows) in enumerate(MUTANTS):
        path = os.path.join(scenario_dir, base + ".json")
        if path not in scenarios:
            continue
        variant = os.path.join(work, "%s_breaks_%s.json" % (base, "_".join(sorted(rows))))
        mutant(path, edits, variant)
        suite.scenario(variant, rows)
        os.remove(variant)
        variants += 1
    if not suite.sensitivity_checked:
        suite.failures.append("no scenario served to show that the comparison can fail")
    if suite.failures:
        fail("\n".join(suite.failures))
    print("sigrok decoder: %d scenarios and %d variants, %d frames as endatsim check decodes them, %d of them as the "
          "master read them; %.1f s" % (len(scenarios), variants, suite.frames, suite.matched, time.time() - started))


main()
