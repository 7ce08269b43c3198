#!/usr/bin/env python3
"""Render a study's summary.md from its template and the numbers its driver wrote.

    render_summary.py studies/<name>/summary.md.in results/<name>/summary.json > results/<name>/summary.md

The template is Markdown with {{key}} placeholders; every key must exist in summary.json (one flat JSON object of
strings written by the driver through studies/common/study.hpp's Summary). A missing key, or a key the template does
not use, is an error: prose and numbers cannot drift apart silently.
"""
import json
import re
import sys


def render(template: str, values: dict) -> str:
    used = set()

    def sub(m):
        key = m.group(1)
        if key not in values:
            raise KeyError(f"template key '{key}' is not in summary.json")
        used.add(key)
        return str(values[key])

    out = re.sub(r"\{\{\s*([A-Za-z0-9_.\-]+)\s*\}\}", sub, template)
    unused = sorted(set(values) - used)
    if unused:
        raise KeyError("summary.json keys not used by the template: " + ", ".join(unused))
    return out


def main(argv):
    if len(argv) != 3:
        sys.exit("usage: render_summary.py TEMPLATE.md.in SUMMARY.json > summary.md")
    with open(argv[1], encoding="utf-8") as f:
        template = f.read()
    with open(argv[2], encoding="utf-8") as f:
        values = json.load(f)
    try:
        sys.stdout.write(render(template, values))
    except KeyError as e:
        sys.exit(f"render_summary.py: {argv[1]}: {e.args[0]}")


if __name__ == "__main__":
    main(sys.argv)
