#!/usr/bin/env python3
"""Turns the json of tl_step_benchmark into a markdown report: the finite-strain total-Lagrangian step per particle on
one core (force evaluation, leap-frog step, constitutive update alone) and its ratio to the memory-bandwidth bound
measured in the same run.

    python3 benchmarks/tl_step_report.py benchmark.json benchmark.md [--commit HASH]

Each row is the fastest repetition of its benchmark (the machine is shared); its counters come from that same
repetition, so particle-steps/s and the bound ratio are from one measurement. The bound ratio is the benchmark's own
counter: wall time per iteration over model_bytes / (the triad bandwidth measured last before it in the process).
Every sentence is computed from the inputs or describes the benchmark's code.
"""
import argparse
import json
import re


def base_name(name):
    return re.split(r"/(?:iterations|min_time|repeats|real_time)", name)[0]


def best(bms, name):
    """The fastest repetition of benchmark `name` (dict), or None."""
    runs = [b for b in bms if b.get("run_type") == "iteration" and base_name(b["name"]) == name
            and not b.get("error_occurred")]
    return min(runs, key=lambda b: b["real_time"]) if runs else None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("json")
    ap.add_argument("md")
    ap.add_argument("--commit", help="the source commit of the benchmark binary, printed in the report")
    a = ap.parse_args()
    with open(a.json) as f:
        data = json.load(f)
    bms = data["benchmarks"]
    errors = [b["name"] for b in bms if b.get("error_occurred")]
    triads = {n: best(bms, n) for n in ("Triad", "TriadAgain")}
    tri = {n: b["bytes_per_second"] / 1e9 for n, b in triads.items() if b}
    ctx = data["context"]
    lines = ["# Finite-strain TL step: speed per particle-step (tl_step_benchmark)", "",
             (f"Commit {a.commit}. " if a.commit else "") +
             f"Machine: {ctx.get('num_cpus')} CPUs at {ctx.get('mhz_per_cpu')} MHz, {ctx.get('date')}; one thread. "
             "STREAM triad in the same run: "
             + ", ".join(f"{n} {v:.2f} GB/s" for n, v in tri.items()) + " (before and after the scenes).", ""]
    if errors:
        lines += ["Benchmarks that stopped with an error (not in the table): " + ", ".join(errors), ""]
    lines += ["| what | material | gradient | particles | pairs / particle | ns per particle-step | "
              "particle-steps/s | model bytes per particle | bound ns per particle | time / bound | peak RSS (MB) |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    keys = []
    for b in bms:
        k = base_name(b["name"])
        if k not in keys and k.split("/")[0] in ("Eval", "Step", "Stress"):
            keys.append(k)
    order = {"Step": 0, "Eval": 1, "Stress": 2}
    keys.sort(key=lambda k: (int(k.split("/")[2]), k.split("/")[1], order[k.split("/")[0]]))
    for k in keys:
        b = best(bms, k)
        if b is None:
            continue
        what, variant, _ = k.split("/")
        material, gradient = variant.split("-")
        n = b["particles"]
        rate = b["particle_steps_per_s"]
        ratio = b.get("bound_ratio")  # absent when no triad ran before it (--benchmark_filter)
        label = {"Step": "leap-frog step", "Eval": "force evaluation", "Stress": "constitutive update"}[what]
        cells = [label, material, gradient if what != "Stress" else "-", f"{int(n)}", f"{b['pairs'] / n:.0f}",
                 f"{1e9 / rate:.1f}", f"{rate / 1e6:.2f} M", f"{b['model_bytes'] / n:.0f}",
                 f"{1e9 / rate / ratio:.2f}" if ratio else "-", f"{ratio:.2f}" if ratio else "-",
                 f"{b['peak_rss_mb']:.0f}"]
        lines.append("| " + " | ".join(cells) + " |")
    lines += ["",
              "- **leap-frog step**: LeapfrogStepper::step (kick, drift, one force evaluation, kick), continuing from "
              "step to step; **force evaluation**: FiniteStrainTotalLagrangian::acceleration at the set-up state "
              "(strain pass into F, P(F) per particle, divergence pass); **constitutive update**: "
              "P(F) alone for every particle through the material's virtual stress() (per material, not per "
              "gradient). Periodic square lattices, cubic B-spline, h = 1.3 dx, plane strain, difference strain and "
              "Plus divergence; gradient Plain: K = G, Ncsph: the corrected reference gradient (a second operator set).",
              "- **model bytes**: the least data the operation must move (tl_step_benchmark.cpp eval_bytes / "
              "step_bytes): the two strain and the two divergence matrices once each (8 B value + 4 B index per "
              "entry, 4 B per row), u read, P written and read back, a written; F is not counted (the model has it "
              "consumed in cache by the constitutive update; the form stores it, 64 B per particle more); the step "
              "adds nine vector passes. "
              "**bound** = model bytes / triad bandwidth; **time / bound** > 1 is that many times slower than "
              "streaming those bytes at the triad's rate.",
              "- **ns per particle-step** = 1 / particle-steps/s (particle-evaluations for the evaluation and the "
              "constitutive update). Fastest of three repetitions; the two cores are shared, so a run with other "
              "jobs on the machine is slower by tens of percent.", ""]
    with open(a.md, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
