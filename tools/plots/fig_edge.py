"""Figure 2: the hierarchical mesh of two surfaces meeting along an edge, and element size against
distance to the edge. `fig_edge.py fig2_edge.csv OUT.png MESH.png [SUBTITLE]`."""
import sys

import matplotlib.image as mpimg

from common import plt, read_csv, save

rows = read_csv(sys.argv[1])
fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5.5))
left.imshow(mpimg.imread(sys.argv[3]))
left.set_axis_off()
left.set_title("hierarchical elements" + (": " + sys.argv[4] if len(sys.argv) > 4 else ""), fontsize=9)
for patch, colour in ((0, "#1f77b4"), (1, "#d62728")):
    pts = [(r["distance"], r["size"]) for r in rows if int(r["patch"]) == patch]
    if pts:
        right.scatter([p[0] for p in pts], [p[1] for p in pts], s=6, color=colour, alpha=0.6,
                      label="patch %d" % patch)
right.set_xscale("log")
right.set_yscale("log")
right.set_xlabel("distance of the element's centroid to the common edge")
right.set_ylabel("element size sqrt(area)")
right.set_title("Refined near the edge, coarse far from it")
right.grid(True, which="both", alpha=0.3)
right.legend(fontsize=8)
fig.tight_layout()
save(fig, sys.argv[2])
