#!/usr/bin/env python3
"""Markdown table of results/critical-strain-petsc/results.csv (for summary.md), with e_crit's relative difference
from the direct route of the same n. Usage: python3 benchmarks/distributed/critical_strain_petsc_table.py [CSV]"""
import csv
import sys

path = sys.argv[1] if len(sys.argv) > 1 else "results/critical-strain-petsc/results.csv"
rows = [r for r in csv.DictReader(open(path)) if r["status"] not in ("error",)]
direct = {r["n"]: float(r["e_crit"]) for r in rows if r["route"] == "direct" and r["status"] == "successful"}
print("| n | route | method | ranks | e_crit | rel. diff. vs direct | status | iterations | inner | residual | "
      "wall s (solve) | wall s (total) | CPU s (all ranks) | peak RSS MB (max rank / sum) |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    e = r["e_crit"]
    rel = "-"
    if r["n"] in direct and e not in ("", "nan") and r["route"] != "direct":
        rel = "%.1e" % (abs(float(e) - direct[r["n"]]) / direct[r["n"]])
    print("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s / %s |" % (
        r["n"], r["route"], r["method"], r["ranks"], e, rel, r["status"], r["iterations"], r["inner_iterations"],
        r["residual"], r["solve_s"], r["total_s"], r["cpu_s"], r["peak_rss_mb_max_rank"], r["peak_rss_mb_sum"]))
