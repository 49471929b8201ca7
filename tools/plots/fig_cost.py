"""Figure 1: measured work against elements, log-log, one panel per measure, with the fitted slopes.
`fig_cost.py fig1_cost.csv OUT.png [fig1_cost_fit.json]`."""
import json
import sys

from common import COLORS, plt, read_csv, save

rows = read_csv(sys.argv[1])
fits = {}
if len(sys.argv) > 3:
    with open(sys.argv[3]) as f:
        fits = json.load(f).get("methods", {}) or {}
measures = [
    ("factor_evaluations", "form factors evaluated (element + point)",
     lambda r: r["element_factor_evaluations"] + r["point_factor_evaluations"]),
    ("gather_terms", "terms per gather iteration", lambda r: r["gather_terms"]),
    ("segment_queries", "visibility rays", lambda r: r["segment_queries"]),
    ("seconds", "seconds", lambda r: r["seconds"]),
]
labels = {"full": "full matrix", "substructure": "substructuring (N input polygons shoot)",
          "hierarchical": "hierarchical"}
fig, axes = plt.subplots(2, 2, figsize=(11, 8))
for ax, (key, title, value) in zip(axes.flat, measures):
    all_n = []
    for method in ("full", "substructure", "hierarchical"):
        pts = sorted((r["elements"], value(r)) for r in rows if r["method"] == method and value(r) > 0)
        if not pts:
            continue
        all_n += [p[0] for p in pts]
        label = labels[method]
        fit = (fits.get(method) or {}).get(key)
        if fit:
            label += ": slope %.2f" % fit["b"]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", color=COLORS[method], label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("elements n")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
fig.suptitle("Measured work against elements: Cornell box (fitted power laws in fig1_cost_fit.json)")
fig.tight_layout()
save(fig, sys.argv[2])
