#!/usr/bin/python3
"""Write results/README.md, the map of the results: per family of studies/index.toml a table, one row per study
with its question, its headline finding, the sources it checks, its wall time, whether the default main job runs it
and a link to its summary.

Every headline is rendered from data. The study's `headline` field in studies/index.toml is a template whose
{placeholders} are keys of results/<name>/summary.json, or values that a named extractor below (index field
`extract`) computes from the study's committed CSV/JSON files or from the tables in its summary.json. A key that is
in neither is an error naming the study and the key: no silent blanks.

Usage: /usr/bin/python3 scripts/results_map.py            write results/README.md
       /usr/bin/python3 scripts/results_map.py --check    exit 1 if the committed results/README.md is not what this
                                                          script would write (or a headline key is missing)
Python 3.11 standard library only.
"""
import csv
import json
import math
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS = os.path.join(ROOT, "results")
OUT = os.path.join(RESULTS, "README.md")
FAMILIES = ["stability analysis", "Swegle", "impact problems", "GMS scenes", "finite strain", "non-reflecting boundaries", "scale",
            "speed"]
REQUIRED = ("family", "question", "sources", "headline")


class MapError(Exception):
    pass


# ---------------------------------------------------------------------------------------------------- small helpers
def g3(x):
    """A number with 3 significant digits (inf/-inf/nan as words)."""
    if isinstance(x, str):
        return x
    if math.isinf(x):
        return "∞" if x > 0 else "−∞"
    if math.isnan(x):
        return "nan"
    return f"{x:.3g}"


def num(cell):
    """The first number in a table cell ('**U** 1.93', '+0.74 %', 'inf', '-inf' ...); None if there is none."""
    s = cell.replace("**", "").replace("−", "-").strip()
    if s in ("inf", "∞"):
        return math.inf
    if s in ("-inf", "−∞"):
        return -math.inf
    m = re.search(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?", s)
    return float(m.group(0)) if m else None


def md_rows(table):
    """The body rows of a markdown table (a string of '| a | b |' lines), each a list of stripped cells. Header and
    separator rows are dropped (a header is a row followed by a |---| row)."""
    lines = [ln.strip() for ln in table.splitlines() if ln.strip().startswith("|")]
    rows = []
    for i, ln in enumerate(lines):
        if re.fullmatch(r"\|[\s\-:|]*\|", ln):
            continue
        if i + 1 < len(lines) and re.fullmatch(r"\|[\s\-:|]*\|", lines[i + 1]):
            continue
        rows.append([c.strip() for c in ln.strip("|").split("|")])
    return rows


def read_csv(study, name):
    path = os.path.join(RESULTS, study, name)
    if not os.path.exists(path):
        raise MapError(f"study '{study}': extractor needs results/{study}/{name}, which does not exist")
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def need(study, data, key):
    if key not in data:
        raise MapError(f"study '{study}': extractor needs key '{key}' in results/{study}/summary.json")
    return data[key]


def names(items):
    return ", ".join(items) if items else "none"


def benchmarks(study, name="benchmark.json"):
    path = os.path.join(RESULTS, study, name)
    if not os.path.exists(path):
        raise MapError(f"study '{study}': extractor needs results/{study}/{name}, which does not exist")
    with open(path, encoding="utf-8") as f:
        return json.load(f)["benchmarks"]


UNIT_SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


# ------------------------------------------------------------------------------------------------------ extractors
# Each takes (study, data) where data is the study's summary.json (an empty dict if it has none) and returns a dict
# of further placeholder values. Named in studies/index.toml (field `extract`).

def swegle_verdicts(study, data, table_key="stability_table", xi_key="xi_list"):
    """Per formulation, the ξ at which the Swegle verdict table's class (the first word of a cell,
    growth/stability_verdict.hpp) is semi-discrete growth, U or B: in compression (ξ < 1), at rest (ξ = 1) and in
    tension (ξ > 1); the formulations with an integrator-only (I) cell; those S at every ξ."""
    xis = [float(x) for x in need(study, data, xi_key).split(",")]
    comp, rest, tens, integrator, stable = [], [], [], [], []
    for row in md_rows(need(study, data, table_key)):
        form = row[0].replace("**", "")
        cells = row[1:]
        if len(cells) != len(xis):
            raise MapError(f"study '{study}': {table_key} row '{form}' has {len(cells)} verdicts for "
                           f"{len(xis)} values of xi")
        classes = [c.replace("**", "").split()[0] if c.strip() else "" for c in cells]
        unstable = [xi for xi, c in zip(xis, classes) if c in ("U", "B")]
        if any(xi < 1 for xi in unstable):
            comp.append(form)
        if any(xi == 1 for xi in unstable):
            rest.append(form)
        if any(xi > 1 for xi in unstable):
            tens.append(form)
        if "I" in classes:
            integrator.append(form)
        if all(c == "S" for c in classes):
            stable.append(form)
    return {"unstable_compression": names(comp), "unstable_at_rest": names(rest),
            "unstable_tension": names(tens), "integrator_only": names(integrator), "stable_everywhere": names(stable)}


def threshold(x):
    """A critical load as the map shows it: infinite means no instability up to the search limit."""
    return "none up to the search limit" if math.isinf(x) else g3(x)


def critical_stress_rate_form(study, data):
    """Basic SPH (rate form, cubic) at h = 1.3 dx in both directions from bar_1d.csv and block_2d.csv; how many 1D
    cases of NCSPH (row form) and C_ij are stable to the search limit."""
    out = {}
    bar = read_csv(study, "bar_1d.csv")
    block = read_csv(study, "block_2d.csv")
    for direction in ("tension", "compression"):
        rows = [r for r in bar if r["kernel"] == "cubic" and float(r["h_over_dx"]) == 1.3
                and r["direction"] == direction and r["formulation"] == "sph"]
        if len(rows) != 1:
            raise MapError(f"study '{study}': bar_1d.csv has {len(rows)} rows for cubic sph h/dx = 1.3 {direction}")
        out[f"bar_sph_{direction}"] = threshold(float(rows[0]["stress_over_modulus"]))
        rows = [r for r in block if float(r["h_over_dx"]) == 1.3 and r["direction"] == direction
                and r["formulation"] == "sph"]
        if len(rows) != 1:
            raise MapError(f"study '{study}': block_2d.csv has {len(rows)} rows for sph h/dx = 1.3 {direction}")
        out[f"square_sph_{direction}"] = threshold(float(rows[0]["stress_over_modulus"]))
    corr = [r for r in bar if r["formulation"] in ("ncsph", "cij")]
    out["corrected_cases"] = str(len(corr))
    out["corrected_stable"] = str(sum(math.isinf(float(r["stress_over_modulus"])) for r in corr))
    out["kernels_1d"] = str(len({r["kernel"] for r in bar}))
    return out


def dispersion_rate_form(study, data):
    """From growth_table (formulation | h/dx | ξ | growth | k | mode): the formulations with a growing branch in
    compression (ξ < 1) and in tension (ξ > 1) at every tabled h, and the neutral ones."""
    comp, tens, neutral = {}, {}, {}
    hs = set()
    for form, h, xi, growth, *_ in md_rows(need(study, data, "growth_table")):
        hs.add(h)
        g = num(growth)
        target = comp if float(xi) < 1 else tens
        target.setdefault(form, []).append(g > 0)
        neutral.setdefault(form, []).append(g == 0)
    return {"h_values": " and ".join(sorted(hs)),
            "grow_compression": names([f for f, v in comp.items() if all(v)]),
            "grow_tension": names([f for f, v in tens.items() if all(v)]),
            "neutral": names([f for f, v in neutral.items() if all(v)])}


def critical_strain_2d(study, data):
    """The conservative form on the square lattice, cubic spline, h = 1.3 dx (table_conservative)."""
    for row in md_rows(need(study, data, "table_conservative")):
        if row[0] == "square" and row[1] == "cubic" and num(row[2]) == 1.3:
            return {"sq13_tension": row[3], "sq13_tension_k": row[4], "sq13_compression": row[6],
                    "sq13_compression_k": row[7]}
    raise MapError(f"study '{study}': table_conservative has no row square | cubic | 1.3")


def artificial_stress(study, data):
    """Counts the verdict_N keys (GMS's statements, numbered as in summary.md): confirmed and the others."""
    verdicts = {int(k.split("_")[1]): v for k, v in data.items() if re.fullmatch(r"verdict_\d+", k)}
    if not verdicts:
        raise MapError(f"study '{study}': no verdict_N keys in results/{study}/summary.json")
    confirmed = [n for n, v in sorted(verdicts.items()) if v.startswith("**confirmed**")]
    other = [str(n) for n, v in sorted(verdicts.items()) if not v.startswith("**confirmed**")]
    return {"statements": str(len(verdicts)), "confirmed": str(len(confirmed)), "not_confirmed": names(other)}


def swegle_nonlinear(study, data):
    """From size_table (formulation | ξ | growth at 9 ... 21 per side): the growth of basic SPH at the smallest and
    largest block in compression and tension."""
    out = {}
    for row in md_rows(need(study, data, "size_table")):
        form, xi = row[0].replace("**", ""), row[1]
        if form == "sph":
            key = "compression" if float(xi) < 1 else "tension"
            out[f"sph_{key}_xi"] = xi
            out[f"sph_{key}_smallest"] = row[2]
            out[f"sph_{key}_largest"] = row[-1]
    if len(out) != 6:
        raise MapError(f"study '{study}': size_table lacks sph rows in compression and tension")
    stable_at_rest = [r[0].replace("**", "") for r in md_rows(need(study, data, "table"))]
    out["table_rows"] = str(len(stable_at_rest))
    return out


def tl_neo_hookean_2d(study, data):
    """Largest |SPH − analytic (5.5)| over the table's three stretch paths."""
    errs = [abs(num(r[6])) for r in md_rows(need(study, data, "table"))]
    return {"worst_percent": g3(max(errs)), "points": str(len(errs))}


def tl_bar_wave_1d(study, data):
    """Largest stress error at the fixed end (max err 0.15, kPa) per method and resolution (fixed_end)."""
    by = {}
    for method, n, _, _, end in md_rows(need(study, data, "fixed_end")):
        by.setdefault(method, []).append((int(n), end))
    out = {}
    for method, vals in by.items():
        vals.sort()
        out[f"end_{method}"] = "/".join(v for _, v in vals)
        out["resolutions"] = "/".join(str(n) for n, _ in vals)
    return out


def tl_density_step(study, data):
    """Largest |measured − impedance value| of the four coefficients over the table (value in parentheses, then
    the deviation)."""
    devs = []
    for row in md_rows(need(study, data, "table")):
        for cell in row[3:]:
            m = re.search(r"\(([-+0-9.e]+), ([0-9.e-]+)\)", cell)
            if not m:
                raise MapError(f"study '{study}': cannot read a coefficient from '{cell}'")
            devs.append(float(m.group(2)))
    return {"worst_deviation": g3(max(devs)), "coefficients": str(len(devs))}


def tl_time_step(study, data):
    """The verdict of each run (runs table: run | Δt | Δt/limit | ... | verdict)."""
    return {"run_verdicts": "; ".join(f"{r[0]}: {r[-1]}" for r in md_rows(need(study, data, "runs")))}


def tl_instability(study, data):
    """Largest growth rate per form over the four sets (cases table: set | form | ... | γ (1/s) ...)."""
    out = {}
    for row in md_rows(need(study, data, "cases")):
        key = "gamma_" + row[1].replace("-", "_")
        out[key] = g3(max(num(row[6]), num(out.get(key, "0"))))
        if row[0] == "beam" and row[1] == "ncsph":
            out["beam_ncsph_asymmetry"] = row[4]
        if row[0] == "periodic" and row[1] == "ncsph":
            out["periodic_ncsph_gamma"] = row[6]
    return out


def tl_csm3(study, data):
    """The finest run's error and the extrapolated error of each CSM3 quantity (order table)."""
    out = {}
    for row in md_rows(need(study, data, "order")):
        key = row[0].replace(" ", "_")
        out[f"{key}_finest"] = row[3]
        out[f"{key}_reference"] = row[4]
        out[f"{key}_err_extrapolated"] = row[8]
    return out


def tl_csm3_hourglass(study, data):
    """The lift of the softest zigzag mode and the shift of the fundamental at the largest c_HG, per resolution and
    form (lift table: across | form | c_HG | ... | lift | ... | shift | ...)."""
    last = {}
    for row in md_rows(need(study, data, "lift")):
        if num(row[5]) is not None and row[5] != "-":
            last[(row[0], row[1])] = row  # the largest c_HG whose softest zigzag mode was found
    parts = [f"{a} across {form}: c_HG = {r[2]} lifts it {r[5]}×, fundamental {r[8]}" for (a, form), r in last.items()]
    return {"largest_lift": "; ".join(parts)}


def tl_plate_hole(study, data):
    """Peak hoop stress over S of the finest linear run, and Ismail's case at the finest resolution (ismail)."""
    lin = md_rows(need(study, data, "linear"))
    fin = max(lin, key=lambda r: int(r[0]))
    ism = md_rows(need(study, data, "ismail"))
    top = max(int(r[1]) for r in ism)
    # Columns of the linear table: a/dx, W/a, particles, Newton, residual, sum f, peak/S, r/a, theta, Kirsch there,
    # edge/S, Heywood, ...
    return {"finest_a": fin[0], "finest_peak": fin[6], "finest_r": fin[7], "kirsch": fin[9], "heywood": fin[11],
            **{f"ismail_{r[0].replace('-', '_')}_mpa": r[6] for r in ism if int(r[1]) == top},
            "ismail_a": str(top)}


def nrbc_1d(study, data):
    """The number of Table 2.1 cells whose X pattern is compared: the truncated rows × columns of table_half (the
    Reference row is not part of the count the driver makes)."""
    rows = [r for r in md_rows(need(study, data, "table_half")) if not r[0].startswith("Reference")]
    return {"cells": str(sum(len(r) - 1 for r in rows))}


def nrbc_2d(study, data):
    """The smallest and largest peak KE deviation per boundary over the scenes (table)."""
    by = {}
    for row in md_rows(need(study, data, "table")):
        if "†" in row[1]:
            continue  # measured against the plain-gradient reference, not the NCSPH one
        if row[4] != "completed":
            by.setdefault(row[1], []).append(math.inf)
            continue
        by.setdefault(row[1], []).append(num(row[5]))
    parts = [f"{b} {g3(min(v))}–{g3(max(v))} %" for b, v in by.items()]
    return {"deviation_by_boundary": "; ".join(parts)}


def nrbc_plane_wave(study, data):
    """Reflected energy per boundary at the coarsest and finest wavelength of table_lambda (normal incidence)."""
    by = {}
    for cond, lam, status, measured, _ in md_rows(need(study, data, "table_lambda")):
        by.setdefault(cond, []).append((float(lam), measured))
    parts = []
    for cond, vals in by.items():
        vals.sort()
        parts.append(f"{cond} {vals[0][1]} (λ = {g3(vals[0][0])} Δx) → {vals[-1][1]} (λ = {g3(vals[-1][0])} Δx)")
    return {"reflected": "; ".join(parts)}


def critical_strain_large(study, data):
    """The default variant of results.csv at its largest n: wall time on 1 and 2 threads, peak memory; the range of
    block steps over all n; the SciPy eigsh agreement (scipy_eigsh.csv)."""
    rows = [r for r in read_csv(study, "results.csv") if r["status"] == "successful" and r["variant"] == "default"]
    nmax = max(int(r["n"]) for r in rows)
    top = {r["threads"]: r for r in rows if int(r["n"]) == nmax}
    if set(top) != {"1", "2"}:
        raise MapError(f"study '{study}': results.csv lacks default runs on 1 and 2 threads at n = {nmax}")
    its = [int(r["iterations"]) for r in rows]
    sc = read_csv(study, "scipy_eigsh.csv")
    return {"n": str(nmax), "dofs": top["2"]["dofs"], "seconds_2": g3(float(top["2"]["total_s"])),
            "seconds_1": g3(float(top["1"]["total_s"])),
            "peak_gb": g3(max(float(r["peak_rss_MB"]) for r in top.values()) / 1024),
            "iterations": f"{min(its)}–{max(its)}",
            "eigsh_rel_diff": g3(max(float(r["rel_diff"]) for r in sc)),
            "eigsh_n": f"{min(int(r['n']) for r in sc)}–{max(int(r['n']) for r in sc)}"}


def critical_strain_3d(study, data):
    """The largest n of results.csv: wall time, peak memory, block steps; agreement with the direct route."""
    rows = [r for r in read_csv(study, "results.csv") if r["status"] == "successful"
            and r["variant"].startswith("--dim 3")]
    nmax = max(int(r["n"]) for r in rows)
    top = min((r for r in rows if int(r["n"]) == nmax), key=lambda r: float(r["total_s"]))
    its = [int(r["iterations"]) for r in rows]
    ref = [float(r["rel_diff_reference"]) for r in rows if r["rel_diff_reference"] != "nan"]
    return {"n": str(nmax), "dofs": top["dofs"], "minutes": g3(float(top["total_s"]) / 60),
            "peak_gb": g3(float(top["peak_rss_MB"]) / 1024), "iterations": f"{min(its)}–{max(its)}",
            "direct_rel_diff": g3(max(ref)) if ref else "not compared"}


def critical_strain_petsc(study, data):
    """PETSc against the direct route: largest relative difference in e_crit at equal n; CPU time per route at
    n = 128 and at the largest PETSc n."""
    rows = read_csv(study, "results.csv")
    direct = {r["n"]: float(r["e_crit"]) for r in rows if r["route"] == "direct" and r["status"] == "successful"}
    petsc = [r for r in rows if r["route"] == "petsc" and r["status"] == "successful"]
    diffs = [abs(float(r["e_crit"]) / direct[r["n"]] - 1) for r in petsc if r["n"] in direct]
    out = {"rel_diff": g3(max(diffs)), "compared": str(len(diffs))}
    for route in ("direct", "matrix-free", "petsc"):
        at = [r for r in rows if r["route"] == route and r["n"] == "128" and r["status"] == "successful"]
        out[f"cpu128_{route.replace('-', '_')}"] = g3(min(float(r["cpu_s"]) for r in at)) if at else "not run"
    nmax = max(int(r["n"]) for r in petsc)
    top = [r for r in petsc if int(r["n"]) == nmax]
    out["petsc_n"] = str(nmax)
    out["petsc_cpu"] = g3(min(float(r["cpu_s"]) for r in top))
    out["petsc_gb"] = g3(min(float(r["peak_rss_mb_sum"]) for r in top) / 1024)
    return out


def assembly_speed(study, data):
    """Pair entries per second (default pages), range over N and h: re-assembly into existing storage
    (ReassembleWG) and fresh assembly (AssembleWG)."""
    rows = [r for r in read_csv(study, "assembly.csv") if r["mode"] == "default"]
    out = {}
    for bench, key in (("ReassembleWG", "existing"), ("AssembleWG", "fresh")):
        rates = [float(r["pair_entries_per_s"]) for r in rows if r["benchmark"] == bench]
        if not rates:
            raise MapError(f"study '{study}': assembly.csv has no default {bench} rows")
        out[f"{key}_min"], out[f"{key}_max"] = g3(min(rates)), g3(max(rates))
    ns = [int(r["particles"]) for r in rows]
    out["n_min"], out["n_max"] = g3(float(min(ns))), g3(float(max(ns)))
    return out


def stepping_speed(study, data):
    """At the largest N: particle-steps/s of the TL SpMV, its ratio to the pair loop and its fraction of the copy
    bandwidth; how much slower the UL re-assembly is."""
    rows = read_csv(study, "stepping_speed.csv")
    nmax = max(int(r["particles"]) for r in rows)
    at = {r["variant"]: r for r in rows if int(r["particles"]) == nmax}
    for v in ("TL_SpMV", "UL_Reassembly"):
        if v not in at:
            raise MapError(f"study '{study}': stepping_speed.csv has no {v} row at N = {nmax}")
    tl = at["TL_SpMV"]
    return {"n": g3(float(nmax)), "tl_rate": g3(float(tl["particle_steps_per_s"])),
            "tl_over_pairs": g3(float(tl["ratio_to_pair_loop"])),
            "tl_bandwidth": g3(100 * float(tl["fraction_of_copy_bandwidth"])),
            "ul_slower": g3(float(tl["particle_steps_per_s"]) / float(at["UL_Reassembly"]["particle_steps_per_s"]))}


def jacobian_speed(study, data):
    """Per family: colours and the Jacobian's cost in real force evaluations over n (jacobian.csv)."""
    by = {}
    for r in read_csv(study, "jacobian.csv"):
        by.setdefault(r["family"], []).append(r)
    parts = []
    for fam, rows in by.items():
        cost = [float(r["ratio_to_real_force"]) for r in rows]
        col = sorted({int(r["colours"]) for r in rows})
        ns = [int(r["n"]) for r in rows]
        parts.append(f"{fam}: {col[0]}–{col[-1]} colours, {g3(min(cost))}–{g3(max(cost))} force evaluations "
                     f"(n = {min(ns)}–{max(ns)})" if len(col) > 1 else
                     f"{fam}: {col[0]} colours, {g3(min(cost))}–{g3(max(cost))} force evaluations "
                     f"(n = {min(ns)}–{max(ns)})")
    return {"by_family": "; ".join(parts)}


def gms_speed(study, data):
    """µs per particle-step of the whole 300-step SI rings run: rows with 2 rate evaluations, and the fastest
    configuration (best of the repetitions)."""
    bench = benchmarks(study)
    out = {}
    configs = {"rows_two": "Run/RingsSI/iterations", "pairs_two": "Run/RingsSI/pairs/iterations",
               "rows_one": "RunOneRate/RingsSI/iterations", "pairs_one": "RunOneRate/RingsSI/pairs/iterations"}
    for key, prefix in configs.items():
        t, b = best_time_exact(study, bench, prefix)
        out[key] = g3(t * UNIT_SECONDS[b["time_unit"]] / (b["particles"] * b["steps"]) * 1e6)
    fastest = min((b for b in bench if b.get("run_type") == "iteration" and b["name"].startswith("Run")),
                  key=lambda b: b["real_time"] * UNIT_SECONDS[b["time_unit"]] / (b["particles"] * b["steps"]))
    out["fastest"] = g3(fastest["real_time"] * UNIT_SECONDS[fastest["time_unit"]]
                        / (fastest["particles"] * fastest["steps"]) * 1e6)
    out["fastest_name"] = fastest["name"].split("/iterations")[0]
    out["particles"] = str(int(fastest["particles"]))
    return out


def best_time_exact(study, bench, prefix):
    """Best real time of the benchmarks whose name starts with prefix (e.g. 'Run/RingsSI/iterations')."""
    runs = [b for b in bench if b.get("run_type") == "iteration" and b["name"].startswith(prefix)]
    if not runs:
        raise MapError(f"study '{study}': no benchmark named {prefix}... in its benchmark.json")
    best = min(runs, key=lambda b: b["real_time"])
    return best["real_time"], best


def rate_form_speed(study, data):
    """CPU µs per particle-step of the library's fused rate evaluation and of the operator route at the largest N
    (best of the repetitions, h = 1.3 and 1.5)."""
    bench = benchmarks(study)
    nmax = max(int(b["particles"]) for b in bench if b["name"].startswith("Fused/"))
    out = {"n": g3(float(nmax))}
    for route in ("Fused", "Operator"):
        vals = [b["cpu_time"] * UNIT_SECONDS[b["time_unit"]] / b["particles"] * 1e6 for b in bench
                if b.get("run_type") == "iteration" and b["name"].startswith(route + "/")
                and int(b["particles"]) == nmax]
        if not vals:
            raise MapError(f"study '{study}': no {route}/ benchmark at N = {nmax}")
        out[route.lower()] = f"{g3(min(vals))}–{g3(max(vals))}"
    return out


def tl_step_speed(study, data):
    """Per-particle-step speed of the whole TL step: range of particle-steps/s and of the ratio to the bandwidth
    bound over all Step benchmarks (best repetition each)."""
    bench = [b for b in benchmarks(study) if b.get("run_type") == "iteration" and b["name"].startswith("Step/")]
    if not bench:
        raise MapError(f"study '{study}': no Step/ benchmark in its benchmark.json")
    best = {}
    for b in bench:
        key = b["name"]
        if key not in best or b["particle_steps_per_s"] > best[key]["particle_steps_per_s"]:
            best[key] = b
    rates = [b["particle_steps_per_s"] for b in best.values()]
    ratios = [b["bound_ratio"] for b in best.values()]
    ns = [b["particles"] for b in best.values()]
    return {"rate_min": g3(min(rates)), "rate_max": g3(max(rates)), "bound_min": g3(min(ratios)),
            "bound_max": g3(max(ratios)), "n_min": g3(float(min(ns))), "n_max": g3(float(max(ns))),
            "cases": str(len(best))}


EXTRACTORS = {f.__name__: f for f in (
    swegle_verdicts, critical_stress_rate_form, dispersion_rate_form, critical_strain_2d, artificial_stress,
    swegle_nonlinear, tl_neo_hookean_2d, tl_bar_wave_1d, tl_density_step, tl_time_step, tl_instability, tl_csm3,
    tl_csm3_hourglass, tl_plate_hole, nrbc_1d, nrbc_2d, nrbc_plane_wave, critical_strain_large, critical_strain_3d,
    critical_strain_petsc, assembly_speed, stepping_speed, jacobian_speed, gms_speed, rate_form_speed,
    tl_step_speed)}


# --------------------------------------------------------------------------------------------------------- the map
# One reader of studies/index.toml (validated) and of results/timings.csv: the main job's engine.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_studies import load_index, load_timings  # noqa: E402


def headline(name, entry):
    """The study's headline template filled from its summary.json and its extractor's values."""
    path = os.path.join(RESULTS, name, "summary.json")
    data = {}
    if os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    values = dict(data)
    if "extract" in entry:
        if entry["extract"] not in EXTRACTORS:
            raise MapError(f"study '{name}': unknown extractor '{entry['extract']}' (studies/index.toml)")
        values.update(EXTRACTORS[entry["extract"]](name, data))

    def fill(m):
        key = m.group(1)
        if key not in values:
            src = f"results/{name}/summary.json" if os.path.exists(path) else f"results/{name}/ (no summary.json)"
            via = f" nor its extractor {entry['extract']}" if "extract" in entry else ""
            raise MapError(f"study '{name}': headline key '{key}' is not in {src}{via}")
        value = str(values[key]).strip()
        if value == "":
            raise MapError(f"study '{name}': headline key '{key}' is empty in {path}")
        return value

    text = re.sub(r"\{([^{}]+)\}", fill, entry["headline"])
    return " ".join(text.split())


def wall(name, timings):
    row = timings.get(name)
    if not row or not row.get("wall_s"):
        return "not yet timed"
    s = float(row["wall_s"])
    text = f"{s:.1f} s" if s < 10 else f"{s:.0f} s" if s < 120 else f"{s / 60:.0f} min"
    return f"{text} ({row['date']})" if row.get("date") else text


def cell(text):
    return text.replace("|", "\\|").replace("\n", " ")


def render():
    index = load_index()
    timings = load_timings()
    for name, entry in index.items():
        missing = [k for k in REQUIRED if k not in entry]
        if missing:
            raise MapError(f"study '{name}': studies/index.toml lacks {', '.join(missing)}")
        if entry["family"] not in FAMILIES:
            raise MapError(f"study '{name}': unknown family '{entry['family']}'")
    out = ["# Results map", "",
           "Generated by `scripts/results_map.py` from `studies/index.toml` (question, sources, headline template), "
           "each study's `results/<name>/summary.json` (or, for the benchmark folders, its CSV/JSON through a named "
           "extractor in the script) and `results/timings.csv`. Do not edit by hand: "
           "`/usr/bin/python3 scripts/results_map.py` rewrites it, `--check` tests that it is current (ctest label "
           "`results`).", "",
           "`results/<name>/` holds what the study `studies/<name>/` last computed: CSV, PNG, `summary.json` and "
           "`summary.md` (parameters, key numbers, wall time and the point-by-point comparison with its sources). "
           "`bash scripts/main.sh` runs the default main job (the studies marked *full* below, in full, and those "
           "marked *quick* as their `--quick` case into `build/quick/`, leaving results/ untouched); "
           "`bash scripts/main.sh --all` regenerates every folder; `bash scripts/main.sh NAME...` the named ones. "
           "Every run rewrites this page.", "",
           "Each headline is the study's main finding with its numbers filled in from the data; the summary behind "
           "the link gives the method, the caveats and the rest. Sources are keys of "
           "[docs/references.md](../docs/references.md).", ""]
    families = [f for f in FAMILIES if any(e["family"] == f for e in index.values())]
    out.append("Families: " + ", ".join(f"[{f}](#{f.lower().replace(' ', '-')})" for f in families) + ".")
    out.append("")
    for family in families:
        out += [f"## {family}", "",
                "| study | question | headline finding (from its data) | sources | wall time | main job | summary |",
                "|---|---|---|---|---|---|---|"]
        for name, entry in index.items():
            if entry["family"] != family:
                continue
            link_name = entry.get("summary", "summary.md")
            if not os.path.exists(os.path.join(RESULTS, name, link_name)):
                raise MapError(f"study '{name}': results/{name}/{link_name} does not exist")
            main = {"full": "full", "quick": "quick"}.get(entry.get("main"), "no (`--all`)")
            out.append("| " + " | ".join(cell(c) for c in (
                f"`{name}`", entry["question"], headline(name, entry), entry["sources"], wall(name, timings), main,
                f"[{link_name}]({name}/{link_name})")) + " |")
        out.append("")
    return "\n".join(out)


def main(argv):
    check = "--check" in argv[1:]
    unknown = [a for a in argv[1:] if a != "--check"]
    if unknown:
        sys.exit(f"results_map: unknown argument(s) {' '.join(unknown)} (usage: results_map.py [--check])")
    try:
        text = render()
    except MapError as e:
        print(f"results_map: error: {e}", file=sys.stderr)
        return 1
    if check:
        current = open(OUT, encoding="utf-8").read() if os.path.exists(OUT) else None
        if current != text:
            print("results_map: results/README.md is stale (or missing): run /usr/bin/python3 "
                  "scripts/results_map.py", file=sys.stderr)
            return 1
        return 0
    with open(OUT, "w", encoding="utf-8") as f:
        f.write(text)
    print(f"results_map: wrote {os.path.relpath(OUT, ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
