#!/usr/bin/env python3
"""Rewrites the absolute program path that Google Benchmark records in a json's context ("executable", its argv[0])
so that no committed result names a directory of one machine (tests/architecture/recorded_paths_test.cpp).

    python3 benchmarks/relative_executable.py results/<study>/benchmark.json [...]

Rule: a program inside the repository becomes its path relative to the repository root (build/bin/x); a program of a
build directory outside the repository becomes build/bin/<name> (the default build directory of scripts/build.sh:
where the build lived is not part of the result). A relative path is left as it is. Only that one line of the file is
changed (the rest is kept byte for byte, so the numbers stay exactly as the benchmark wrote them).
"""
import os
import re
import sys

ROOT = os.path.realpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
LINE = re.compile(r'("executable":\s*")([^"]*)(")')


def relative(path):
    if not os.path.isabs(path):
        return path
    real = os.path.realpath(path)
    if os.path.commonpath([real, ROOT]) == ROOT:
        return os.path.relpath(real, ROOT)
    return "build/bin/" + os.path.basename(path)


def main(files):
    for name in files:
        with open(name, encoding="utf-8") as f:
            text = f.read()
        new = LINE.sub(lambda m: m.group(1) + relative(m.group(2)) + m.group(3), text, count=1)
        if new != text:
            with open(name, "w", encoding="utf-8") as f:
                f.write(new)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
