#!/usr/bin/python3
"""Keeps schema/scenario.schema.json and the loader (scenarios/loader.cpp) in agreement.

Every bundled scenario and the example of docs/scenario-format.md must validate against the schema and load;
then each of them is mutated systematically (an unknown key in every object, a value of the
wrong kind at every leaf, an emptied script, each required key removed, each optional key
removed) and the schema and `endatsim validate` must give the same verdict on every mutant.

When this fails after a change to the loader (a new operation, a new key), update the schema.

The malformed corpus in tests/malformed/ (every file there is rejected by the loader) must be
rejected by the schema too, or not parse as JSON at all, except the cases listed in
BEYOND_SCHEMA: constraints JSON Schema cannot state (ranges inside duration strings, order of
times, relations between numbers, duplicate keys, which JSON parsers resolve silently).

usage: schema_test.py ENDATSIM SCHEMA BUNDLED_DIR SCENARIO_FORMAT_MD WORKDIR [MALFORMED_DIR]
"""
import copy
import glob
import json
import os
import subprocess
import sys

try:
    import jsonschema
except ImportError:
    sys.exit("FAIL: python3-jsonschema is not installed (tools/quickstart installs it)")

REQUIRED = {("name",), ("line",), ("master",), ("script",), ("line", "cable_length_m"), ("master", "f_c")}
FREE_TEXT = {"name", "description", "$schema"}  # any string is right for these

BEYOND_SCHEMA = {
    "asynchronous_time_delay_step_too_long.json": "range inside a duration string",
    "cable_delay_too_large.json": "range inside a duration string",
    "t_cal_22_too_long.json": "range inside a duration string",
    "event_corrupt_address_beyond_area.json": "the size of a memory area depends on the encoder's image",
    "event_corrupt_missing_area.json": "which memory areas exist depends on the encoder's image",
    "event_corrupt_zero_mask.json": "a word that must not be zero, written as integer or hex string",
    "event_late_release_too_long.json": "range inside a duration string",
    "event_power_interruption_too_long.json": "range inside a duration string",
    "duplicate_key.json": "duplicate keys: JSON parsers keep the last",
    "duplicate_nested_key.json": "duplicate keys: JSON parsers keep the last",
    "events_backwards.json": "order of times",
    "expect_count_range_reversed.json": "relation between the two numbers of a count string",
    "f_c_too_high.json": "range inside a frequency string",
    "f_c_zero.json": "range inside a frequency string",
    "measurement_f_e_below_1_mhz.json": "range inside a frequency string",
    "huge_duration.json": "range inside a duration string",
    "huge_duration_in_range_digits.json": "range inside a duration string",
    "huge_frequency.json": "range inside a frequency string",
    "jitter_too_large_for_clock.json": "relation between jitter and the clock period",
    "max_time_zero.json": "range inside a duration string",
    "motion_start_beyond_position_bits.json": "relation between motion.start and position_bits",
    "selected_reference_mark_beyond_marks.json": "how many reference marks exist depends on the profile's words 18/19",
    "script_at_backwards.json": "order of times",
    "start_bit_timeout_zero.json": "range inside a duration string",
    "t_cal_fraction_of_ps.json": "a duration that is not a whole number of picoseconds",
    "t_m_too_short.json": "range inside a duration string",
    "transceiver_delay_too_large.json": "range inside a duration string",
}


def doc_example(path):
    text = open(path, encoding="utf-8").read()
    section = text.index("# Scenario format")
    begin = text.index("```json\n", section) + len("```json\n")
    return json.loads(text[begin:text.index("```\n", begin)])


def walk(node, path=()):
    yield path, node
    if isinstance(node, dict):
        for k, v in node.items():
            yield from walk(v, path + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from walk(v, path + (i,))


def get(doc, path):
    for p in path:
        doc = doc[p]
    return doc


def required(doc, path):
    """Keys the loader needs: the fixed ones, an operation's op and a wait's duration, an event's keys."""
    if tuple(path) in REQUIRED:
        return True
    parent = get(doc, path[:-1])
    key = path[-1]
    if len(path) == 3 and path[0] == "script":
        return key == "op" or (key == "duration" and parent.get("op") == "wait")
    if len(path) == 3 and path[0] == "events":
        return key in ("at", "set_cable")
    if len(path) == 4 and path[0] == "events":
        return key == "cable_length_m"
    return False


def mutants(doc):
    """(description, mutant, rejected_by_design) for one valid document."""
    for path, node in walk(doc):
        where = "/" + "/".join(str(p) for p in path)
        if isinstance(node, dict):
            m = copy.deepcopy(doc)
            get(m, path)["no_such_key"] = 1
            yield "unknown key in " + where, m, True
            for key in node:
                m = copy.deepcopy(doc)
                del get(m, path)[key]
                sub = path + (key,)
                yield "without " + "/" + "/".join(str(p) for p in sub), m, required(doc, sub)
        elif isinstance(node, list):
            if path == ("script",):
                m = copy.deepcopy(doc)
                m["script"] = []
                yield "empty script", m, True
        else:
            if path[-1] in FREE_TEXT and len(path) == 1:
                continue
            m = copy.deepcopy(doc)
            replacement = "yes" if isinstance(node, bool) else "seven" if isinstance(node, (int, float)) else "no such value"
            get(m, path[:-1])[path[-1]] = replacement
            yield "wrong kind at " + where, m, True


def main():
    if len(sys.argv) not in (6, 7):
        sys.exit(__doc__)
    endatsim, schema_path, bundled, doc, work = sys.argv[1:6]
    malformed = sys.argv[6] if len(sys.argv) == 7 else None
    os.makedirs(work, exist_ok=True)
    schema = json.load(open(schema_path))
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)

    # The bundled scenarios and the safety-function pairs next to them (scenarios/safety/).
    paths = glob.glob(os.path.join(bundled, "*.json")) + glob.glob(os.path.join(bundled, "..", "safety", "*.json"))
    documents = [(os.path.basename(p), json.load(open(p))) for p in sorted(paths)]
    documents.append(("docs/scenario-format.md example", doc_example(doc)))
    if len(documents) < 2:
        sys.exit("FAIL: no bundled scenarios found in " + bundled)

    # Every other scenario of the source tree is validated too (without mutants, which the
    # documents above already cover): the field-bug library, the sweeps and the benchmark's.
    others = []
    for folder in (os.path.join(bundled, "..", "field"), os.path.join(bundled, "..", "sweeps"),
                   os.path.join(bundled, "..", "..", "bench", "scenarios")):
        found = sorted(glob.glob(os.path.join(folder, "*.json")))
        if not found:
            sys.exit("FAIL: no scenarios found in " + folder)
        others += [(os.path.relpath(p, os.path.join(bundled, "..", "..")), json.load(open(p))) for p in found]

    problems = []
    for name, doc in documents + others:
        errors = sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))
        for e in errors:
            problems.append("%s does not validate against %s at /%s: %s\n  -> update the schema to match "
                            "scenarios/loader.cpp" % (name, schema_path, "/".join(str(p) for p in e.absolute_path), e.message))

    cases = []
    for name, doc in documents:
        cases.append((name + ": as bundled", doc, False))
        for description, mutant, rejected in mutants(doc):
            cases.append((name + ": " + description, mutant, rejected))
    files = []
    for i, (_, doc, _) in enumerate(cases):
        path = os.path.join(work, "case%05d.json" % i)
        with open(path, "w") as out:
            json.dump(doc, out, indent=1)
        files.append(path)
    r = subprocess.run([endatsim, "validate", *files], capture_output=True, text=True, timeout=600)
    accepted = {line.split()[1] for line in r.stdout.splitlines() if line.startswith("valid ")}
    errors = {}
    for line in r.stderr.splitlines():
        for f in files:
            if (f + ":") in line:
                errors[f] = line

    agreed = rejected_both = 0
    for (description, doc, by_design), path in zip(cases, files):
        schema_ok = validator.is_valid(doc)
        loader_ok = path in accepted
        if schema_ok != loader_ok:
            problems.append("%s: the schema %s it, the loader %s it%s" % (
                description, "accepts" if schema_ok else "rejects", "accepts" if loader_ok else "rejects",
                (" (" + errors[path] + ")") if path in errors else ""))
        elif by_design and schema_ok:
            problems.append("%s: both accept what should be rejected" % description)
        else:
            agreed += 1
            rejected_both += 0 if schema_ok else 1
    corpus = 0
    if malformed:
        for path in sorted(glob.glob(os.path.join(malformed, "*.json"))):
            name = os.path.basename(path)
            try:
                doc = json.loads(open(path, "rb").read().decode("utf-8"))
            except (ValueError, UnicodeDecodeError, RecursionError):
                corpus += 1  # no JSON tool reads it: rejected by both
                continue
            if not validator.is_valid(doc) or name in BEYOND_SCHEMA:
                corpus += 1
                continue
            problems.append("%s: the loader rejects it, the schema accepts it -> tighten the schema, or list it in "
                            "BEYOND_SCHEMA in tests/interop/schema_test.py with the reason" % path)
        if corpus == 0:
            problems.append("no malformed scenarios found in " + malformed)

    if problems:
        print("FAIL: schema/scenario.schema.json and scenarios/loader.cpp disagree:", file=sys.stderr)
        for p in problems:
            print("  " + p, file=sys.stderr)
        sys.exit(1)
    print("%d documents validate; %d cases agree (%d rejected by both); %d malformed files rejected" %
          (len(documents), agreed, rejected_both, corpus))


main()
