"""Headline claims of gms-slab-ensemble (results/gms-slab-ensemble/), run by tests/scripts/claims_test.py."""
import math

from claims import approx, check, md_table, one, select


def _members(r, eps):
    return select(r.csv("runs.csv"), eps=eps)


def _member(row):
    return row["tag"].rsplit("_", 1)[1]


def _range(values, decimals):
    values = [v for v in values if not (isinstance(v, float) and math.isnan(v))]
    if not values:
        return "-"
    lo, hi = f"{min(values):.{decimals}f}", f"{max(values):.{decimals}f}"
    return lo if lo == hi else f"{lo}–{hi}"


def claim_reference_member_is_gms_slabs_run(r):
    """The `rows` member of each eps is gms-slab's committed run at the same dp (neck, break, cracks, crack place)."""
    dp = r.num("dp")
    found = []
    for eps in (0.3, 0.0):
        mine = one(r.csv("runs.csv"), tag=f"dp{dp:g}_eps{eps:g}_rows")
        theirs = one(r.other("gms-slab").csv("runs.csv"), dp=dp, eps=eps)
        for col in ("t_neck", "t_break", "cracks", "x_crack_left", "x_crack_right", "junction_distance_left"):
            a, b = mine[col], theirs[col]
            check((isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b)) or a == b,
                  f"{mine.where()} {col} {a} vs {theirs.where()} {b}")
        found.append(f"eps {eps:g}: break {mine['t_break']}")
    return "; ".join(found) + " = gms-slab"


def claim_counts_and_ranges_are_runs_csv(r):
    """The members, the reference's break and cracks, the counts (same cracks, necked before the break, cracks in the
    middle third) and the spreads of the summary are recomputed from runs.csv."""
    found = []
    for eps, k in ((0.3, "eps03_"), (0.0, "eps0_")):
        rows = _members(r, eps)
        ref = next(x for x in rows if _member(x) == "rows")
        check(r.num(k + "members") == len(rows), f"{k}members {r.key(k + 'members')}, runs.csv {len(rows)}")
        check(r.num(k + "ref_cracks") == ref["cracks"], f"{k}ref_cracks")
        approx(r.num(k + "ref_t_break"), ref["t_break"], f"{k}ref_t_break", rel=1e-3)
        same = sum(x["cracks"] == ref["cracks"] for x in rows)
        necked = sum(not math.isnan(x["t_neck"]) and not math.isnan(x["t_break"]) and x["t_neck"] < x["t_break"]
                     for x in rows)
        middle = sum(abs(x["position_left"] - 0.5) < 1 / 6 and abs(x["position_right"] - 0.5) < 1 / 6 for x in rows)
        for key, want in (("same_cracks", same), ("necked_before_break", necked), ("middle_cracks", middle)):
            check(r.num(k + key) == want, f"{k}{key} {r.key(k + key)}, runs.csv {want}")
        for key, col, dec in (("t_break_range", "t_break", 0), ("t_neck_range", "t_neck", 0),
                              ("crack_x_range", "x_crack_left", 3)):
            want = _range([x[col] for x in rows], dec)
            check(r.key(k + key) == want, f"{k}{key} '{r.key(k + key)}', runs.csv '{want}'")
        want = _range([min(x["junction_distance_left"], x["junction_distance_right"]) for x in rows], 3)
        check(r.key(k + "junction_range") == want, f"{k}junction_range '{r.key(k + 'junction_range')}', '{want}'")
        found.append(f"eps {eps:g}: {same}/{len(rows)} same cracks, {necked} necked, {middle} middle")
    return "; ".join(found)


def claim_members_table_is_runs_csv(r):
    """The members table lists every runs.csv row (member, break time, cracks)."""
    rows, table = r.csv("runs.csv"), md_table(r.key("members_table"))
    check(len(table) == len(rows), f"members table {len(table)} rows, runs.csv {len(rows)}")
    for cells, x in zip(table, rows):
        check(cells[1] == _member(x) and cells[4] == str(x["cracks"]), f"{x.where()}: table row {cells}")
    return f"{len(table)} rows = runs.csv"
