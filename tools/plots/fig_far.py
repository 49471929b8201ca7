"""Figure 3: two surfaces far apart: k^2 element pairs (full), 2k (substructuring), HR's links.
`fig_far.py fig3_far.csv OUT.png`."""
import sys

from common import COLORS, plt, read_csv, save

rows = read_csv(sys.argv[1])
fig, ax = plt.subplots(figsize=(7, 5))
labels = {"full": "full matrix: element pairs (k^2)", "substructure": "substructuring: factors (2k)",
          "hierarchical": "hierarchical: link pairs"}
for method in ("full", "substructure", "hierarchical"):
    pts = sorted((r["k"], r["cross_pairs"]) for r in rows if r["method"] == method)
    if pts:
        ax.plot([p[0] for p in pts], [max(p[1], 0.5) for p in pts], "o-", color=COLORS[method], label=labels[method])
ks = sorted({r["k"] for r in rows})
if ks:
    ax.plot(ks, [k * k for k in ks], "--", color="gray", linewidth=0.8, label="k^2")
    ax.plot(ks, [2 * k for k in ks], ":", color="gray", linewidth=0.8, label="2k")
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("elements per surface k (finest element size = surface / k)")
ax.set_ylabel("interactions between the two surfaces")
ax.set_title("Two surfaces far apart")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
save(fig, sys.argv[2])
