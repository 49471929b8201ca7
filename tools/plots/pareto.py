"""Error against time, log-log, one curve per method and parameter: `pareto.py SWEEP.csv OUT.png TITLE`.

Left: the error of the element radiosity (the unknowns: constant, or linear for the *_linear methods); then, when the sweep measured them,
the error of the displayed field (column error_l2_smooth: vertex radiosity interpolated linearly) and
of the run's own final gather at the samples (column error_l2_gathered, against the time of the solve
and the gather, gather_seconds)."""
import math
import sys

from common import COLORS, plt, read_csv, save

rows = read_csv(sys.argv[1])
fields = [("error_l2", "element radiosity (the unknowns)", False)]
if rows and "error_l2_smooth" in rows[0]:
    fields.append(("error_l2_smooth", "displayed (interpolated) radiosity", False))
if rows and "error_l2_gathered" in rows[0] and any(not math.isnan(r["error_l2_gathered"]) for r in rows):
    fields.append(("error_l2_gathered", "final gather of the run (solve + gather time)", True))
fig, axes = plt.subplots(1, len(fields), figsize=(7 * len(fields), 5), squeeze=False, sharey=True)
for ax, (column, name, gathered) in zip(axes[0], fields):
    for method in ("full", "substructure", "hierarchical", "full_linear", "substructure_linear", "hierarchical_linear"):
        for parameter, marker in (("max_area", "o"), ("patch_area", "s"), ("feps", "o"), ("aeps", "^")):
            pts = sorted((r["seconds"] + (r["gather_seconds"] if gathered else 0.0), r[column]) for r in rows
                         if r["method"] == method and r["parameter"] == parameter and r[column] > 0)
            if not pts:
                continue
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=marker, color=COLORS[method],
                    label="%s (%s)" % (method, parameter), linestyle="-" if marker == "o" else ":")
    ax.axhline(0.01, color="gray", linewidth=0.8, linestyle="--")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.text(ax.get_xlim()[0], 0.0105, " 1% L2", color="gray", va="bottom")
    ax.set_xlabel("seconds (wall clock)")
    ax.set_title(name, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
axes[0][0].set_ylabel("relative L2 error of B - E against the reference")
axes[0][0].legend(fontsize=8)
fig.suptitle(sys.argv[3] if len(sys.argv) > 3 else "What accuracy costs in time")
save(fig, sys.argv[2])
