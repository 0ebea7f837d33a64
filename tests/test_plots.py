"""Result.plot draws figures people read: panels by kind of quantity labelled with units,
events and command ends marked, paths, static tables, failed runs titled so; pyplot keeps no
figure (Jupyter shows it once)."""
import pathlib

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib", reason="matplotlib is not installed")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import pysolver  # noqa: E402
from pysolver import plotting  # noqa: E402

DECKS = pathlib.Path(__file__).resolve().parent.parent / "decks"


def _run(name, **kw):
    return pysolver.load(DECKS / name).run(**kw)


def _legend(ax):
    legend = ax.get_legend()
    return [t.get_text() for t in legend.get_texts()] if legend else []


def _vlines(ax):
    """x of the vertical lines (axvline) of an axes, with their line style."""
    return [(ln.get_xdata()[0], ln.get_linestyle()) for ln in ax.get_lines()
            if len(ln.get_xdata()) == 2 and ln.get_xdata()[0] == ln.get_xdata()[1]
            and tuple(ln.get_ydata()) == (0, 1)]


def test_readme_deck_panels_by_quantity_with_units(tmp_path):
    plt.close("all")
    res = _run("particle_between_lines.xml")
    fig = res.plot(tmp_path / "p.png")
    assert (tmp_path / "p.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    labels = [(ax.get_ylabel(), ax.get_xlabel()) for ax in fig.axes]
    assert labels == [("length [mm]", ""), ("force [N]", "time [s]"), ("z [mm]", "x [mm]")]
    assert _legend(fig.axes[0]) == ["x", "z"] and _legend(fig.axes[1]) == ["force_L1",
                                                                          "force_L2"]
    assert _legend(fig.axes[2]) == ["path (request 1)", "start", "end"]
    path = fig.axes[2].get_lines()[0]
    np.testing.assert_array_equal(path.get_xdata(), res.request(1)[:, 0])
    np.testing.assert_array_equal(path.get_ydata(), res.request(1)[:, 1])
    for ax in fig.axes:                         # legends beside the data, not over it
        assert ax.get_legend()._loc == 2 and ax.get_legend().get_bbox_to_anchor().x0 > \
            ax.get_window_extent().x1 - 1
    assert fig._suptitle.get_text() == "particle_between_lines.xml"
    assert fig.get_size_inches()[0] >= 8 and fig.get_size_inches()[1] >= 6
    assert plt.get_fignums() == []              # pyplot holds nothing: Jupyter shows it once


def test_returned_figure_is_not_a_pyplot_figure():
    plt.close("all")
    fig = _run("particle_between_lines.xml").plot()
    assert isinstance(fig, matplotlib.figure.Figure)
    assert plt.get_fignums() == []


def test_angles_and_angular_velocities_get_separate_panels():
    fig = _run("spinning_top.xml").plot()
    ylabels = [ax.get_ylabel() for ax in fig.axes]
    assert ylabels == ["length [m]", "length [m]", "angle [rad]", "angular velocity [rad/s]",
                       "force [N]", "y_cm [m]"]
    assert _legend(fig.axes[2]) == ["azimuth"] and _legend(fig.axes[3]) == ["spin"]
    # tip_gap (about 1e-4 m) is apart from the centre's coordinates (0.1 m)
    assert _legend(fig.axes[0]) == ["x_cm", "y_cm", "z_cm"] and _legend(fig.axes[1]) == \
        ["tip_gap"]


def test_a_steady_channel_reads_as_its_value():
    """The top's spin stays 200 rad/s to 1e-10: its panel spans 198..202 rad/s and its axis
    has no offset notation, where matplotlib alone would show a flat line under
    '1e-10+2e2'."""
    fig = _run("spinning_top.xml").plot()
    fig.canvas.draw()
    spin = fig.axes[3]
    assert spin.get_ylim() == pytest.approx((198.0, 202.0), abs=1e-6)
    assert spin.yaxis.get_offset_text().get_text() == ""


def test_a_wide_spread_in_one_kind_splits_the_panel():
    res = _run("torque_free_spin.xml")
    groups = plotting._panels(plotting._channels(res))
    assert [[ch[0] for ch in g[2]] for g in groups] == \
        [["wx_body", "wy_body", "wz_body", "wx", "wy", "wz"], ["x", "z"]]
    # scaled so that wx_body and wy_body peak 1000x below the others: their own panel
    res._outputs[:, :2] *= 1e-3
    res._requests.clear()
    groups = plotting._panels(plotting._channels(res))
    assert [[ch[0] for ch in g[2]] for g in groups] == \
        [["wz_body", "wx", "wy", "wz"], ["wx_body", "wy_body"], ["x", "z"]]
    fig = res.plot()
    assert [ax.get_ylabel() for ax in fig.axes[:2]] == ["angular velocity [rad/s]"] * 2


def test_sensor_event_is_a_labelled_vertical_line():
    res = _run("sensor_end_condition.xml")
    fig = res.plot()
    t_event = res.t_events[0]
    time_axes = [ax for ax in fig.axes if ax.get_ylabel() == "length [mm]"]
    for ax in time_axes:
        assert (t_event, "-") in _vlines(ax)
    assert "event: near the vertex" in _legend(time_axes[0])
    assert [t.get_text() for t in time_axes[0].texts] == ["near the vertex"]


def test_simulate_command_ends_are_dashed_lines(tmp_path):
    text = (DECKS / "particle_between_lines.xml").read_text().replace(
        '<Simulate analysis_type="Transient" end_time="3.0" print_interval="0.005"/>',
        '<Simulate analysis_type="Transient" end_time="0.5" print_interval="0.01"/>\n'
        '  <Simulate analysis_type="Transient" end_time="1.0" print_interval="0.01"/>')
    res = pysolver.loads(text).run()
    fig = res.plot()
    assert (0.5, "--") in _vlines(fig.axes[0]) and (0.5, "--") in _vlines(fig.axes[1])
    assert "end of command 1" in _legend(fig.axes[0])
    assert not any(x == 1.0 for x, _ in _vlines(fig.axes[0]))      # the last end: none


def test_static_results_are_a_table_of_values_with_the_imbalance():
    res = _run("static_seed3.xml")
    fig = res.plot()
    table_ax = fig.axes[-1]
    st = res.statics[0]
    assert table_ax.get_title() == (f"static equilibrium at t = 0: FIM_S, {st.iterations} "
                                    f"iterations, imbalance {st.imbalance:.3g} N")
    cells = {(r, c): cell.get_text().get_text()
             for (r, c), cell in table_ax.tables[0].get_celld().items()}
    assert [cells[(0, c)] for c in range(3)] == ["channel", "value", "unit"]
    assert [cells[(2, c)] for c in range(3)] == ["z", f"{res.request(1)[0, 1]:.6g}", "mm"]
    assert [cells[(3, c)] for c in range(3)] == ["force_L1", f"{res.request(1)[0, 2]:.6g}",
                                                 "N"]


def test_a_static_only_run_is_not_an_empty_frame():
    res = pysolver.load(DECKS / "static_seed3.xml",
                        simulate={"analysis_type": "Static"}).run()
    assert len(res.t) == 1
    fig = res.plot()
    assert len(fig.axes) == 1 and len(fig.axes[0].tables) == 1
    cells = fig.axes[0].tables[0].get_celld()
    assert cells[(2, 0)].get_text().get_text() == "z"
    assert float(cells[(2, 1)].get_text().get_text()) == pytest.approx(0.944629, abs=1e-6)


def test_a_failed_run_is_titled_failed_in_red():
    res = _run("particle_between_lines.xml", max_num_steps=5)
    assert not res.success
    fig = res.plot()
    title = fig._suptitle
    assert title.get_text().replace("\n", " ") == f"FAILED: {res.message}"
    assert matplotlib.colors.to_hex(title.get_color()) == "#ff0000"


def test_loadcontrol_panel_keeps_its_units():
    fig = _run("loadcontrol_indenter.xml").plot()
    ax = next(ax for ax in fig.axes if ax.get_title(loc="right") == "LoadControl 1")
    assert ax.get_ylabel() == "load [N]"
    twins = [a for a in fig.axes if a.bbox.bounds == ax.bbox.bounds and a is not ax]
    assert [a.get_ylabel() for a in twins] == ["velocity [mm/s]"]
    assert _legend(ax) == ["target load", "measured load", "velocity"]
    # the legend covers neither the data nor the velocity axis' label
    fig.canvas.draw()
    box = ax.get_legend().get_window_extent()
    assert not box.overlaps(ax.get_window_extent())
    assert not box.overlaps(twins[0].yaxis.label.get_window_extent())
    assert fig.axes[0].get_ylabel() == "length [mm]"


def test_a_small_variation_on_a_large_value_has_whole_tick_labels():
    """Bricard's energy stays -29.43 J to 1e-6: its ticks read -29.429996 .. -29.430000, not
    an offset ('1e-6-2.942999e1') that leaves the reader to add it up."""
    res = _run("joints/iftomm_a04_bricard.xml", progress=False)
    fig = res.plot()
    fig.canvas.draw()
    ax = next(a for a in fig.axes if _legend(a) == ["energy"])
    assert ax.yaxis.get_offset_text().get_text() == ""
    low, high = ax.get_ylim()
    assert -29.4301 < low < high < -29.4299
    ticks = [t.get_text() for t in ax.get_yticklabels() if t.get_text()]
    assert all(t.replace("\u2212", "-").startswith("-29.4") for t in ticks), ticks
