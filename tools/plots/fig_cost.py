"""Figure 1: form factors (links) against elements, log-log, with n^2 and n lines.
`fig_cost.py fig1_cost.csv OUT.png [fig1_cost_fit.json]`."""
import json
import sys

from common import COLORS, plt, read_csv, save

rows = read_csv(sys.argv[1])
fits = {}
if len(sys.argv) > 3:
    with open(sys.argv[3]) as f:
        fits = json.load(f).get("methods", {}) or {}
fig, ax = plt.subplots(figsize=(7, 5))
labels = {"full": "full matrix (n^2)", "substructure": "substructuring (nN)", "hierarchical": "hierarchical (links)"}
all_n = []
for method in ("full", "substructure", "hierarchical"):
    pts = sorted((r["elements"], r["links"]) for r in rows if r["method"] == method and r["links"] > 0)
    if not pts:
        continue
    all_n += [p[0] for p in pts]
    label = labels[method]
    fit = fits.get(method)
    if fit:
        label += " slope %.2f" % fit["b"]
    ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", color=COLORS[method], label=label)
if all_n:
    lo, hi = min(all_n), max(all_n)
    xs = [lo, hi]
    ax.plot(xs, [x * x for x in xs], "--", color="gray", linewidth=0.8, label="n^2")
    ax.plot(xs, [x for x in xs], ":", color="gray", linewidth=0.8, label="n")
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("elements n")
ax.set_ylabel("form factors (links)")
ax.set_title("Form factors against elements: Cornell box")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
save(fig, sys.argv[2])
