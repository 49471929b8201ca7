"""Writes sweep.ipynb and figures.ipynb (run with Debian's python3: `/usr/bin/python3 make_notebooks.py`).

The notebooks read what `hrad sweep` and `hrad figures` wrote and plot it with pandas and matplotlib:
sweep.ipynb the folder in $HRAD_SWEEP (a user's own `hrad sweep SCENE --out DIR`), figures.ipynb the folder
in $HRAD_FIGURES; by default the committed runs under notebooks_data/experiments/ (or the folder in
$HRAD_EXPERIMENTS)."""
import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

SETUP = """import json
import os
from pathlib import Path

import matplotlib
matplotlib.use("Agg")  # headless (nbconvert); the figures still show inline in Jupyter
import matplotlib.pyplot as plt
import matplotlib.image as mpimg
import pandas as pd
%matplotlib inline

EXPERIMENTS = Path(os.environ.get("HRAD_EXPERIMENTS", "../experiments"))
# One colour per method and basis (rows labelled as `hrad sweep` labels them); others take matplotlib's cycle.
COLORS = {"full": "#d62728", "substructure": "#1f77b4", "hierarchical": "#2ca02c", "full_linear": "#ff7f0e",
          "substructure_linear": "#17becf", "hierarchical_linear": "#9467bd", "hierarchical_leaf": "#8c564b",
          "hierarchical_leaf_linear": "#e377c2"}"""


def notebook(cells):
    nb = new_notebook(cells=cells)
    nb.metadata["kernelspec"] = {"display_name": "Python 3", "language": "python", "name": "python3"}
    nb.metadata["language_info"] = {"name": "python"}
    return nb


sweep = notebook([
    new_markdown_cell("# What accuracy costs in time\n\n"
                      "Reads the folder `hrad sweep` wrote (`sweep.csv`, `fit.json`, `reference.json`, "
                      "`command.txt`): every method run over its accuracy parameter on one scene, each run's "
                      "relative L2 error of B - E against one reference: a full-matrix LU solve, final-gathered "
                      "at the error samples (`reference.json` says how), for the constant element field and for the "
                      "displayed (vertex-interpolated) field."),
    new_code_cell(SETUP + '\n# The sweep to plot: set HRAD_SWEEP to the folder of your own `hrad sweep SCENE --out DIR`.\n'
                  'DIR = Path(os.environ.get("HRAD_SWEEP", EXPERIMENTS / "sweep_cornell"))\n'
                  'print((DIR / "command.txt").read_text())'),
    new_code_cell('sweep = pd.read_csv(DIR / "sweep.csv")\n'
                  'reference = json.loads((DIR / "reference.json").read_text())\n'
                  'fits = json.loads((DIR / "fit.json").read_text())\n'
                  'print("reference:", reference["elements"], "elements,", round(reference["seconds"], 2), "s")\n'
                  'sweep'),
    new_markdown_cell("## Error against time (the Pareto front)"),
    new_code_cell('columns = [c for c in ("error_l2", "error_l2_smooth") if c in sweep]\n'
                  'fig, axes = plt.subplots(1, len(columns), figsize=(7 * len(columns), 5), squeeze=False, sharey=True)\n'
                  'for ax, column in zip(axes[0], columns):\n'
                  '    for (method, parameter), g in sweep.groupby(["method", "parameter"]):\n'
                  '        g = g.sort_values("seconds")\n'
                  '        ax.plot(g.seconds, g[column], "o-" if parameter in ("max_area", "feps") else "^:",\n'
                  '                color=COLORS.get(method), label=f"{method} ({parameter})")\n'
                  '    ax.set(xscale="log", yscale="log", xlabel="seconds", ylabel="relative L2 error", title=column)\n'
                  '    ax.axhline(0.01, color="gray", lw=0.8, ls="--")\n'
                  '    ax.grid(True, which="both", alpha=0.3)\n'
                  'axes[0][0].legend(fontsize=8)\n'
                  'plt.show()'),
    new_markdown_cell("## Links and time against elements, with the Ceres fits"),
    new_code_cell('fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.5))\n'
                  'for method, g in sweep[sweep.parameter != "patch_area"].groupby("method"):\n'
                  '    g = g.sort_values("elements")\n'
                  '    fit = fits["methods"][method]\n'
                  '    lf, tf = fit.get("links_vs_elements"), fit.get("time_vs_elements")\n'
                  '    a.plot(g.elements, g.links, "o-", color=COLORS.get(method),\n'
                  '           label=method + (f" slope {lf[\'b\']:.2f}" if lf else ""))\n'
                  '    b.plot(g.elements, g.seconds, "o-", color=COLORS.get(method),\n'
                  '           label=method + (f" slope {tf[\'b\']:.2f}" if tf else ""))\n'
                  'for ax, label in ((a, "links (form factors)"), (b, "seconds")):\n'
                  '    ax.set(xscale="log", yscale="log", xlabel="elements", ylabel=label)\n'
                  '    ax.grid(True, which="both", alpha=0.3)\n'
                  '    ax.legend(fontsize=8)\n'
                  'plt.show()\n'
                  'print(json.dumps({k: fits[k] for k in ("speedup", "speedup_smooth") if k in fits}, indent=1))'),
])

figures = notebook([
    new_markdown_cell("# The lecture's figures, measured\n\n"
                      "Reads the folder `hrad figures` wrote: `figN_<name>.csv` behind each figure, the PNGs, "
                      "`headlines.json` and `command.txt`. Each section re-plots one CSV."),
    new_code_cell(SETUP + '\n# The figures to plot: set HRAD_FIGURES to the folder of your own `hrad figures --out DIR`.\n'
                  'DIR = Path(os.environ.get("HRAD_FIGURES", EXPERIMENTS / "figures"))\n'
                  'print((DIR / "command.txt").read_text())\n'
                  'headlines = json.loads((DIR / "headlines.json").read_text())\n'
                  'print(json.dumps(headlines, indent=1))'),
    new_markdown_cell("## 1. Measured work against elements (Cornell box)\n\n"
                      "The lecture: n elements need n^2 form factors; substructuring nN; hierarchical radiosity "
                      "O(n) links at a fixed accuracy. Plotted here: what the solves counted (form factors "
                      "evaluated, terms per gather iteration, visibility rays) and their seconds."),
    new_code_cell('cost = pd.read_csv(DIR / "fig1_cost.csv")\n'
                  'cost["factor_evaluations"] = cost.element_factor_evaluations + cost.point_factor_evaluations\n'
                  'measures = ["factor_evaluations", "gather_terms", "segment_queries", "seconds"]\n'
                  'fig, axes = plt.subplots(2, 2, figsize=(11, 8))\n'
                  'for ax, measure in zip(axes.flat, measures):\n'
                  '    for method, g in cost.groupby("method"):\n'
                  '        g = g.sort_values("elements")\n'
                  '        g = g[g[measure] > 0]\n'
                  '        ax.plot(g.elements, g[measure], "o-", color=COLORS.get(method), label=method)\n'
                  '    ax.set(xscale="log", yscale="log", xlabel="elements n", title=measure)\n'
                  '    ax.grid(True, which="both", alpha=0.3)\n'
                  '    ax.legend(fontsize=8)\n'
                  'plt.show()\n'
                  'print(json.dumps(json.loads((DIR / "fig1_cost_fit.json").read_text()), indent=1))'),
    new_markdown_cell("## 2. Two surfaces meeting along an edge\n\n"
                      "Hierarchical elements are small where the surfaces are close (near the common edge)."),
    new_code_cell('edge = pd.read_csv(DIR / "fig2_edge.csv")\n'
                  'fig, (a, b) = plt.subplots(1, 2, figsize=(12, 5))\n'
                  'a.imshow(mpimg.imread(DIR / "fig2_edge_mesh.png"))\n'
                  'a.set_axis_off()\n'
                  'for patch, g in edge.groupby("patch"):\n'
                  '    b.scatter(g.distance, g["size"], s=6, alpha=0.6, label=f"patch {patch}")\n'
                  'b.set(xscale="log", yscale="log", xlabel="distance to the common edge", ylabel="element size")\n'
                  'b.grid(True, which="both", alpha=0.3)\n'
                  'b.legend()\n'
                  'plt.show()\n'
                  'edge.groupby(pd.cut(edge.distance, [0, 0.25, 0.5, 1, 2, 4, 8]), observed=True)["size"].describe()'),
    new_markdown_cell("## 3. Two surfaces far apart\n\n"
                      "k elements per surface: k^2 element pairs for the full matrix, 2k factors for "
                      "substructuring, and the few links hierarchical radiosity needs at the same finest element."),
    new_code_cell('far = pd.read_csv(DIR / "fig3_far.csv")\n'
                  'fig, ax = plt.subplots(figsize=(7, 5))\n'
                  'for method, g in far.groupby("method"):\n'
                  '    ax.plot(g.k, g.cross_pairs, "o-", color=COLORS.get(method), label=method)\n'
                  'k = far.k.drop_duplicates().sort_values().to_numpy(dtype=float)\n'
                  'ax.plot(k, k**2, "--", color="gray", lw=0.8, label="k^2")\n'
                  'ax.plot(k, 2 * k, ":", color="gray", lw=0.8, label="2k")\n'
                  'ax.set(xscale="log", yscale="log", xlabel="elements per surface k", ylabel="interactions between the surfaces")\n'
                  'ax.grid(True, which="both", alpha=0.3)\n'
                  'ax.legend(fontsize=8)\n'
                  'plt.show()\n'
                  'far.pivot(index="k", columns="method", values="cross_pairs")'),
    new_markdown_cell("## 4. The N-body analogy (Barnes-Hut)\n\n"
                      "Interactions per body against n: n - 1 for the direct sum (theta = 0), far fewer for theta > 0."),
    new_code_cell('nbody = pd.read_csv(DIR / "fig4_nbody.csv")\n'
                  'fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.5))\n'
                  'for theta, g in nbody.groupby("theta"):\n'
                  '    a.plot(g.n, g.mean_interactions, "o-", label=f"theta = {theta:g}")\n'
                  '    g = g[g.relative_force_error > 0]\n'
                  '    if len(g):\n'
                  '        b.plot(g.n, g.relative_force_error, "o-", label=f"theta = {theta:g}")\n'
                  'n = nbody.n.drop_duplicates().sort_values()\n'
                  'a.plot(n, n - 1, "--", color="gray", label="n - 1")\n'
                  'a.set(xscale="log", yscale="log", xlabel="bodies n", ylabel="interactions per body")\n'
                  'b.set(xscale="log", yscale="log", xlabel="bodies n", ylabel="relative RMS force error")\n'
                  'for ax in (a, b):\n'
                  '    ax.grid(True, which="both", alpha=0.3)\n'
                  '    ax.legend(fontsize=8)\n'
                  'plt.show()'),
    new_markdown_cell("## 5. Convergence of the three solvers (Cornell box)"),
    new_code_cell('conv = pd.read_csv(DIR / "fig5_convergence.csv")\n'
                  'fig, ax = plt.subplots(figsize=(7, 5))\n'
                  'for method, g in conv.groupby("method"):\n'
                  '    ax.plot(g.iteration, g.change, "o-", ms=3, color=COLORS.get(method), label=method)\n'
                  'ax.set(yscale="log", xlabel="iteration", ylabel="largest relative change")\n'
                  'ax.grid(True, which="both", alpha=0.3)\n'
                  'ax.legend()\n'
                  'plt.show()\n'
                  'conv.groupby("method").iteration.max()'),
    new_markdown_cell("## 6. Equal time\n\nEach method at about the hierarchical solve's time; errors against a "
                      "finer full-matrix reference (emitters left out)."),
    new_code_cell('eq = pd.read_csv(DIR / "fig6_equal_time.csv")\n'
                  'runs = eq[eq.method != "reference"]\n'
                  'fig, axes = plt.subplots(2, len(runs), figsize=(4 * len(runs), 8), squeeze=False)\n'
                  'for col, r in enumerate(runs.itertuples()):\n'
                  '    axes[0][col].imshow(mpimg.imread(DIR / r.image))\n'
                  '    axes[0][col].set_title(f"{r.method}: {r.elements} elements, {r.seconds:.2f} s")\n'
                  '    axes[1][col].imshow(mpimg.imread(DIR / r.error_image))\n'
                  '    axes[1][col].set_title(f"relative L2 error {r.error_l2:.3g}")\n'
                  '    for ax in axes[:, col] if hasattr(axes, "shape") else (axes[0][col], axes[1][col]):\n'
                  '        ax.set_axis_off()\n'
                  'plt.show()\n'
                  'eq'),
])

nbformat.write(sweep, "sweep.ipynb")
nbformat.write(figures, "figures.ipynb")
