#!/usr/bin/env python3
"""Writes the parameter rows' properties into schema/scenario.schema.json.

    endatsim parameters --schema | tools/update_schema.py schema/scenario.schema.json

The input maps the JSON pointer of an object's "properties" to the properties its rows generate
and the keys it requires (scenarios/parameter_docs.hpp). Each generated property replaces the
text of the one with the same key, on one line; everything else in the file stays as written.
A key the schema lacks is refused: where it goes is for a person to decide.
"""
import json
import os
import sys

DECODER = json.JSONDecoder()
WHITESPACE = " \t\r\n"


def past_whitespace(text, i):
    while i < len(text) and text[i] in WHITESPACE:
        i += 1
    return i


def spans(text, i, path, out):
    """Parses the value at text[i:], recording (start, end) of every value by its path."""
    i = past_whitespace(text, i)
    start = i
    if text[i] == "{":
        i = past_whitespace(text, i + 1)
        while text[i] != "}":
            key, i = DECODER.raw_decode(text, i)
            i = past_whitespace(text, i)
            assert text[i] == ":"
            i = spans(text, i + 1, path + (key,), out)
            i = past_whitespace(text, i)
            if text[i] == ",":
                i = past_whitespace(text, i + 1)
        i += 1
    elif text[i] == "[":
        i = past_whitespace(text, i + 1)
        k = 0
        while text[i] != "]":
            i = spans(text, i, path + (str(k),), out)  # JSON pointers name items by their index
            k += 1
            i = past_whitespace(text, i)
            if text[i] == ",":
                i = past_whitespace(text, i + 1)
        i += 1
    else:
        _, i = DECODER.raw_decode(text, i)
    out[path] = (start, i)
    return i


def compact(value):
    text = json.dumps(value, ensure_ascii=False, separators=(", ", ": "))
    return "{ " + text[1:-1] + " }" if isinstance(value, dict) and value else text


def path_of(pointer):
    return tuple(p.replace("~1", "/").replace("~0", "~") for p in pointer.lstrip("/").split("/"))


def main():
    path = sys.argv[1]
    generated = json.load(sys.stdin)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    where = {}
    spans(text, 0, (), where)
    edits = []
    for pointer, part in generated.items():
        properties = path_of(pointer)
        for key, prop in part["properties"].items():
            if properties + (key,) not in where:
                sys.exit(f"{path}: no property {pointer}/{key} to replace; add it by hand first")
            edits.append((where[properties + (key,)], compact(prop)))
        required = properties[:-1] + ("required",)
        if part.get("required"):
            if required not in where:
                sys.exit(f"{path}: {'/'.join(required)} missing; add it by hand first")
            edits.append((where[required], compact(part["required"])))
    for (start, end), replacement in sorted(edits, reverse=True):
        text = text[:start] + replacement + text[end:]
    json.loads(text)  # still a JSON document
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    main()
