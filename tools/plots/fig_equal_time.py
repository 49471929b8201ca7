"""Figure 6: a 2 x 3 montage: the Cornell box by each method (top) and its error (bottom).
`fig_equal_time.py fig6_equal_time.csv OUT.png ERROR_HI`; the images sit beside the CSV."""
import os
import sys

import matplotlib.image as mpimg

from common import plt, read_csv, save

all_rows = read_csv(sys.argv[1])
rows = [r for r in all_rows if r["method"] != "reference"]
reference = next((r for r in all_rows if r["method"] == "reference"), None)
folder = os.path.dirname(os.path.abspath(sys.argv[1]))
fig, axes = plt.subplots(2, len(rows), figsize=(4 * len(rows), 8.4), squeeze=False)
for col, r in enumerate(rows):
    top, bottom = axes[0][col], axes[1][col]
    top.imshow(mpimg.imread(os.path.join(folder, r["image"])))
    top.set_title("%s: %d elements, %.2f s (%.2gx the budget)" % (r["method"], r["elements"], r["seconds"],
                                                                  r["seconds"] / r["budget_seconds"]), fontsize=9)
    bottom.imshow(mpimg.imread(os.path.join(folder, r["error_image"])))
    bottom.set_title("relative L2 error %.3g (colour bar 0 to %s)" % (r["error_l2"], sys.argv[3]), fontsize=9)
    for ax in (top, bottom):
        ax.set_axis_off()
budget = rows[0]["budget_seconds"] if rows else 0
# Each panel gives its own time; the budget is the hierarchical solve's. The reference is named with its
# size, and said plainly when it is not finer than every run (its "error" is then a difference).
against = "a full-matrix reference"
if reference:
    against = "a %d-element full-matrix reference" % reference["elements"]
    if any(r["elements"] >= reference["elements"] for r in rows):
        against += " (no finer than every run: the errors are differences)"
# "Equal time" only where the measured time is within 1.5x of the budget; a method that could not get there (the
# smallest mesh it allows is slower, or its largest allowed mesh faster) is named with its own time.
missed = [r for r in rows if not (1 / 1.5 <= r["seconds"] / budget <= 1.5)] if budget > 0 else rows
if missed:
    timing = "Each method set toward the hierarchical solve's time (%.2f s), missed by %s" % (
        budget, ", ".join("%s (%.2f s)" % (r["method"], r["seconds"]) for r in missed))
else:
    timing = "Each method at the hierarchical solve's time (%.2f s) within 1.5x" % budget
fig.suptitle("%s; error against %s" % (timing, against), fontsize=10)
fig.tight_layout()
save(fig, sys.argv[2])
