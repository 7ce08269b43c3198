"""Headline claims of tl-neo-hookean-2d (results/tl-neo-hookean-2d/), run by tests/scripts/claims_test.py."""
from claims import approx, check, md_table


def claim_centre_stress_within_one_percent(r):
    """The headline's 'centre T11 within worst_percent % of (5.5) at all points tabled stretches': recomputed from
    table.csv (|relative_error| < 1 %, and the largest equals the table's), notes value (where tabled) = analytic to 1e-4."""
    rows = r.csv("table.csv")
    worst = max(abs(x["relative_error"]) for x in rows)
    check(worst < 0.01, f"table.csv: worst relative error {100 * worst:.3g} %")
    table = md_table(r.key("table"))
    check(len(table) == len(rows), f"{len(table)} tabled points, {len(rows)} CSV rows")
    approx(max(abs(float(row[6].replace("%", ""))) for row in table), 100 * worst, "worst % in the table", abs_=0.006)
    for x in (x for x in rows if x["t11_notes_over_mu"] == x["t11_notes_over_mu"]):  # nan: no tabled value
        approx(x["t11_notes_over_mu"], x["t11_analytic_over_mu"], f"{x.where()} notes against (5.5)", abs_=1e-4)
    return f"{len(rows)} points, worst {100 * worst:.2f} %"


def claim_paths_reach_their_stretches(r):
    """Every stretch path completes and ends at lambda_1 = 6 (centre F11 within 0.1 %), lambda_2 as prescribed."""
    for row in md_table(r.key("ends")):
        check(row[3] == "completed", f"path {row[0]} status {row[3]}")
        approx(float(row[4]), 6.0, f"path {row[0]} final F11", rel=1e-3)
    return "3 paths completed at F11 = 6"
