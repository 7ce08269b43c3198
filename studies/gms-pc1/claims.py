"""Headline claims of gms-pc1 (results/gms-pc1/), run by tests/scripts/claims_test.py."""
import math

from claims import approx, check, md_table, one, select

REFINEMENTS = (1, 2, 4)


def _errors(r, scene, integrator):
    return [one(r.csv("runs.csv"), scene=scene, integrator=integrator, refinement=k)["error_dp"] for k in REFINEMENTS]


def _slope(xs, ys):
    lx, ly = [math.log(x) for x in xs], [math.log(abs(y)) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def claim_every_run_completes_against_one_reference(r):
    """Every plate and rings run completed; each scene has one reference (error 0) and every other run a positive
    error; all runs of a scene end at the same time."""
    rows = r.csv("runs.csv")
    for scene in ("plate", "rings"):
        mine = select(rows, scene=scene)
        check(all(x["status"] == "completed" for x in mine), f"{scene}: a run did not complete")
        refs = [x for x in mine if x["error_dp"] == 0]
        check(len(refs) == 1 and refs[0]["integrator"] == "PC2" and refs[0]["refinement"] == r.num(f"{scene}_reference"),
              f"{scene}: {len(refs)} runs with error 0")
        check(all(x["error_dp"] > 0 for x in mine if x is not refs[0]), f"{scene}: a non-reference run with error 0")
        ends = {x["t_end"] for x in mine}
        check(len(ends) == 1, f"{scene}: end times {ends}")
        for x in mine:  # whole steps to the common end
            approx(x["steps"] * x["dt"], x["t_end"], f"{x.where()} steps x dt", rel=1e-12)
    return "plate and rings: every run completed, one reference each, one end time"


def claim_cost_is_one_rate_per_pc1_step(r):
    """PC2 evaluates 2 rates per step, PC1 one per step plus the start: PC1 at dt0/2 has PC2 at dt0's evaluations + 1."""
    for x in r.csv("runs.csv"):
        want = 2 * x["steps"] if x["integrator"] == "PC2" else x["steps"] + 1
        check(x["rate_evaluations"] == want, f"{x.where()}: {x['rate_evaluations']} evaluations, expected {want}")
    for scene in ("plate", "rings"):
        pc2 = one(r.csv("runs.csv"), scene=scene, integrator="PC2", refinement=1)
        pc1 = one(r.csv("runs.csv"), scene=scene, integrator="PC1", refinement=2)
        check(pc1["rate_evaluations"] == pc2["rate_evaluations"] + 1, f"{scene}: equal-cost pair is not equal cost")
    return "rate evaluations: 2 per PC2 step, 1 per PC1 step (+ the start)"


def claim_ratios_orders_and_decisions_are_the_csv(r):
    """The summary's errors, orders, equal- and half-cost ratios and the decision by the README's rule (PC1 completes at
    dt0 and its error at dt0/2 is <= PC2's at dt0) are recomputed from runs.csv."""
    found = []
    for scene in ("plate", "rings"):
        e2, e1 = _errors(r, scene, "PC2"), _errors(r, scene, "PC1")
        dt0 = one(r.csv("runs.csv"), scene=scene, integrator="PC2", refinement=1)["dt"]
        dts = [dt0 / k for k in REFINEMENTS]
        for name, errs in (("pc2", e2), ("pc1", e1)):
            for k, e in zip(REFINEMENTS, errs):
                approx(r.num(f"{scene}_{name}_error_{k}"), e, f"{scene} {name} error dt0/{k}", rel=5e-3)
            approx(r.num(f"{scene}_{name}_order"), _slope(dts, errs), f"{scene} {name} order", rel=5e-3)
        equal, half = e1[1] / e2[0], e1[0] / e2[0]
        approx(r.num(f"{scene}_equal_cost_ratio"), equal, f"{scene} equal-cost ratio", rel=5e-3)
        approx(r.num(f"{scene}_half_cost_ratio"), half, f"{scene} half-cost ratio", rel=5e-3)
        decision = "PC1" if math.isfinite(e1[0]) and equal <= 1 else "PC2"
        check(r.key(f"{scene}_decision") == decision, f"{scene}: decision {r.key(f'{scene}_decision')}, rule {decision}")
        found.append(f"{scene} equal-cost {equal:.3g} -> {decision}")
    return "; ".join(found)


def claim_slab_refuses_pc1(r):
    """The slab (yield stress) refuses the one-rate step, so its decision is PC2."""
    check(r.key("slab_pc1").startswith("refused: ") and "yield stress" in r.key("slab_pc1"),
          f"slab_pc1: {r.key('slab_pc1')}")
    check(r.key("slab_decision") == "PC2", f"slab decision {r.key('slab_decision')}")
    return "slab: PC1 refused (yield stress) -> PC2"


def claim_runs_table_is_runs_csv(r):
    """The runs table lists every runs.csv row with its evaluations and status."""
    rows, table = r.csv("runs.csv"), md_table(r.key("runs_table"))
    check(len(table) == len(rows), f"runs table {len(table)} rows, runs.csv {len(rows)}")
    for cells, x in zip(table, rows):
        check(cells[0] == x["scene"] and cells[3] == str(x["rate_evaluations"]) and cells[6] == x["status"],
              f"{x.where()}: table row {cells}")
    return f"{len(table)} rows = runs.csv"


def claim_library_default_is_the_decision(r):
    """The plate's and rings' default integrator in the library (src/problems/gms_scenes.cpp, kGmsElasticIntegrator,
    which `sphstab scene` and Python's run use) is the study's decision for both scenes."""
    import os
    import re
    from claims import ROOT
    with open(os.path.join(ROOT, "src", "problems", "gms_scenes.cpp"), encoding="utf-8") as f:
        m = re.search(r'kGmsElasticIntegrator = "(\w+)"', f.read())
    check(m is not None, "src/problems/gms_scenes.cpp: no kGmsElasticIntegrator")
    for scene in ("plate", "rings"):
        check(m.group(1) == r.key(f"{scene}_decision").lower(),
              f"library default {m.group(1)}, {scene} decision {r.key(f'{scene}_decision')}")
    return f"library default {m.group(1)} = the plate's and rings' decision"
