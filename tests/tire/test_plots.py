"""Tire figure set and characteristic values (checked against the laws' closed forms)."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402

from vehdyn.tire import BrushTire, FialaTire, LinearTire, describe_tire, plot_tire_characteristics  # noqa: E402
from vehdyn.tire.plots import characteristic_values, nominal_load  # noqa: E402

BRUSH = BrushTire(contact_half_length=0.08, tread_stiffness=5e6, mu=0.9)


def test_characteristic_values_match_closed_forms():
    frame = characteristic_values(BRUSH, [2000.0, 4000.0])
    np.testing.assert_allclose(frame["cornering_stiffness"], 2 * 5e6 * 0.08**2, rtol=1e-5)
    np.testing.assert_allclose(frame["slip_stiffness"], 2 * 5e6 * 0.08**2, rtol=1e-5)
    np.testing.assert_allclose(frame["trail_at_zero_slip"], 0.08 / 3, rtol=1e-5)
    np.testing.assert_allclose(frame["peak_lateral_friction"], 0.9, rtol=1e-12)
    np.testing.assert_allclose(frame["peak_longitudinal_friction"], 0.9, rtol=1e-12)
    assert frame.attrs["units"]["cornering_stiffness"] == "N/rad"


def test_nominal_load():
    assert nominal_load(LinearTire(cornering_stiffness=1e4, nominal_load=3500.0)) == 3500.0
    assert nominal_load(BRUSH) == 4000.0


def test_figure_set_for_one_and_several_tires():
    import matplotlib.pyplot as plt

    for tire in (BRUSH, {"brush": BRUSH, "fiala": FialaTire(cornering_stiffness=64000.0, mu=0.9)}):
        figures = plot_tire_characteristics(tire, loads=[2000.0, 4000.0], n_points=21)
        assert set(figures) == {"lateral_force", "longitudinal_force", "aligning_moment", "friction_ellipse",
                                "cornering_stiffness"}
        for fig in figures.values():
            ax = fig.axes[0]
            assert "[" in ax.get_xlabel() and "[" in ax.get_ylabel()  # units on every axis
            plt.close(fig)
    # the lateral-force curve is the law's own output
    figures = plot_tire_characteristics(BRUSH, loads=[3000.0], n_points=11, max_slip_angle_deg=10.0)
    x, y = figures["lateral_force"].axes[0].lines[0].get_data()
    np.testing.assert_allclose(y, BRUSH.forces(3000.0, 0.0, np.deg2rad(x), 0.0, 20.0).fy, rtol=1e-14)
    plt.close("all")


def test_describe_tire_lists_parameters_and_values():
    text = describe_tire(BRUSH)
    assert "BrushTire" in text and "tread_stiffness" in text and "cornering_stiffness" in text
