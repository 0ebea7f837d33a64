"""The figure of a run (:meth:`pysolver.Result.plot`): request channels by kind of quantity.

One panel per kind and unit (lengths, velocities, forces, angles, ...) labelled like
``length [mm]`` against ``time [s]``; channels of one kind whose peaks differ by more than
:data:`SPREAD` get panels of their own, so a 200 rad/s spin does not flatten a 0.1 rad/s
nutation. Sensor events are solid vertical lines with their labels, the ends of Simulate
commands dashed ones; LoadControl tasks get their load and velocity panel; a request with two
length channels of one point (``x`` and ``z``) gets its path; static equilibria are a table of
values with the imbalance; a run with nothing to draw (no request channels, no LoadControl)
is one panel that says so and where its reactions and states are; a failed run is titled
``FAILED: message`` in red. Channels are named as the CSV's columns. The figure is a
:class:`matplotlib.figure.Figure` made without pyplot, so Jupyter shows the returned figure
once and pyplot keeps no reference to it.
"""
import os
import textwrap

import numpy as np

#: Largest ratio of peak magnitudes drawn in one panel.
SPREAD = 100.0
#: Height of a panel and width of the figure, inches.
PANEL_HEIGHT, WIDTH = 2.3, 10.0
#: Legends beside the data, never over it.
LEGEND = {"loc": "upper left", "bbox_to_anchor": (1.01, 1.0), "fontsize": 8,
          "borderaxespad": 0.0}
#: Axis letters of a point's coordinates, in the order a path is drawn (horizontal first).
AXES = ("x", "y", "z")


def figure(res):
    """Draw `res` (a :class:`pysolver.Result`) and return the Figure (see the module);
    ImportError naming the extra to install when matplotlib is missing."""
    try:
        from matplotlib.figure import Figure
    except ImportError:
        raise ImportError("plotting needs matplotlib: pip install \"pysolver[plot]\"") \
            from None

    channels = _channels(res)
    static_only = len(res.t) <= 1
    groups = [] if static_only else _panels(channels)
    ctrl = [] if static_only else res.controller_ids
    paths = [] if static_only else _paths(res, channels)
    tables = 1 if res.statics or static_only else 0
    # a run with nothing to draw (no request channels, no LoadControl task) says so
    empty = 0 if groups or ctrl or paths or tables else 1
    n = len(groups) + len(ctrl) + len(paths) + tables + empty
    heights = [PANEL_HEIGHT] * (len(groups) + len(ctrl)) + [3.2] * len(paths) + \
        [0.5 + 0.3 * len(channels) + (1.0 if not channels else 0.0)] * tables + [1.6] * empty
    fig = Figure(figsize=(WIDTH, sum(heights) + 0.8), layout="constrained")
    grid = fig.add_gridspec(n, 1, height_ratios=heights)
    time_axes = []
    for i, group in enumerate(groups):
        ax = fig.add_subplot(grid[i], sharex=time_axes[0] if time_axes else None)
        _draw_group(ax, res, group)
        time_axes.append(ax)
    for i, lid in enumerate(ctrl, start=len(groups)):
        ax = fig.add_subplot(grid[i], sharex=time_axes[0] if time_axes else None)
        _draw_controller(ax, res, lid)
        time_axes.append(ax)
    for ax in time_axes:
        _marks(ax, res, labels=ax is time_axes[0])
    if time_axes:
        time_axes[-1].set_xlabel(_label("time", res.units.get("time")))
    row = len(groups) + len(ctrl)
    for i, (rid, hor, ver) in enumerate(paths, start=row):
        _draw_path(fig.add_subplot(grid[i]), res, rid, hor, ver)
    if tables:
        _draw_statics(fig.add_subplot(grid[n - 1]), res, channels)
    if empty:
        ax = fig.add_subplot(grid[0])
        ax.axis("off")
        ax.text(0.5, 0.5, "\n".join(nothing_to_plot(res)), ha="center", va="center",
                fontsize=10, transform=ax.transAxes)
    _title(fig, res)
    return fig


def save(res, path):
    """Draw `res` and write the figure to `path` (format by suffix)."""
    fig = figure(res)
    fig.savefig(os.fspath(path), dpi=110)
    return fig


def nothing_to_plot(res):
    """The lines a figure of `res` shows in place of request channels when it has none: that
    there are none, how to get some, and where the run's reactions and states are."""
    def ids(values):
        return ", ".join(map(str, values[:6])) + (", ..." if len(values) > 6 else "")

    lines = ["nothing to plot: this run has no request channels",
             "add a Post_Request (msolve: Request) for what to plot"]
    if res.joint_ids:
        lines.append(f"joint reactions: res.joint(id), joints {ids(res.joint_ids)}")
    if res.motion_ids:
        lines.append(f"motion reactions: res.motion(id), motions {ids(res.motion_ids)}")
    return lines + ["states: res.y, columns named by res.state_names"]


def _label(kind, unit):
    """An axis label: ``length [mm]``; ``[N/mm]`` for a unit with no common name."""
    if unit is None:
        return f"{kind} (no unit)" if kind else "no unit"
    return f"{kind} [{unit}]" if kind else f"[{unit}]"


def _channels(res):
    """(name shown, bare name, values, unit, kind) of each channel res.columns() has, shown
    by its column name (``x``; ``x (request 2)`` for a name several channels have)."""
    return [(name, bare, res._channel(rid, k), *res._quantity((rid, k)))
            for rid, k, bare, name in res._named_channels()]


def _peak(values):
    finite = np.abs(values[np.isfinite(values)])
    return float(finite.max()) if finite.size else 0.0


def _panels(channels):
    """Channels grouped by (kind, unit) in order of appearance, each group split where the
    peaks of its channels differ by more than SPREAD (channels ~0 stay with the largest)."""
    groups = {}
    for ch in channels:
        groups.setdefault((ch[4], ch[3]), []).append(ch)
    panels = []
    for (kind, unit), members in groups.items():
        if unit is None:                       # no unit: nothing says they compare
            panels += [(kind, unit, [ch]) for ch in members]
            continue
        ranked = sorted(members, key=lambda ch: -_peak(ch[2]))
        top = _peak(ranked[0][2])
        split = [[ranked[0]]]
        for ch in ranked[1:]:
            p = _peak(ch[2])
            if p <= 1e-9 * top or p * SPREAD >= _peak(split[-1][0][2]):
                (split[0] if p <= 1e-9 * top else split[-1]).append(ch)
            else:
                split.append([ch])
        order = {id(ch): i for i, ch in enumerate(members)}
        panels += [(kind, unit, sorted(s, key=lambda ch: order[id(ch)])) for s in split]
    return panels


def _draw_group(ax, res, group):
    kind, unit, members = group
    for shown, _, values, _, _ in members:
        ax.plot(res.t, values, lw=1.2, label=shown)
    # whole values on the ticks: an offset (``1e-6-2.942999e1``) is harder to read than
    # -29.429999 .. -29.430001
    ax.ticklabel_format(axis="y", useOffset=False)
    _steady_limits(ax, [values for _, _, values, _, _ in members])
    ax.set_ylabel(_label(kind, unit))
    ax.grid(True, alpha=0.3)
    ax.legend(**LEGEND)


def _steady_limits(ax, series):
    """A panel whose channels all stay within 1e-9 of their size (a spin of 200 rad/s held to
    1e-11) reads as its value: limits 1 % either side (not a flat line under 1e-10 ticks)."""
    data = np.concatenate([np.asarray(v, float).ravel() for v in series])
    data = data[np.isfinite(data)]
    if not len(data):
        return
    lo, hi = data.min(), data.max()
    size = max(abs(lo), abs(hi))
    if hi - lo <= 1e-9 * size and size > 0:
        mid = 0.5 * (lo + hi)
        ax.set_ylim(mid - 0.01 * size, mid + 0.01 * size)


def _draw_controller(ax, res, lid):
    rec, units = res.controller(lid), res.controller_units()
    ax.plot(rec["time"], rec["target"], "k--", label="target load")
    ax.plot(rec["time"], rec["measured"], label="measured load")
    ax.set_title(f"LoadControl {lid}", fontsize=9, loc="right")
    ax.set_ylabel(_label("load", units["target"]))
    ax.grid(True, alpha=0.3)
    vel = ax.twinx()
    vel.plot(rec["time"], rec["velocity"], color="tab:red", lw=0.8, label="velocity")
    vel.set_ylabel(_label("velocity", units["velocity"]), color="tab:red")
    # the legend above the panel: beside it, it would cover the velocity axis' label
    lines = ax.get_lines() + vel.get_lines()
    ax.legend(lines, [ln.get_label() for ln in lines], loc="lower left",
              bbox_to_anchor=(0.0, 1.0), ncol=len(lines), fontsize=8, borderaxespad=0.2)


def _marks(ax, res, labels):
    """Sensor events (solid, labelled on the first panel) and the ends of Simulate commands
    but the last (dashed) as vertical lines."""
    for e in res.events:
        ax.axvline(e.time, color="tab:purple", lw=1.0,
                   label=f"event: {e.label or f'sensor {e.sensor}'}" if labels else None)
        if labels:               # the text on the side of the line with room for it
            right = len(res.t) and e.time > (res.t[0] + res.t[-1]) / 2
            ax.annotate(e.label or f"sensor {e.sensor}", (e.time, 1.0),
                        xycoords=("data", "axes fraction"), xytext=(-3 if right else 3, -3),
                        textcoords="offset points", va="top", ha="right" if right else "left",
                        fontsize=7, color="tab:purple")
    ends = [c["end_time"] for c in res.meta.get("commands", [])[:-1]]
    t0, t1 = (res.t[0], res.t[-1]) if len(res.t) else (0.0, 0.0)
    for k, end in enumerate(ends, start=1):
        if t0 < end < t1:
            ax.axvline(end, color="0.4", ls="--", lw=0.9,
                       label=f"end of command {k}" if labels else None)
    if labels and (res.events or ends):
        ax.legend(**LEGEND)


def _axis_of(name):
    """(axis letter, the rest of the name) for ``x``, ``x_cm``, ``tip_x``; None otherwise."""
    low = name.lower()
    if low in AXES:
        return low, ""
    if len(low) > 2 and low[0] in AXES and low[1] in "_.":
        return low[0], low[2:]
    if len(low) > 2 and low[-1] in AXES and low[-2] in "_.":
        return low[-1], low[:-2]
    return None


def _paths(res, channels):
    """(request id, horizontal, vertical channel) of each request with two or three length
    channels named as coordinates of one point: the two that move most."""
    out = []
    by_request = {}
    for (rid, *_), ch in zip(res._named_channels(), channels):
        axis = _axis_of(ch[1])
        if ch[4] == "length" and axis is not None:
            by_request.setdefault((rid, axis[1], ch[3]), {})[axis[0]] = ch
    for (rid, _, _), coords in by_request.items():
        if len(coords) < 2:
            continue
        spans = {a: np.ptp(np.nan_to_num(c[2])) for a, c in coords.items()}
        two = sorted(sorted(spans, key=lambda a: -spans[a])[:2])
        if spans[two[0]] > 0 or spans[two[1]] > 0:
            out.append((rid, coords[two[0]], coords[two[1]]))
    return out


def _draw_path(ax, res, rid, hor, ver):
    ax.plot(hor[2], ver[2], lw=1.2, label=f"path (request {rid})")
    ax.plot(hor[2][:1], ver[2][:1], "o", color="tab:green", label="start")
    ax.plot(hor[2][-1:], ver[2][-1:], "s", color="tab:red", label="end")
    ax.set_xlabel(_label(hor[0], hor[3]))
    ax.set_ylabel(_label(ver[0], ver[3]))
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.legend(**LEGEND)


def _draw_statics(ax, res, channels):
    """The channels' values at the last static equilibrium, with its method and imbalance;
    without one (a run of one output row) the values of that row."""
    ax.axis("off")
    row = len(res.t) - 1
    if res.statics:
        st = res.statics[-1]
        rows = np.flatnonzero(res.t == st.time)
        row = rows[-1] if len(rows) else row
        force = res._quantity("force").unit or ""
        its = f"{st.iterations} iteration{'s' * (st.iterations != 1)}"
        ax.set_title(f"static equilibrium at t = {st.time:g}: {st.method}, {its}, imbalance "
                     f"{st.imbalance:.3g} {force}".rstrip()
                     + ("" if st.success else " (FAILED)"), fontsize=9)
    elif row >= 0:
        ax.set_title(f"the one output row, t = {res.t[row]:g}", fontsize=9)
    else:
        ax.set_title("no output rows", fontsize=9)
    if not channels:
        ax.text(0.5, 0.4, "\n".join(nothing_to_plot(res)), ha="center", va="center",
                fontsize=10, transform=ax.transAxes)
    if row < 0 or not channels:
        return
    cells = [[shown, f"{values[row]:.6g}", unit or ""] for shown, _, values, unit, _ in channels]
    table = ax.table(cellText=cells, colLabels=["channel", "value", "unit"], loc="upper center",
                     cellLoc="left", colWidths=[0.3, 0.25, 0.15])
    table.auto_set_font_size(False)
    table.set_fontsize(9)


def _title(fig, res):
    if not res.success:
        fig.suptitle("\n".join(textwrap.wrap(f"FAILED: {res.message}", 110)), color="red",
                     fontsize=10)
    else:
        deck = res.meta.get("deck")
        fig.suptitle(os.path.basename(deck) if deck else "pysolver run", fontsize=10)
