"""Shared helpers of hrad's plot scripts: a non-interactive backend and PNG writes."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLORS = {"full": "#d62728", "substructure": "#1f77b4", "hierarchical": "#2ca02c",
          "hierarchical_linear": "#9467bd", "full_linear": "#ff7f0e", "substructure_linear": "#17becf"}


def save(fig, path):
    """Writes the figure to `path`. hrad passes a temporary in its staging folder and renames it with
    the command's other outputs, so the file is created here like any other output: mode 0666 less
    the umask (tempfile.mkstemp would make it 0600)."""
    fig.savefig(path, dpi=120, format="png")
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
