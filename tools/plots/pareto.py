"""Error against time, log-log, one curve per method: `pareto.py SWEEP.csv OUT.png TITLE`."""
import sys

from common import COLORS, plt, read_csv, save

rows = read_csv(sys.argv[1])
fig, ax = plt.subplots(figsize=(7, 5))
for method in ("full", "substructure", "hierarchical"):
    for parameter, marker in (("max_area", "o"), ("patch_area", "s"), ("feps", "o"), ("aeps", "^")):
        pts = sorted((r["seconds"], r["error_l2"]) for r in rows
                     if r["method"] == method and r["parameter"] == parameter and r["error_l2"] > 0)
        if not pts:
            continue
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=marker, color=COLORS[method],
                label="%s (%s)" % (method, parameter), linestyle="-" if marker == "o" else ":")
ax.axhline(0.01, color="gray", linewidth=0.8, linestyle="--")
ax.text(ax.get_xlim()[0], 0.0105, " 1% L2", color="gray", va="bottom")
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("seconds (wall clock)")
ax.set_ylabel("relative L2 error against the reference")
ax.set_title(sys.argv[3] if len(sys.argv) > 3 else "What accuracy costs in time")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
save(fig, sys.argv[2])
