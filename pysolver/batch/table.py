"""A sweep's rows as columns, without pandas (:attr:`pysolver.Sweep.table`)."""
import csv
import math
import numbers

import numpy as np


def _column(values):
    """Numbers (None -> NaN) as a float array, flags as a bool array, texts as a str array,
    anything else as an object array."""
    if all(isinstance(v, (bool, np.bool_)) for v in values):
        return np.array(values, dtype=bool)
    if all(v is None or (isinstance(v, numbers.Real) and not isinstance(v, (bool, np.bool_)))
           for v in values):
        return np.array([math.nan if v is None else float(v) for v in values], dtype=float)
    if all(isinstance(v, str) for v in values):
        return np.array(values, dtype=str)
    out = np.empty(len(values), dtype=object)
    out[:] = values
    return out


class Table(dict):
    """Column name -> NumPy array, one entry per case in case order: ``case``, the inputs (one
    column per path), ``status``, ``message``, ``wall``, ``steps``, the outputs, ``resumed``.

    ``table["x_end"].max()``, ``table["status"] == "ok"`` work as with NumPy; a value a row
    does not have (None: the outputs of a case that did not run) is NaN in a column of
    numbers. :meth:`to_dataframe` gives a pandas DataFrame indexed by case (``pip install
    pandas``), :meth:`to_csv` writes the rows (an empty cell for None); printing shows them.

    Parameters
    ----------
    rows : list of dict
        One per case.
    columns : list of str, optional
        The columns, in order (a sweep's :attr:`pysolver.Sweep.columns`); by default the keys
        of the rows, in the order they first appear.
    """

    def __init__(self, rows, columns=None):
        names = list(dict.fromkeys(k for r in rows for k in r) if columns is None else columns)
        super().__init__((n, _column([r.get(n) for r in rows])) for n in names)
        self.rows = rows

    def to_dataframe(self):
        """The rows as a pandas DataFrame indexed by case."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("Sweep.to_dataframe() needs pandas (pip install pandas, or "
                              "pysolver[dataframe]); Sweep.table gives the same columns "
                              "without it") from None
        frame = pd.DataFrame(self.rows, columns=list(self.keys()))
        for name, column in self.items():
            if column.dtype.kind == "f" and frame[name].dtype == object:    # None -> NaN
                frame[name] = column
        return frame.set_index("case") if "case" in frame else frame

    def to_csv(self, path):
        """Write the rows to a CSV file (one column per name, a row per case)."""
        with open(path, "w", newline="", encoding="utf-8") as fh:
            w = csv.DictWriter(fh, fieldnames=list(self.keys()))
            w.writeheader()
            for r in self.rows:
                w.writerow(r)

    def __repr__(self):
        names = list(self.keys())
        n = len(self.rows)
        shown = list(range(n)) if n <= 20 else list(range(10)) + [None] + list(range(n - 10, n))
        cells = [[_cell(self.rows[i].get(c)) for c in names] if i is not None else
                 ["..."] * len(names) for i in shown]
        width = [max([len(c)] + [len(r[j]) for r in cells]) for j, c in enumerate(names)]
        width = [min(w, 40) for w in width]

        def line(vals):
            return "  ".join(_fit(v, w).rjust(w) for v, w in zip(vals, width)).rstrip()
        return "\n".join([line(names)] + [line(r) for r in cells] +
                         [f"[{n} rows x {len(names)} columns]"])

    __str__ = __repr__


def _cell(v):
    if v is None:
        return ""
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def _fit(text, width):
    return text if len(text) <= width else text[:width - 3] + "..."
