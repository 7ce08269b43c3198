#!/usr/bin/env python3
"""The sanitizer stage of CI (scripts/sanitize.sh) still covers the library.

    sanitizer_coverage_test.py BUILD_DIR

scripts/sanitize.sh is cut for time (no studies, no benchmarks, -O1). This test fails when a cut goes too far:
  1. the sanitize build still compiles with -fsanitize=address,undefined and does not switch the tests off;
  2. its ctest call selects, among the tests registered in BUILD_DIR (the same CMake test list: sanitize.sh only
     changes compile flags and the study/benchmark/PETSc options), at least one test program for every layer of
     docs/layers.txt that has test programs of its own in tests/<layer>/ (PETSc's distributed/ excepted: sanitize.sh
     leaves MPI out);
  3. every test program the Release suite builds from tests/**/*_test.cpp is also in the sanitizer selection, except
     MPI programs and *_slow_test.cpp (label slow, which the sanitizer stage may leave to the Release stage).
A test file tests/<layer>/<name>_test.cpp belongs to the layer of its folder, and to the program that builds it:
BUILD_DIR/test_programs.txt (written by tests/CMakeLists.txt) lists each program with its sources (a group of files
with SPHSTAB_TEST_PROGRAMS=folder, one file with =file); a selected program covers every file it builds.
"""
import json
import os
import re
import shlex
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def fail(msg):
    print("sanitizer_coverage_test: " + msg)
    sys.exit(1)


def sanitize_script():
    with open(os.path.join(ROOT, "scripts", "sanitize.sh"), encoding="utf-8") as f:
        return f.read()


def ctest_filters(text):
    """The selection arguments (-L/-LE/-R/-E/--label-regex/...) of sanitize.sh's ctest call."""
    calls = [line for line in text.splitlines() if line.strip().startswith("ctest ")]
    if len(calls) != 1:
        fail(f"expected one ctest call in scripts/sanitize.sh, found {len(calls)}")
    words = shlex.split(calls[0].replace('"$build"', "BUILD").replace('"$(nproc)"', "2"))
    keep, i = [], 0
    selecting = {"-L", "-LE", "-R", "-E", "--label-regex", "--label-exclude", "--tests-regex", "--exclude-regex",
                 "-I", "--tests-information"}
    while i < len(words):
        if words[i] in selecting and i + 1 < len(words):
            keep += words[i:i + 2]
            i += 2
        else:
            i += 1
    return keep


def selected_programs(build, filters):
    out = subprocess.run(["ctest", "--test-dir", build, "--show-only=json-v1"] + filters, capture_output=True,
                         text=True, check=True).stdout
    programs = set()
    for test in json.loads(out).get("tests", []):
        command = test.get("command") or []
        if command:
            programs.add(os.path.basename(command[0]))
    return programs


def main(argv):
    if len(argv) != 2:
        fail("usage: sanitizer_coverage_test.py BUILD_DIR")
    build = argv[1]
    text = sanitize_script()
    flags = re.search(r'flags="([^"]*)"', text)
    if not flags or "-fsanitize=address" not in flags.group(1) or "undefined" not in flags.group(1):
        fail("scripts/sanitize.sh no longer compiles with -fsanitize=address,undefined")
    if re.search(r"SPHSTAB_BUILD_TESTS=OFF", text):
        fail("scripts/sanitize.sh switches the tests off")

    tests_dir = os.path.join(ROOT, "tests")
    program_layer = {}
    for dirpath, _, files in os.walk(tests_dir):
        for f in files:
            if f.endswith("_test.cpp"):
                layer = os.path.relpath(dirpath, tests_dir).split(os.sep)[0]
                program_layer[f[:-4]] = layer
    chosen = selected_programs(build, ctest_filters(text))
    if not chosen:
        fail(f"the sanitizer's ctest selection finds no test in {build}")

    with open(os.path.join(ROOT, "docs", "layers.txt"), encoding="utf-8") as f:
        layers = [line.split()[0] for line in f if line.strip() and not line.startswith("#")]
    # A program stands for every test file it builds (test_programs.txt: "program source...").
    listing = os.path.join(build, "test_programs.txt")
    if not os.path.exists(listing):
        fail(f"{listing} is missing (tests/CMakeLists.txt writes it)")
    with open(listing, encoding="utf-8") as f:
        for line in f:
            words = line.split()
            if words and words[0] in chosen:
                chosen = chosen | {os.path.basename(src)[:-4] for src in words[1:]}
    covered = {program_layer[p] for p in chosen if p in program_layer}
    tested = set(program_layer.values())  # layers with test programs of their own (system/ is tested through growth/)
    missing = [layer for layer in layers if layer != "distributed" and layer in tested and layer not in covered]
    if missing:
        fail("library layers with no test program in the sanitizer stage: " + ", ".join(missing))
    release = {p for p, layer in program_layer.items() if layer != "distributed" and not p.endswith("_slow_test")}
    left_out = sorted(release - chosen)
    if left_out:
        fail(f"{len(left_out)} test program(s) of the Release suite are not in the sanitizer selection: "
             + ", ".join(left_out[:10]) + (" ..." if len(left_out) > 10 else ""))
    print(f"OK: {len(chosen)} test programs in the sanitizer selection cover {len(covered)} layers")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
