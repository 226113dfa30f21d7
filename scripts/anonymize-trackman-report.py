#!/usr/bin/env python3
"""Replaces the player's name, any e-mail address and the facility's names in TrackMan report JSON files
(`"Kind": "multiGroupReport"`) with neutral placeholders, in place, and changes nothing else.

- every `Player` object's `Name` -> "Player A"
- the report's `User.Name` and every `Groups` entry of kind `Facility...` or `Location` -> "Facility A"
- every `Groups` entry of kind `Bay` -> "Facility A bay N" (N: the bay's number in its name, if any)
- every string value of a key containing "mail" -> "player-a@example.invalid"

The replacement is made on the file's text (each old value's JSON string literal becomes the new one's), so the
layout, number formatting and key order stay byte for byte the upstream file's. The script fails if a word of a
replaced name (4 letters or more) is still in the file afterwards, in any case and any field.

Usage: scripts/anonymize-trackman-report.py FILE.json...
"""
import json
import re
import sys

PLAYER = "Player A"
FACILITY = "Facility A"
EMAIL = "player-a@example.invalid"
# Words of a facility's name that name no one ("Golf" in "... Golf") and occur elsewhere in TrackMan's reports.
GENERIC = {"golf", "club", "studio", "center", "centre", "range"}


def replacements(report):
    """Old string -> new string, from the fields that name a person or a place."""
    out = {}

    def walk(node, key=""):
        if isinstance(node, dict):
            for k, v in node.items():
                if k == "Player" and isinstance(v, dict) and isinstance(v.get("Name"), str):
                    out[v["Name"]] = PLAYER
                if "mail" in k.lower() and isinstance(v, str) and v:
                    out[v] = EMAIL
                walk(v, k)
        elif isinstance(node, list):
            for v in node:
                walk(v, key)

    walk(report)
    user = report.get("User") or {}
    if isinstance(user.get("Name"), str):
        out[user["Name"]] = FACILITY
    for group in report.get("Groups") or []:
        kind, name = str(group.get("Kind", "")), group.get("Name")
        if not isinstance(name, str):
            continue
        if kind.startswith("Facility") or kind == "Location":
            out[name] = FACILITY
        elif kind == "Bay":
            number = re.findall(r"\d+", name)
            out[name] = f"{FACILITY} bay {number[-1]}" if number else f"{FACILITY} bay"
    return {old: new for old, new in out.items() if old != new}


def anonymize(path):
    text = open(path, encoding="utf-8").read()
    table = replacements(json.loads(text))
    for old, new in table.items():
        text = text.replace(json.dumps(old, ensure_ascii=False), json.dumps(new, ensure_ascii=False))
    words = {w.lower() for old in table for w in re.findall(r"[A-Za-z]{4,}", old)}
    words -= {w.lower() for new in (PLAYER, FACILITY, EMAIL) for w in re.findall(r"[A-Za-z]{4,}", new)}
    words -= {"invalid", "example"} | GENERIC
    left = sorted(w for w in words if w in text.lower())
    if left:
        sys.exit(f"{path}: still names {left} after the replacement")
    json.loads(text)
    open(path, "w", encoding="utf-8", newline="").write(text)
    print(f"{path}: {len(table)} values replaced", file=sys.stderr)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for p in sys.argv[1:]:
        anonymize(p)
