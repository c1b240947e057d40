#!/usr/bin/python3
"""Loads a waveform endatsim wrote into the viewers an FPGA engineer uses and checks that each
sees the same edges as the simulator: sigrok-cli (the PulseView back end), GTKWave's own VCD
reader through vcd2fst/fst2vcd, and GTKWave itself under xvfb with a Tcl script. The number of
rising CLOCK edges at both ends must equal the clock pulses the master reports in --json.

usage: viewers_test.py ENDATSIM VCDLINT SCENARIO WORKDIR
"""
import json
import os
import shutil
import subprocess
import sys


def fail(message):
    print("FAIL: " + message, file=sys.stderr)
    sys.exit(1)


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300, **kw)
    if r.returncode != 0:
        fail("%s exited %d\nstdout:\n%s\nstderr:\n%s" % (" ".join(cmd), r.returncode, r.stdout, r.stderr))
    return r


def count_edges(path):
    """Independent of endatsim's VCD reader: (name, rising, falling) per $var in declaration
    order; several values at one timestamp count as the last one."""
    tokens = open(path).read().split()
    names, ids, i = [], {}, 0
    while i < len(tokens) and tokens[i] != "$enddefinitions":
        if tokens[i] == "$var":
            ids.setdefault(tokens[i + 3], len(names))
            names.append(tokens[i + 4])
            i += 5
        else:
            i += 1
    history = [[] for _ in names]  # (time, value)
    now = 0
    for tok in tokens[i:]:
        if tok.startswith("#"):
            now = int(tok[1:])
        elif tok[0] in "01xzXZ" and tok[1:] in ids:
            h = history[ids[tok[1:]]]
            if h and h[-1][0] == now:
                h.pop()
            if not h or h[-1][1] != tok[0]:
                h.append((now, tok[0]))
    result = []
    for name, h in zip(names, history):
        values = [v for _, v in h]
        rising = sum(1 for a, b in zip(values, values[1:]) if (a, b) == ("0", "1"))
        falling = sum(1 for a, b in zip(values, values[1:]) if (a, b) == ("1", "0"))
        result.append((name, rising, falling))
    return result


def main():
    if len(sys.argv) != 5:
        fail(__doc__)
    endatsim, vcdlint, scenario, work = sys.argv[1:]
    for tool in ("sigrok-cli", "vcd2fst", "fst2vcd", "gtkwave", "xvfb-run"):
        if shutil.which(tool) is None:
            fail(tool + " is not installed (tools/quickstart installs it: sigrok-cli, gtkwave, xvfb)")
    os.makedirs(work, exist_ok=True)
    vcd, results = os.path.join(work, "wave.vcd"), os.path.join(work, "results.json")
    run([endatsim, "run", scenario, "--vcd", vcd, "--json", results, "--quiet"])
    frames = json.load(open(results))["scenarios"][0]["frames"]
    # Continuous-clock words report the pulses counted since FE1: a frame's last word has them all.
    per_frame = {}
    for f in frames:
        per_frame[f["start_ps"]] = max(per_frame.get(f["start_ps"], 0), f["clocks"])
    pulses = sum(per_frame.values())
    if pulses == 0:
        fail("the scenario produced no clock pulses")

    # endatsim's own reading (and the lint, with sigrok's restrictions).
    lint = run([vcdlint, "--sigrok", "--edges", "--quiet", vcd])
    ours = [(n, int(r), int(f)) for n, r, f in (line.split() for line in lint.stdout.splitlines())]
    by_name = {n: (r, f) for n, r, f in ours}
    for end in ("master", "encoder"):
        if by_name["endat." + end + "_clock"][0] != pulses:
            fail("%s_clock has %d rising edges, the master reports %d pulses" % (end, by_name["endat." + end + "_clock"][0], pulses))
    print("endatsim: %d clock pulses in %d frames; %d signals" % (pulses, len(per_frame), len(ours)))

    # sigrok-cli: imports the VCD as a logic capture (1 ns samples) and exports it again.
    sigrok_vcd = os.path.join(work, "sigrok.vcd")
    run(["sigrok-cli", "-i", vcd, "-I", "vcd:downsample=1000", "-O", "vcd", "-o", sigrok_vcd])
    seen = count_edges(sigrok_vcd)
    if len(seen) != len(ours):
        fail("sigrok-cli read %d channels, the file has %d" % (len(seen), len(ours)))
    for (name, r, f), (sname, sr, sf) in zip(ours, seen):  # sigrok drops the scopes, keeps the order
        if not name.endswith("." + sname) or (r, f) != (sr, sf):
            fail("sigrok-cli sees %s with %d/%d edges, endatsim wrote %s with %d/%d" % (sname, sr, sf, name, r, f))
    # Without the scopes every name still says which end it is.
    if len({n for n, _, _ in seen}) != len(seen):
        fail("sigrok-cli shows channels of the same name: %s" % [n for n, _, _ in seen])
    print("sigrok-cli: same edges on all %d channels, each name unique" % len(seen))

    # GTKWave's VCD reader, through its converters.
    fst, back = os.path.join(work, "wave.fst"), os.path.join(work, "fst2vcd.vcd")
    run(["vcd2fst", vcd, fst])
    with open(back, "w") as out:
        subprocess.run(["fst2vcd", fst], stdout=out, check=True, timeout=300)
    # fst2vcd keeps the declaration order.
    edges_back = [(n, r, f) for n, r, f in count_edges(back)]
    if [(r, f) for _, r, f in edges_back] != [(r, f) for _, r, f in ours]:
        fail("vcd2fst/fst2vcd edges %s differ from endatsim's %s" % (edges_back, ours))
    print("vcd2fst/fst2vcd: same edges on all %d signals" % len(edges_back))

    # GTKWave itself, headless.
    tcl = os.path.join(os.path.dirname(os.path.abspath(__file__)), "gtkwave_edges.tcl")
    r = run(["xvfb-run", "-a", "gtkwave", "-S", tcl, vcd], cwd=work)
    gtk = {}
    for line in r.stdout.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[0] == "edges":
            gtk[parts[1]] = (int(parts[2]), int(parts[3]))
    if set(gtk) != set(by_name):
        fail("GTKWave loaded signals %s, the file has %s" % (sorted(gtk), sorted(by_name)))
    for name, edges in by_name.items():
        if gtk[name] != edges:
            fail("GTKWave sees %s with %s edges, endatsim wrote %s" % (name, gtk[name], edges))
    print("gtkwave: same edges on all %d signals" % len(gtk))

    # The save file written by --gtkw: GTKWave opens with every signal shown, master first, on
    # the first frame that is not a delay measurement (the view from a tenth of its length before
    # FE1, the marker at FE1), with named markers at the violations.
    shown = os.path.join(work, "shown.tcl")
    with open(shown, "w") as out:
        out.write('puts "displayed [gtkwave::getDisplayedSignals]"\n'
                  'puts "start [gtkwave::getWindowStartTime]"\nputs "end [gtkwave::getWindowEndTime]"\n'
                  'puts "marker [gtkwave::getMarker]"\n'
                  'puts "named [gtkwave::getNamedMarker A]"\n'
                  'puts "decoded [gtkwave::getTraceValueAtMarkerFromName endat.decoded]"\ngtkwave::/File/Quit\n')
    # --gtkw adds the text trace endat.decoded (GTKWave's string variables; sigrok skips them).
    gtk_vcd = os.path.join(work, "gtk.vcd")
    run([endatsim, "run", scenario, "--vcd", gtk_vcd, "--gtkw", "--quiet"])
    lint = run([vcdlint, gtk_vcd])
    r = run(["xvfb-run", "-a", "gtkwave", "-S", shown, gtk_vcd, os.path.join(work, "gtk.gtkw")], cwd=work)
    said = {line.split()[0]: line.split()[1:] for line in r.stdout.splitlines()
            if line.split() and line.split()[0] in ("displayed", "start", "end", "marker", "named", "decoded")}
    expected = ["endat.master_clock", "endat.master_data", "endat.master_data_driver_enable", "endat.master_sample",
                "endat.master_frame", "endat.decoded", "endat.encoder_clock", "endat.encoder_data",
                "endat.encoder_data_driver_enable"]
    if said.get("displayed") != expected:
        fail("GTKWave shows %s with the save file, expected %s" % (said.get("displayed"), expected))
    first = next((f for f in frames if not f["measurement"]), frames[0])
    length = first["end_ps"] - first["start_ps"]
    # GTKWave starts the window on a whole pixel: up to one before the time asked for.
    asked = max(0, first["start_ps"] - length // 10)
    start, end = int(said.get("start", ["-1"])[0]), int(said.get("end", ["0"])[0])
    if not asked - (end - start) // 400 <= start <= asked or said.get("marker") != [str(first["start_ps"])]:
        fail("GTKWave opens at %s with the marker at %s; the first frame starts at %d ps"
             % (said.get("start"), said.get("marker"), first["start_ps"]))
    # The whole frame is in the window, and fills at least half of it (the zoom once showed 50 ns).
    if end < first["end_ps"] or end - start > 2 * (length + length // 5):
        fail("GTKWave's window ends at %s ps; the first frame runs from %d to %d ps"
             % (said.get("end"), first["start_ps"], first["end_ps"]))
    # At FE1 the text trace names the frame and its mode command.
    if said.get("decoded") != ["#%d_%s" % (first["index"], first["command"])]:
        fail("GTKWave's text trace at the first frame's FE1 says %s" % said.get("decoded"))
    violations = sorted(v["time_ps"] for v in json.load(open(results))["scenarios"][0]["violations"])
    if said.get("named") != [str(violations[0] if violations else -1)]:
        fail("GTKWave's marker A is at %s; the first violation at %s" % (said.get("named"), violations[:1]))
    print("gtkwave: the .gtkw save file shows all %d signals from %s to %s ps, marker A at %s, %s"
          % (len(expected), said["start"][0], said["end"][0], said["named"][0], said["decoded"][0]))

main()
