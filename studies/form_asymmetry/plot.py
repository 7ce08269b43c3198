"""Bar chart of the Jacobian asymmetry of each momentum form (reads form_asymmetry.csv, writes form_asymmetry.png)."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

out = sys.argv[1] if len(sys.argv) > 1 else "results/form_asymmetry"
rows = list(csv.DictReader(open(f"{out}/form_asymmetry.csv")))
forms = ["uncorrected", "plus", "minus", "conservative"]
floor = 1e-17  # exact zeros drawn at the floor
fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
for ax, dim in zip(axes, ["1", "2"]):
    sub = [r for r in rows if r["dim"] == dim]
    configs = []
    for r in sub:
        if r["config"] not in configs:
            configs.append(r["config"])
    width = 0.2
    for k, form in enumerate(forms):
        values = [max(floor, float(next(r for r in sub if r["config"] == c and r["form"] == form)["relative_asymmetry"]))
                  for c in configs]
        ax.bar([i + (k - 1.5) * width for i in range(len(configs))], values, width, label=form)
    ax.set_yscale("log")
    ax.set_ylim(floor / 2, 10)
    ax.set_xticks(range(len(configs)))
    ax.set_xticklabels(configs, rotation=25, ha="right", fontsize=8)
    ax.set_title(f"{dim}D: " + ("pre-stressed wave equation" if dim == "1" else "plane-strain elasticity"))
    ax.axhline(1e-15, color="grey", lw=0.8, ls="--")
axes[0].set_ylabel(r"$\|A - A^T\|_F / \|A\|_F$")
axes[1].legend(fontsize=8)
fig.suptitle("Symmetry of the exact Jacobian A = -da/du (dashed: round-off level)")
fig.tight_layout()
fig.savefig(f"{out}/form_asymmetry.png", dpi=150)
print(f"wrote {out}/form_asymmetry.png")
