"""Figure 4: Barnes-Hut interactions per body against n for several theta, and n - 1 (direct sum).
`fig_nbody.py fig4_nbody.csv OUT.png`."""
import sys

from common import plt, read_csv, save

rows = read_csv(sys.argv[1])
fig, ax = plt.subplots(figsize=(7, 5))
thetas = sorted({r["theta"] for r in rows})
cmap = plt.get_cmap("viridis")
for i, theta in enumerate(thetas):
    pts = sorted((r["n"], r["mean_interactions"]) for r in rows if r["theta"] == theta)
    ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", color=cmap(i / max(1, len(thetas) - 1)),
            label="Barnes-Hut theta = %g" % theta)
ns = sorted({r["n"] for r in rows})
ax.plot(ns, [n - 1 for n in ns], "--", color="gray", label="direct sum: n - 1")
ax.set_xscale("log")
ax.set_yscale("log")
ax.set_xlabel("bodies n")
ax.set_ylabel("interactions per body (mean)")
ax.set_title("The N-body analogy: interactions per body")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8)
save(fig, sys.argv[2])
