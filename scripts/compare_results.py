#!/usr/bin/env python3
"""Compare two results/ trees CSV by CSV, ignoring timing columns.

Usage:
    python3 scripts/compare_results.py OLD_DIR NEW_DIR [--rtol 0] [--ignore-columns REGEX] [--list-timing] [--subset]

OLD_DIR and NEW_DIR are results/ trees (results/<study>/*.csv, possibly nested). If a directory holds
no CSV outside a `results/` subdirectory (e.g. the output of `git archive HEAD results | tar -x -C DIR`),
that subdirectory is used. Every *.csv present in either tree is compared; a file present in only one
tree is a failure (with --subset, OLD_DIR is a stored reference: only its CSVs are compared, and files only in
NEW_DIR are allowed).

Columns are matched by header name (a column present in only one file is a failure), rows by position
(a different row count is a failure). A cell is equal when both values parse as floats and are equal
(nan == nan, inf == inf with sign; within --rtol relative if given, default 0 = exact) or, otherwise,
when the two strings are identical. Timing columns (see TIMING_COLUMN_RULES) are not compared and are
counted separately; columns matching --ignore-columns are not compared either.

Rows in the output are numbered from 1 = first data row (the header is not counted).
Exit status: 0 iff no differing value, no missing file, no missing column and no row-count mismatch;
1 otherwise; 2 on usage errors.
"""

from __future__ import annotations

import argparse
import csv
import math
import os
import re
import signal
import sys
from dataclasses import dataclass, field

# ---------------------------------------------------------------------------------------------------
# Timing columns: measured wall/CPU times, quantities derived from them (throughputs, ratios of two
# timings, fractions of a measured bandwidth, fits against wall time), memory measured from the OS, and
# counts chosen by the benchmark harness from a time budget. They are not compared.
#
# Derived from the headers of every CSV under results/ (head -1 results/**/*.csv, Dec 2026):
#   assembly-speed/assembly.csv          seconds, pair_entries_per_s, bytes_per_s, copy_bandwidth,
#                                        ratio_to_copy                     (particles, h_over_dx compared)
#   critical-strain-2d/benchmark.csv     cpu_s, real_s, peak_rss_MB        (n, particles, dofs, nnz_A0,
#                                        nnz_lower, lnz, flops [CHOLMOD flop count], factorizations,
#                                        ecrit, colours compared)
#   critical-strain-2d/{sweep,nonsymmetric,versus_n}.csv, critical-tension/versus_n.csv,
#   mean-polishing/tcrit.csv             seconds
#   critical-tension/benchmark.csv       seconds, iterations (Google Benchmark iteration count, chosen
#                                        from the measured time)   (N, tcrit, rel_diff_vs_bisection,
#                                        factorizations compared)
#   critical-tension/timing.csv          seconds
#   jacobian-speed/jacobian.csv          jacobian_s, ratio_to_real_force, complex_over_real,
#                                        ratio_over_colours, setup_over_real (all ratios of timings)
#                                        (n, dofs, colours compared)
#   speed-vs-error/runs.csv              setup_s, run_s, total_s, us_per_particle_step
#   speed-vs-error/rates.csv             l1_vs_seconds_slope (slope of log L1 against log wall seconds)
#   stepping-speed/stepping_speed.csv    seconds_per_step, particle_steps_per_s, ratio_to_pair_loop,
#                                        achieved_GB_per_s, fraction_of_copy_bandwidth, setup_s,
#                                        neighbour_rebuilds_in_timed_steps (depends on the number of
#                                        timed iterations)   (particles, model_bytes_per_step,
#                                        stored_nonzeros, rel_diff_matrix_vs_pair_loop compared)
#   swegle/{energy,runs}.csv             wall_seconds
# Physical values that look like timings and ARE compared: t, T, dt, t_stop, t_end, t_linear_end,
# fit_t_begin, fit_t_end, t_first_minor, t_nn, growth_rate, growth_rate_per_us (per simulated
# microsecond), gamma_*, ratio, late_ratio, ratio_first_minor, ratio_uncorrected, rel_diff, steps,
# iterations (Newton, swegle/equilibrium.csv), neighbour_builds, flops.
#
# Each rule is (file regex, column regex); both are matched with re.fullmatch, the file against the
# path relative to the results/ root with '/' separators.
TIMING_COLUMN_RULES: list[tuple[str, str]] = [
    # wall / CPU time in seconds, anywhere in the name: seconds, wall_seconds, seconds_per_step,
    # l1_vs_seconds_slope
    (r".*", r".*seconds.*"),
    # times with a unit suffix: cpu_s, real_s, setup_s, run_s, total_s, jacobian_s, *_ms, *_ns, *_us
    (r".*", r"(.*_)?(cpu|real|wall|setup|run|total|elapsed|time|jacobian|solve|assembly|factor\w*)_(s|ms|us|ns)"),
    (r".*", r".*_(ms|ns)|(ms|ns|us)_.*"),
    # rates per wall second: particle_steps_per_s, pair_entries_per_s, bytes_per_s, achieved_GB_per_s
    (r".*", r".*_per_s(ec(ond)?)?"),
    # microseconds per unit of work: us_per_particle_step
    (r".*", r"(us|ns|ms)_per_.*"),
    # measured bandwidth and fractions of it: copy_bandwidth, fraction_of_copy_bandwidth
    (r".*", r".*bandwidth.*"),
    # ratios of two measured times
    (r".*", r"ratio_to_(copy|pair_loop|real_force)|ratio_over_colours|complex_over_real|setup_over_real"),
    # generic timing words (none in the current headers; kept for new benchmark columns)
    (r".*", r".*(elapsed|throughput|wall_?time|gflops|mflops|speedup).*"),
    # bare wall or thread-CPU seconds of a run: wall (swegle-nonlinear), wall_run, wall_linear, cpu (gms-rings)
    (r".*", r"(wall|cpu)(_\w+)?"),
    # memory measured from the OS: peak_rss_MB
    (r".*", r".*rss.*"),
    # Google Benchmark iteration counts (chosen from the measured time) in benchmark CSVs
    (r"(.*/)?benchmark[^/]*\.csv", r"iterations"),
    # neighbour rebuilds during the timed steps: the number of timed steps is chosen by the harness
    (r"(.*/)?stepping_speed\.csv", r"neighbour_rebuilds_in_timed_steps"),
]
# Physical quantities that are always compared, even if a timing rule above would match them
# (simulation time and time steps, growth rates per simulated time unit).
PHYSICAL_COLUMN_RULES: list[str] = [
    r"t|T|dt|time|t_.*|dt_.*|.*_t|fit_t_.*",  # dt_ns: a time step in ns, not a measured time
    r".*growth.*|gamma.*|.*_rate_per_.*",
]
_TIMING_RULES = [(re.compile(f), re.compile(c)) for f, c in TIMING_COLUMN_RULES]
_PHYSICAL_RULES = [re.compile(c) for c in PHYSICAL_COLUMN_RULES]


def is_timing_column(relpath: str, column: str) -> bool:
    if any(c.fullmatch(column) for c in _PHYSICAL_RULES):
        return False
    return any(f.fullmatch(relpath) and c.fullmatch(column) for f, c in _TIMING_RULES)


# ---------------------------------------------------------------------------------------------------

MAX_EXAMPLES = 10
MISSING_CELL = "<missing cell>"


def parse_float(s: str) -> float | None:
    t = s.strip()
    if not t or "_" in t:  # float() accepts '1_000'; a CSV value like that is a string
        return None
    try:
        return float(t)
    except ValueError:
        return None


def cells_equal(a: str, b: str, rtol: float) -> bool:
    if a == b:
        return True
    x, y = parse_float(a), parse_float(b)
    if x is None or y is None:
        return False  # non-numeric: exact string comparison
    if math.isnan(x) or math.isnan(y):
        return math.isnan(x) and math.isnan(y)
    if x == y:
        return True
    if math.isinf(x) or math.isinf(y) or rtol <= 0:
        return False
    return abs(x - y) <= rtol * max(abs(x), abs(y))


def find_root(d: str) -> str:
    """The results/ root: d itself, or d/results when d holds no CSV outside it."""
    sub = os.path.join(d, "results")
    if os.path.isdir(sub):
        for dirpath, dirnames, filenames in os.walk(d):
            if os.path.abspath(dirpath) == os.path.abspath(sub):
                dirnames[:] = []
                continue
            if any(f.endswith(".csv") for f in filenames):
                return d
        return sub
    return d


def list_csvs(root: str) -> set[str]:
    out = set()
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames.sort()
        for f in filenames:
            if f.endswith(".csv"):
                out.add(os.path.relpath(os.path.join(dirpath, f), root).replace(os.sep, "/"))
    return out


def read_csv(path: str) -> tuple[list[str], list[list[str]]]:
    with open(path, newline="", encoding="utf-8", errors="surrogateescape") as fh:
        rows = list(csv.reader(fh))
    if not rows:
        return [], []
    return rows[0], rows[1:]


def column_keys(header: list[str]) -> list[tuple[str, int]]:
    """(name, occurrence) for each column, so that repeated header names still match one to one."""
    seen: dict[str, int] = {}
    keys = []
    for h in header:
        k = seen.get(h, 0)
        seen[h] = k + 1
        keys.append((h, k))
    return keys


def key_name(k: tuple[str, int]) -> str:
    return k[0] if k[1] == 0 else f"{k[0]}#{k[1] + 1}"


def show(s: str) -> str:
    return s if s and s.strip() == s else repr(s)


@dataclass
class FileResult:
    relpath: str
    rows: int = 0
    compared_columns: int = 0
    compared_values: int = 0
    timing_values: int = 0
    timing_columns: list[str] = field(default_factory=list)
    ignored_columns: list[str] = field(default_factory=list)
    structural: list[str] = field(default_factory=list)  # missing columns, row counts
    differing: int = 0
    examples: list[str] = field(default_factory=list)

    @property
    def failed(self) -> bool:
        return bool(self.structural) or self.differing > 0


def compare_file(relpath: str, old_path: str, new_path: str, rtol: float,
                 ignore: re.Pattern | None) -> FileResult:
    r = FileResult(relpath)
    old_header, old_rows = read_csv(old_path)
    new_header, new_rows = read_csv(new_path)
    old_keys, new_keys = column_keys(old_header), column_keys(new_header)
    old_idx = {k: i for i, k in enumerate(old_keys)}
    new_idx = {k: i for i, k in enumerate(new_keys)}

    def ignored(k: tuple[str, int]) -> bool:
        return ignore is not None and bool(ignore.fullmatch(k[0]) or ignore.fullmatch(f"{relpath}:{k[0]}"))

    for k in old_keys:
        if k not in new_idx and not ignored(k):
            r.structural.append(f"column {key_name(k)} only in OLD")
    for k in new_keys:
        if k not in old_idx and not ignored(k):
            r.structural.append(f"column {key_name(k)} only in NEW")
    if len(old_rows) != len(new_rows):
        r.structural.append(f"row count differs: {len(old_rows)} in OLD, {len(new_rows)} in NEW")
    r.rows = min(len(old_rows), len(new_rows))

    compared: list[tuple[tuple[str, int], int, int]] = []
    for k in old_keys:  # OLD column order
        if k not in new_idx:
            continue
        if ignored(k):
            r.ignored_columns.append(key_name(k))
        elif is_timing_column(relpath, k[0]):
            r.timing_columns.append(key_name(k))
        else:
            compared.append((k, old_idx[k], new_idx[k]))
    r.compared_columns = len(compared)
    r.timing_values = len(r.timing_columns) * r.rows

    def cell(row: list[str], i: int) -> str:
        return row[i] if i < len(row) else MISSING_CELL

    for ri in range(r.rows):
        orow, nrow = old_rows[ri], new_rows[ri]
        for k, io, inew in compared:
            a, b = cell(orow, io), cell(nrow, inew)
            r.compared_values += 1
            if not cells_equal(a, b, rtol):
                r.differing += 1
                if len(r.examples) < MAX_EXAMPLES:
                    r.examples.append(f"row {ri + 1} column {key_name(k)}: {show(a)} -> {show(b)}")
    return r


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        description="Compare the CSV files of two results/ trees, skipping timing columns.",
        epilog="Exit status 0 iff every CSV is present in both trees with the same columns, the same "
               "number of rows and equal values (timing columns aside).")
    ap.add_argument("old_dir", metavar="OLD_DIR")
    ap.add_argument("new_dir", metavar="NEW_DIR")
    ap.add_argument("--rtol", type=float, default=0.0,
                    help="relative tolerance for numeric cells (default 0 = exact)")
    ap.add_argument("--ignore-columns", metavar="REGEX",
                    help="do not compare columns whose name (or 'study/file.csv:name') fully matches REGEX")
    ap.add_argument("--list-timing", action="store_true",
                    help="list the columns treated as timing columns, per file")
    ap.add_argument("--subset", action="store_true",
                    help="OLD_DIR is a stored reference: compare its CSVs only (files only in NEW_DIR are allowed)")
    args = ap.parse_args(argv)
    if args.rtol < 0 or math.isnan(args.rtol):
        ap.error("--rtol must be >= 0")
    for d in (args.old_dir, args.new_dir):
        if not os.path.isdir(d):
            ap.error(f"not a directory: {d}")
    try:
        ignore = re.compile(args.ignore_columns) if args.ignore_columns else None
    except re.error as e:
        ap.error(f"bad --ignore-columns regex: {e}")

    old_root, new_root = find_root(args.old_dir), find_root(args.new_dir)
    old_files, new_files = list_csvs(old_root), list_csvs(new_root)
    only_old = sorted(old_files - new_files)
    only_new = [] if args.subset else sorted(new_files - old_files)
    common = sorted(old_files & new_files)

    results: list[FileResult] = []
    for rel in common:
        res = compare_file(rel, os.path.join(old_root, rel), os.path.join(new_root, rel), args.rtol, ignore)
        results.append(res)
        skipped = ",".join(res.timing_columns) or "none"
        extra = f", ignored: {','.join(res.ignored_columns)}" if res.ignored_columns else ""
        if not res.failed:
            print(f"OK {rel} ({res.rows} x {res.compared_columns}, skipped timing: {skipped}{extra})")
        else:
            print(f"DIFF {rel} ({res.rows} x {res.compared_columns}, skipped timing: {skipped}{extra})")
            for s in res.structural:
                print(f"  {s}")
            for e in res.examples:
                print(f"  {e}")
            if res.differing > len(res.examples):
                print(f"  ... {res.differing - len(res.examples)} more differing values")
    for rel in only_old:
        print(f"MISSING {rel}: only in OLD ({old_root})")
    for rel in only_new:
        print(f"MISSING {rel}: only in NEW ({new_root})")

    if args.list_timing:
        print("timing columns (not compared):")
        for res in results:
            if res.timing_columns:
                print(f"  {res.relpath}: {', '.join(res.timing_columns)}")

    values = sum(r.compared_values for r in results)
    timing = sum(r.timing_values for r in results)
    differing = sum(r.differing for r in results)
    failed_files = sum(1 for r in results if r.failed) + len(only_old) + len(only_new)
    print(f"compared {len(results)} files, {values} values ({timing} timing values skipped): "
          f"{differing} differing values in {failed_files} files")
    structural = sum(len(r.structural) for r in results)
    if only_old or only_new or structural:
        print(f"also: {len(only_old)} files only in OLD, {len(only_new)} files only in NEW, "
              f"{structural} missing-column/row-count problems")
    return 1 if (differing or failed_files) else 0


if __name__ == "__main__":
    if hasattr(signal, "SIGPIPE"):
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # quiet when piped into head
    sys.exit(main())
