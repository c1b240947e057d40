#!/usr/bin/python3
"""Every relative link in the project's Markdown resolves.

Checks README.md, docs/*.md and every other *.md file of the source tree (build trees and
hidden directories left out): each inline link or image `[text](target)` and each reference
definition `[label]: target` whose target is not a URL must name a file or directory that
exists, relative to the Markdown file; a `#fragment` into a Markdown file (or into the file
itself) must name a heading of that file, as GitHub derives its anchor, or an explicit
`<a id="...">`. Links inside code blocks and code spans are not links and are not checked.

usage: doc_links_test.py SOURCE_DIR
"""
import os
import re
import sys
import urllib.parse

URL = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")  # http:, https:, mailto:, ...
INLINE = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+\"[^\"]*\")?\s*$")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
EXPLICIT_ID = re.compile(r"<a\s+(?:[^>]*\s)?(?:id|name)=\"([^\"]+)\"", re.IGNORECASE)


def markdown_files(root):
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith(".")
                             and not os.path.exists(os.path.join(dirpath, d, "CMakeCache.txt")))
        for name in sorted(filenames):
            if name.endswith(".md"):
                yield os.path.join(dirpath, name)


def prose_lines(text):
    """(line number, line, line with code spans blanked) outside fenced code blocks."""
    fence = None
    for number, line in enumerate(text.split("\n"), 1):
        stripped = line.lstrip()
        if fence:
            if stripped.startswith(fence):
                fence = None
            continue
        if stripped.startswith("```") or stripped.startswith("~~~"):
            fence = stripped[:3]
            continue
        yield number, line, re.sub(r"(`+)(?:(?!\1).)*?\1", lambda m: " " * len(m.group(0)), line)


def slug(heading):
    """GitHub's anchor for a heading's text."""
    text = re.sub(r"<[^>]*>", "", heading)                    # HTML tags
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)    # links: their text
    text = text.strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


anchor_cache = {}


def anchors(path):
    if path not in anchor_cache:
        found = set()
        counts = {}
        text = open(path, encoding="utf-8").read()
        for _, line, prose in prose_lines(text):
            found.update(EXPLICIT_ID.findall(prose))
            m = HEADING.match(line)
            if m:
                base = slug(m.group(2))
                n = counts.get(base, 0)
                counts[base] = n + 1
                found.add(base if n == 0 else f"{base}-{n}")
        anchor_cache[path] = found
    return anchor_cache[path]


def check(root):
    problems = []
    checked = 0
    for md in markdown_files(root):
        text = open(md, encoding="utf-8").read()
        rel_md = os.path.relpath(md, root)
        for number, _, prose in prose_lines(text):
            targets = INLINE.findall(prose)
            m = REFERENCE.match(prose)
            if m:
                targets.append(m.group(1))
            for target in targets:
                if not target or URL.match(target):
                    continue
                checked += 1
                path_part, _, fragment = target.partition("#")
                path_part = urllib.parse.unquote(path_part)
                resolved = os.path.normpath(os.path.join(os.path.dirname(md), path_part)) if path_part else md
                where = f"{rel_md}:{number}: ({target})"
                if not os.path.exists(resolved):
                    problems.append(f"{where}: {os.path.relpath(resolved, root)} does not exist")
                    continue
                if not os.path.realpath(resolved).startswith(os.path.realpath(root) + os.sep):
                    problems.append(f"{where}: points outside the repository")
                    continue
                if fragment and resolved.endswith(".md"):
                    if urllib.parse.unquote(fragment) not in anchors(resolved):
                        problems.append(f"{where}: no heading or anchor #{fragment} in "
                                        f"{os.path.relpath(resolved, root)}")
    return checked, problems


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    root = os.path.realpath(sys.argv[1])
    checked, problems = check(root)
    for p in problems:
        print("FAIL " + p)
    if problems:
        sys.exit(f"{len(problems)} broken link(s) of {checked}")
    if checked == 0:
        sys.exit("FAIL: no relative links found; is SOURCE_DIR the repository?")
    print(f"ok: {checked} relative links resolve")


if __name__ == "__main__":
    main()
