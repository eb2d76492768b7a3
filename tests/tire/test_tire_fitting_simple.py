"""fit_brush and fit_linear recover the laws' own parameters from data they generated."""

from __future__ import annotations

import numpy as np
import pytest

from vehdyn.errors import ParameterError
from vehdyn.tire import BrushTire, LinearTire, fit_brush, fit_linear
from vehdyn.tire.fitting.synthetic import sample_tire

LOADS = [2000.0, 4000.0, 6000.0]


@pytest.mark.parametrize("sliding", [False, True])
def test_brush_parameters_recovered(sliding):
    truth = BrushTire(contact_half_length=0.08, tread_stiffness=5e6, mu=1.0, mu_sliding=0.8 if sliding else None)
    data = sample_tire(truth, loads=LOADS, cambers=[0.0], combined_angles=[], vx=10.0)
    fit = fit_brush(data, sliding=sliding)
    values = fit.stages["brush"].coefficients
    assert values["cornering_stiffness"] == pytest.approx(2 * 5e6 * 0.08**2, rel=1e-6)
    assert values["mu"] == pytest.approx(1.0, rel=1e-6)
    assert values["contact_half_length"] == pytest.approx(0.08, rel=1e-6)
    if sliding:
        assert values["mu_sliding"] == pytest.approx(0.8, rel=1e-6)
    assert max(fit.stages["brush"].nrms.values()) < 1e-6


def test_brush_from_magic_formula_data_is_close(shipped=("MagicFormula61_Parameters",)):
    """The brush is a rougher law: on Magic Formula data it fits the side force to a few percent."""
    from vehdyn.tire import load_tire

    tire = load_tire(shipped[0])
    data = sample_tire(tire, loads=[tire.nominal_load], cambers=[0.0], combined_angles=[])
    fit = fit_brush(data)
    assert fit.stages["brush"].nrms["fy"] < 0.1
    kya = float(tire.evaluate(tire.nominal_load, 0.0, 0.0).kya)
    assert fit.stages["brush"].coefficients["cornering_stiffness"] == pytest.approx(-kya, rel=0.25)


def test_brush_needs_contact_length_without_mz():
    truth = BrushTire(contact_half_length=0.08, tread_stiffness=5e6, mu=1.0)
    data = sample_tire(truth, loads=LOADS, cambers=[0.0], combined_angles=[], vx=10.0).drop(columns=["mz"])
    with pytest.raises(ParameterError, match="give contact_half_length"):
        fit_brush(data)
    fit = fit_brush(data, contact_half_length=0.08)
    assert fit.stages["brush"].coefficients["mu"] == pytest.approx(1.0, rel=1e-6)


def test_linear_closed_form_recovers_parameters():
    truth = LinearTire(cornering_stiffness=8e4, slip_stiffness=1.2e5, camber_stiffness=3e3, pneumatic_trail=0.03,
                       nominal_load=4000.0)
    data = sample_tire(truth, loads=LOADS, slip_angles=np.radians(np.linspace(-2, 2, 9)),
                       slip_ratios=np.linspace(-0.02, 0.02, 9), cambers=np.radians([0.0, -4.0, 4.0]),
                       combined_angles=[], vx=10.0)
    fit = fit_linear(data, nominal_load=4000.0)
    values = fit.stages["linear"].coefficients
    for name, value in (("cornering_stiffness", 8e4), ("slip_stiffness", 1.2e5), ("camber_stiffness", 3e3),
                        ("pneumatic_trail", 0.03)):
        assert values[name] == pytest.approx(value, rel=1e-10), name
    assert fit.tire.nominal_load == 4000.0
    with pytest.raises(ParameterError, match="only a Magic Formula fit writes a .tir file"):
        fit.to_tir("linear.tir")


def test_simple_fits_bad_input():
    data = {"fz": np.full(3, 4000.0), "kappa": np.zeros(3), "alpha": np.zeros(3), "fy": np.zeros(3)}
    with pytest.raises(ParameterError, match="slip-angle sweep"):
        fit_linear(data)
    with pytest.raises(ParameterError, match="slip-angle sweep"):
        fit_brush(data)
    data["alpha"] = np.array([0.0, 0.01, 0.5])
    with pytest.raises(ParameterError, match="cornering stiffness 0 N/rad is not positive"):
        fit_linear(data)
    data["alpha"] = np.array([0.0, 0.5, 0.6])
    with pytest.raises(ParameterError, match="1 points with"):
        fit_linear(data)
    data["alpha"] = np.array([0.0, 0.0, 0.6])
    with pytest.raises(ParameterError, match="0 of them at a non-zero slip angle"):
        fit_linear(data)


def test_fit_plots_data_against_fit():
    """One figure per stage; the fitted curve of each output lies on its data (exact laws), and the
    dashed curves between the measured loads are the fitted law at the loads midway, between their
    neighbours' curves (the brush's force grows with the load at every slip)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    truth = BrushTire(contact_half_length=0.08, tread_stiffness=5e6, mu=1.0)
    fit = fit_brush(sample_tire(truth, loads=LOADS, cambers=[0.0], combined_angles=[], vx=10.0))
    figures = fit.plot()
    assert list(figures) == ["brush"]
    axes = figures["brush"].axes
    assert [ax.get_ylabel() for ax in axes] == ["fy [N]", "fx [N]", "mz [N*m]"]
    for ax, out in zip(axes, ("fy", "fx", "mz")):
        lines = [line for line in ax.get_lines() if len(line.get_xdata())]
        measured = [line for line in lines if line.get_linestyle() == "None"]
        solid = [line for line in lines if line.get_linestyle() == "-"]
        between = [line for line in lines if line.get_linestyle() == "--"]
        assert len(measured) == len(solid) == len(LOADS) and len(between) == len(LOADS) - 1
        for data, model in zip(measured, solid):
            y = data.get_ydata()
            np.testing.assert_allclose(model.get_ydata(), y, atol=1e-6 * np.max(np.abs(y)))
        for i, line in enumerate(between):
            x = line.get_xdata()
            slip = np.radians(x) if out != "fx" else x
            load = 0.5 * (LOADS[i] + LOADS[i + 1])
            kappa, alpha = (slip, 0.0 * slip) if out == "fx" else (0.0 * slip, slip)
            expected = getattr(fit.tire.forces(np.full(slip.size, load), kappa, alpha, 0.0, 10.0), out)
            np.testing.assert_allclose(line.get_ydata(), expected, rtol=1e-12, atol=1e-9)
            if out != "mz":  # |F| grows with the load at every slip
                low, high = (getattr(fit.tire.forces(np.full(slip.size, f), kappa, alpha, 0.0, 10.0), out)
                             for f in (LOADS[i], LOADS[i + 1]))
                assert np.all(np.abs(low) <= np.abs(expected) + 1e-9) and np.all(np.abs(expected) <= np.abs(high) + 1e-9)
    plt.close("all")
