"""Shared helpers of hrad's plot scripts: a non-interactive backend and atomic PNG writes."""
import os
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLORS = {"full": "#d62728", "substructure": "#1f77b4", "hierarchical": "#2ca02c"}


def save(fig, path):
    """Writes the figure to a temporary file beside `path`, then renames it."""
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".plot-", suffix=".png", dir=folder)
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=120, format="png")
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    plt.close(fig)


def read_csv(path):
    """Rows of a CSV as dicts, numbers converted where they parse."""
    import csv
    rows = []
    with open(path) as f:
        for r in csv.DictReader(f):
            for k, v in r.items():
                try:
                    r[k] = float(v)
                except (TypeError, ValueError):
                    pass
            rows.append(r)
    return rows
