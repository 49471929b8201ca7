"""Figure 5: largest relative change per iteration of the three solvers.
`fig_convergence.py fig5_convergence.csv OUT.png`."""
import sys

from common import COLORS, plt, read_csv, save

rows = read_csv(sys.argv[1])
fig, ax = plt.subplots(figsize=(7, 5))
labels = {"full": "full matrix (Jacobi)", "substructure": "substructuring", "hierarchical": "hierarchical"}
for method in ("full", "substructure", "hierarchical"):
    pts = sorted((r["iteration"], r["change"]) for r in rows if r["method"] == method and r["change"] > 0)
    if pts:
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", markersize=3, color=COLORS[method],
                label=labels[method])
ax.set_yscale("log")
ax.set_xlabel("iteration")
ax.set_ylabel("relative change (largest element, reflected power)")
ax.set_title("Convergence on the Cornell box")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
save(fig, sys.argv[2])
