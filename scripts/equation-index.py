#!/usr/bin/env python3
"""Writes ARCHITECTURE.md's section 8: every seed equation cited in src/ and crates/*/src/ (`eq. 3.14`, `eq. 4.3-4.9`,
`eqs. 3.16`) and the files that cite it. Run from anywhere: python3 scripts/equation-index.py"""
import collections
import os
import re
import sys

sys.path.insert(0, os.path.dirname(__file__))
import docs_regions  # noqa: E402

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
cite = re.compile(r"eqs?\.\s?(\d+)\.(\d+)(?:\s?[-\u2013]\s?(?:(\d+)\.)?(\d+))?")
where = collections.defaultdict(set)
sources = [os.path.join(root, "src")] + sorted(
    os.path.join(root, "crates", c, "src") for c in os.listdir(os.path.join(root, "crates"))
)
for dirpath, _, files in (walked for src in sources for walked in os.walk(src)):
    for name in files:
        if not name.endswith((".rs", ".md")):
            continue
        path = os.path.join(dirpath, name)
        rel = os.path.relpath(path, root)
        with open(path, encoding="utf-8") as f:
            for m in cite.finditer(f.read()):
                chapter, first = int(m.group(1)), int(m.group(2))
                last = int(m.group(4)) if m.group(4) and (m.group(3) is None or int(m.group(3)) == chapter) else first
                for n in range(first, max(first, last) + 1):
                    if chapter in (3, 4):
                        where[(chapter, n)].add(rel)

lines = ["| equation | cited in |", "|---|---|"]
for (chapter, n) in sorted(where):
    lines.append(f"| {chapter}.{n} | " + ", ".join(f"`{p}`" for p in sorted(where[(chapter, n)])) + " |")
docs_regions.replace(os.path.join(root, "ARCHITECTURE.md"), {"equations": lines})
