#!/usr/bin/python3
"""Runs every bundled scenario with --vcd and lints each waveform with sigrok's restrictions,
so that a change to the VCD writer that viewers would silently misread fails here.

usage: lint_all_vcd.py ENDATSIM VCDLINT BUNDLED_DIR WORKDIR
"""
import glob
import os
import subprocess
import sys

endatsim, vcdlint, bundled, work = sys.argv[1:]
os.makedirs(work, exist_ok=True)
scenarios = sorted(glob.glob(os.path.join(bundled, "*.json")))
if not scenarios:
    sys.exit("FAIL: no scenarios in " + bundled)
r = subprocess.run([endatsim, "run", *scenarios, "--vcd", work, "--quiet"], capture_output=True, text=True)
if r.returncode not in (0, 1):  # 1: an expectation failed, which the scenario tests report; the waveforms exist
    sys.exit("FAIL: endatsim run exited %d: %s" % (r.returncode, r.stderr))
waves = sorted(glob.glob(os.path.join(work, "*.vcd")))
if len(waves) != len(scenarios):
    sys.exit("FAIL: %d scenarios wrote %d waveforms" % (len(scenarios), len(waves)))
r = subprocess.run([vcdlint, "--sigrok", "--quiet", *waves], capture_output=True, text=True)
sys.stderr.write(r.stderr)
if r.returncode != 0:
    sys.exit("FAIL: endatsim-vcdlint exited %d" % r.returncode)
print("%d waveforms clean" % len(waves))
