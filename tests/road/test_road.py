"""ISO 8608 spectra and synthesis (F-ISO8608-SYNTH), parallel tracks, events and the IRI (E-QC-GOLDENCAR)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import vehdyn
from vehdyn import road

PRINTED = 1e-6  # the cases print 7 significant digits: no comparison can be tighter than that


def tolerance(case, key):
    value, _unit, tol = case["expected"][key]
    return value, max(tol, PRINTED)

# ISO 8608:2016 Table C.2 (classification by Gd(n0)), geometric means of the classes [1e-6 m^3]
ISO8608_GEOMETRIC_MEANS = {"A": 16, "B": 64, "C": 256, "D": 1024, "E": 4096, "F": 16384, "G": 65536, "H": 262144}


def test_class_values_are_geometric_means():
    for letter, value in ISO8608_GEOMETRIC_MEANS.items():
        assert road.iso8608_class_value(letter) == pytest.approx(value * 1e-6, rel=1e-15)
        assert road.iso8608_psd(letter.lower(), 0.1) == pytest.approx(value * 1e-6, rel=1e-15)
    # pitfall 1: not the class upper limit (32e-6 for A), not the value at Omega0 = 1 rad/m (~1e-6 for A)
    assert road.iso8608_psd("A", 0.1) != 32e-6


def test_psd_slope_and_user_value(cases):
    gd0 = cases["E-QC-ISO-C"]["inputs"]["Gd(n0)_class_C"][0]
    assert road.iso8608_psd("C", 0.1) == gd0
    assert road.iso8608_psd(gd0, 1.0) == pytest.approx(gd0 / 100, rel=1e-14)  # w = 2: a decade is 1/100
    assert road.iso8608_psd(gd0, 1.0, waviness=1.5) == pytest.approx(gd0 * 10**-1.5, rel=1e-14)


def test_temporal_velocity_psd_is_white(cases):
    case = cases["E-QC-ISO-C"]
    value, tol = tolerance(case, "road_velocity_PSD_white_Gzr'")
    spec = road.RoadSpectrum.from_class("C")
    for f in (0.1, 1.0, 10.0, 100.0):
        g = (2 * np.pi * f) ** 2 * spec.temporal_psd(f, case["inputs"]["V"][0])
        assert g == pytest.approx(value, rel=tol)


@pytest.mark.parametrize("w, nc", [(2.0, 0.0), (2.5, 0.0), (1.0, 0.0), (2.0, 0.02), (2.5, 0.02)])
def test_band_variance_closed_form_against_quadrature(w, nc):
    from scipy.integrate import quad

    spec = road.RoadSpectrum.from_class("D", waviness=w, cut_on=nc)
    num = quad(lambda n: float(spec.psd(n)), 0.011, 2.83, limit=200, epsrel=1e-12)[0]
    assert spec.variance(0.011, 2.83) == pytest.approx(num, rel=1e-9)


def test_synthesis_f_iso8608_synth(cases):
    case = cases["F-ISO8608-SYNTH"]
    exp = {k: tolerance(case, k) for k in case["expected"]}
    for seed in (0, 1, 2):
        p = road.synthesize_profile("C", 100.0, 0.01, seed=seed, n_max=10.0)
        value, tol = exp["component_amplitude_A_1_at_n=0.01"]
        assert np.abs(p.coefficients[1]) == pytest.approx(value, rel=tol)
        value, tol = exp["component_amplitude_A_100_at_n=1.0"]
        assert np.abs(p.coefficients[100]) == pytest.approx(value, rel=tol)
        assert p.coefficients.size == 1001  # n_i = i dn, i = 1 .. 1000
        value, tol = exp["profile_variance_any_phases"]
        assert np.var(p.elevation) == pytest.approx(value, rel=tol)
    spec = road.RoadSpectrum.from_class("C")
    # the continuous values are printed to 5 and 7 digits
    assert spec.rms(0.01, 10) == pytest.approx(exp["continuous_rms_0.01-10"][0], rel=5e-5)
    assert spec.rms(0.005, 10.005) == pytest.approx(exp["continuous_rms_0.005-10.005"][0], rel=PRINTED)
    # pitfall 2: with dn = 0.01 the discrete variance is tens of percent off the continuous band value
    assert np.std(p.elevation) / spec.rms(0.01, 10) - 1 > 0.25


def test_band_rms_of_a_fine_synthesis_against_the_psd_integral():
    """Refine dn (2 km profile), band-pass by FFT to [0.1, 1] cycles/m, compare with the integral."""
    p = road.synthesize_profile("B", 2000.0, 0.05, seed=7)
    Z = np.fft.rfft(p.elevation)
    n = np.fft.rfftfreq(p.elevation.size, p.spacing)
    Z[(n < 0.1) | (n > 1.0)] = 0
    band = np.fft.irfft(Z, p.elevation.size)
    spec = road.RoadSpectrum.from_class("B")
    # left-endpoint Riemann sum of n^-2 with dn = 5e-4 over [0.1, 1]: relative error ~ dn / (2 n_low) = 0.25 %
    assert np.std(band) == pytest.approx(spec.rms(0.1, 1.0), rel=0.003)


def test_white_noise_synthesis_spectrum():
    from scipy.signal import welch

    spec = road.RoadSpectrum.from_class("C", cut_on=0.05)
    p = road.synthesize_profile(spec, 40000.0, 0.1, seed=3, method="white_noise")
    n, G = welch(p.elevation, fs=1 / p.spacing, nperseg=4096)
    band = (n > 0.02) & (n < 1.0)
    ratio = G[band] / spec.psd(n[band])
    assert np.mean(ratio) == pytest.approx(1.0, abs=0.05)
    assert np.var(p.elevation) == pytest.approx(spec.variance(), rel=0.15)


def test_shaping_filter_reproduces_the_spectrum():
    V = 15.0
    for spec in (road.RoadSpectrum.from_class("C"), road.RoadSpectrum.from_class("E", cut_on=0.01)):
        filt = spec.shaping_filter(V)
        f = np.geomspace(0.01, 50, 30)
        H = filt.frequency_response(2 * np.pi * f).response
        # unit-intensity white noise has one-sided PSD 2 per Hz
        np.testing.assert_allclose(2 * np.abs(H[0, 0]) ** 2, spec.temporal_psd(f, V), rtol=1e-12)
        np.testing.assert_allclose(2 * np.abs(H[1, 0]) ** 2, (2 * np.pi * f) ** 2 * spec.temporal_psd(f, V),
                                   rtol=1e-12)
    car = road.golden_car()  # a quarter car driven by the road's displacement
    aug = vehdyn.connect_in_series(road.RoadSpectrum.from_class("C").shaping_filter(V), car)
    assert aug.input_names == ("road_noise",)
    assert "suspension_velocity" in aug.output_names


def test_shaping_filter_needs_waviness_two():
    with pytest.raises(vehdyn.ParameterError, match="waviness"):
        road.RoadSpectrum.from_class("C", waviness=2.5).shaping_filter(20.0)


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("w", [2.0, 2.6])
def test_isotropic_coherence_against_the_2d_integral(w):
    """rho(n) = int S2(sqrt(n^2+m^2)) cos(2 pi m B) dm / int S2 dm with S2 ~ k^-(w+1) (Dodds & Robson)."""
    from scipy.integrate import quad

    B = 1.5
    for n in (0.01, 0.1, 0.3, 1.0):
        s2 = lambda m: (n**2 + m**2) ** (-(w + 1) / 2)  # noqa: E731
        num = quad(s2, 0, np.inf, weight="cos", wvar=2 * np.pi * B)[0]
        den = quad(s2, 0, np.inf)[0]
        assert road.isotropic_coherence(n, B, w) == pytest.approx(num / den, rel=1e-6)
    assert road.isotropic_coherence(0.0, B) == 1.0


def test_parallel_profiles_have_the_coherence():
    B = 1.5
    acc, amp = 0.0, 0.0
    for seed in range(300):
        left, right = road.synthesize_parallel_profiles("C", 50.0, 0.05, B, seed=seed, n_max=2.0)
        acc = acc + np.real(left.coefficients * np.conj(right.coefficients))
        amp = np.abs(left.coefficients) ** 2
        np.testing.assert_allclose(np.abs(right.coefficients) ** 2 <= 4 * amp + 1e-30, True)
    n = np.arange(left.coefficients.size) / 50.0
    rho_est = (acc / 300)[1:] / amp[1:]
    rho = road.isotropic_coherence(n[1:], B)
    # each estimate is a mean of 300 terms of std ~ sqrt((1 - rho^2)/2)
    assert np.max(np.abs(rho_est - rho)) < 5 * np.sqrt(0.5 / 300)


def test_shift_and_slope_are_exact_for_synthesized_profiles():
    p = road.synthesize_profile("C", 64.0, 0.02, seed=5, n_max=5.0)
    c = p.coefficients
    n = np.arange(c.size) / p.length

    def direct(x, deriv=False):
        e = np.exp(2j * np.pi * np.outer(x, n))
        return np.real(e @ (c * (2j * np.pi * n if deriv else 1)))

    x = p.distance
    np.testing.assert_allclose(p.elevation, direct(x), atol=1e-12)
    np.testing.assert_allclose(p.shifted(2.71).elevation, direct(x - 2.71), atol=1e-12)
    np.testing.assert_allclose(p.slope(), direct(x, True), atol=1e-10)
    t, u = p.road_inputs(20.0, {"_front": 0.0, "_rear": 2.71})
    np.testing.assert_allclose(u["road_velocity_rear"], 20.0 * direct(x - 2.71, True), atol=1e-9)
    np.testing.assert_allclose(t, x / 20.0)


# --------------------------------------------------------------------------- events
def test_events():
    x = np.linspace(0, 20, 2001)
    b = road.bump(x, 5.0, 2.0, 0.05)
    assert b.max() == pytest.approx(0.05) and x[np.argmax(b)] == pytest.approx(6.0)
    assert np.all(b[(x < 5) | (x > 7)] == 0)
    h = road.speed_hump(x, 10.0, 3.7, 0.1)
    assert h.max() == pytest.approx(0.1, rel=1e-9)
    # every point of the arc lies on one circle through the ends and the crest
    R = (3.7**2 / 4 + 0.1**2) / (2 * 0.1)
    inside = (x >= 10) & (x <= 13.7)
    np.testing.assert_allclose((x[inside] - 11.85) ** 2 + (h[inside] - (0.1 - R)) ** 2, R**2, rtol=1e-12)
    p = road.pothole(x, 2.0, 0.5, 0.04)
    assert p.min() == -0.04 and np.sum(p < 0) == 50
    pe = road.pothole(x, 2.0, 0.5, 0.04, edge_length=0.1)
    assert pe.min() == pytest.approx(-0.04) and np.all(pe >= -0.04) and pe[x == 2.0] == 0
    s = road.step(x, 4.0, 0.02)
    assert s[x < 4].max() == 0 and s[x >= 4].min() == 0.02
    prof = road.RoadProfile(x, b) + h
    assert prof.elevation.max() == pytest.approx(0.1)


def test_event_errors():
    x = np.linspace(0, 1, 11)
    with pytest.raises(vehdyn.ParameterError, match="length"):
        road.bump(x, 0.0, -1.0, 0.1)
    with pytest.raises(vehdyn.ParameterError, match="edge_length"):
        road.pothole(x, 0.0, 0.5, 0.1, edge_length=0.3)
    with pytest.raises(vehdyn.ParameterError, match="shape"):
        road.speed_hump(x, 0.0, shape="flat")


def test_parameter_errors():
    with pytest.raises(vehdyn.ParameterError, match="road class"):
        road.iso8608_class_value("Z")
    with pytest.raises(vehdyn.ParameterError, match="road_class"):
        road.iso8608_psd(-1e-6, 0.1)
    with pytest.raises(vehdyn.ParameterError, match="spatial frequency"):
        road.iso8608_psd("A", 0.0)
    with pytest.raises(vehdyn.ParameterError, match="speed"):
        road.RoadSpectrum.from_class("A").temporal_psd(1.0, 0.0)
    with pytest.raises(vehdyn.ParameterError, match="method"):
        road.synthesize_profile("A", 10, 0.1, method="magic")
    with pytest.raises(vehdyn.ParameterError, match="uniformly"):
        road.RoadProfile(np.array([0, 1, 3.0]), np.zeros(3))
    with pytest.raises(vehdyn.ParameterError, match="spacing"):
        road.iri(np.zeros(100))


# --------------------------------------------------------------------------- IRI
def test_golden_car_against_e_qc_goldencar(cases):
    case = cases["E-QC-GOLDENCAR"]
    modes = road.golden_car().modes()
    lam = modes.eigenvalues[modes.eigenvalues.imag > 0]
    lam = lam[np.argsort(np.abs(lam))]
    for k, mode in enumerate(("mode1", "mode2")):
        for part, val in (("real", lam[k].real), ("imag", lam[k].imag)):
            value, tol = tolerance(case, f"{mode}_eig_{part}")
            assert val == pytest.approx(value, rel=tol)


def _iri_sinusoid_closed_form(amplitude, wavelength, dx):
    """IRI [m/km] of z = a sin(2 pi x / lambda): steady state of the golden car solved by hand."""
    g = road.GOLDEN_CAR
    k1, k2, mu, c, V = (g[k] for k in ("tire_stiffness_ratio", "spring_stiffness_ratio", "mass_ratio",
                                       "damping_ratio", "speed"))
    w = 2 * np.pi * V / wavelength
    s = 1j * w
    # [s^2 + c s + k2, -(c s + k2); -(c s + k2), mu s^2 + c s + k2 + k1] [Zs; Zu] = [0; k1] Zr
    a11, a12, a22 = s**2 + c * s + k2, -(c * s + k2), mu * s**2 + c * s + k2 + k1
    det = a11 * a22 - a12**2
    zs, zu = -a12 * k1 / det, a11 * k1 / det
    k = round(0.25 / dx)
    smoothing = np.sin(k * np.pi * dx / wavelength) / (k * np.sin(np.pi * dx / wavelength))
    # mean |sin| = 2 / pi; IRI = mean |zs' - zu'| / V
    return 1000 * (2 / np.pi) * amplitude * w * abs(zs - zu) * abs(smoothing) / V


@pytest.mark.parametrize("wavelength", [2.4, 5.0, 15.0])
def test_iri_of_a_sinusoid(wavelength):
    dx, a = 0.05, 0.003
    x = np.arange(0, 3000, dx)
    z = a * np.sin(2 * np.pi * x / wavelength)
    assert road.iri(z, dx) == pytest.approx(_iri_sinusoid_closed_form(a, wavelength, dx), rel=2e-3)
    assert road.iri(road.RoadProfile(x, z)) == road.iri(z, dx)


def test_iri_of_a_ramp_is_zero():
    x = np.arange(0, 200, 0.1)
    assert road.iri(0.01 * x - 0.3, 0.1) == pytest.approx(0.0, abs=1e-9)


@settings(max_examples=10, deadline=None)
@given(st.floats(0.5, 3.0))
def test_iri_scales_with_amplitude(scale):
    p = road.synthesize_profile("C", 300, 0.1, seed=11)
    assert road.iri(scale * p.elevation, 0.1) == pytest.approx(scale * road.iri(p), rel=1e-9)


def test_more_parameter_errors():
    with pytest.raises(vehdyn.ParameterError, match="waviness"):
        road.RoadSpectrum(1e-4, waviness=7.0)
    with pytest.raises(vehdyn.ParameterError, match="cut_on"):
        road.RoadSpectrum(1e-4, cut_on=-0.1)
    with pytest.raises(vehdyn.ParameterError, match="gd0"):
        road.RoadSpectrum(0.0)
    with pytest.raises(vehdyn.ParameterError, match="no spatial frequency"):
        road.synthesize_profile("A", 10.0, 0.1, n_min=20.0)  # above the Nyquist frequency
    with pytest.raises(vehdyn.ParameterError, match="spacing"):
        road.synthesize_profile("A", 0.2, 0.1)
    with pytest.raises(vehdyn.ParameterError, match="depth"):
        road.pothole(np.linspace(0, 1, 11), 0.0, 0.5, -0.1)
    with pytest.raises(vehdyn.ParameterError, match="shorter"):
        road.iri(np.zeros(50), 0.1)
    with pytest.raises(vehdyn.ParameterError, match="n_low"):
        road.RoadSpectrum(1e-4).variance(1.0, 0.5)
    with pytest.raises(vehdyn.ParameterError, match="track_width"):
        road.isotropic_coherence(0.1, -1.0)


def test_iri_of_a_flat_road_and_infinite_band_variance():
    assert road.iri(np.zeros(1000), 0.1) == 0.0
    assert road.RoadSpectrum(1e-4).variance(0.0, 1.0) == np.inf  # n^-2 has no finite variance down to n = 0


# ISO 8608 class limits of Gd(n0) [1e-6 m^3] (lower, upper); A has no lower limit, H no upper one
ISO8608_LIMITS = {"A": (0, 32), "B": (32, 128), "C": (128, 512), "D": (512, 2048), "E": (2048, 8192),
                  "F": (8192, 32768), "G": (32768, 131072), "H": (131072, np.inf)}


def test_class_of_against_the_class_limits():
    for letter, (lo, hi) in ISO8608_LIMITS.items():
        assert road.iso8608_class_of(max(lo, 1.0) * 1e-6 * 1.001) == letter
        if np.isfinite(hi):
            assert road.iso8608_class_of(hi * 1e-6 * 0.999) == letter
        assert road.iso8608_class_of(ISO8608_GEOMETRIC_MEANS[letter] * 1e-6) == letter


@pytest.mark.parametrize("letter", ["B", "D"])
def test_estimate_spectrum_of_a_synthesized_profile(letter):
    p = road.synthesize_profile(letter, 1000.0, 0.05, seed=21)
    gd0, cls = road.estimate_spectrum(p)
    assert cls == letter
    assert gd0 == pytest.approx(road.iso8608_class_value(letter), rel=0.15)
    with pytest.raises(vehdyn.ParameterError, match="band"):
        road.estimate_spectrum(p, n_low=20.0)


def test_golden_car_is_the_quarter_car_of_its_ratios():
    """ASTM E1926's golden car (road.golden_car, written from the standard's equations) against
    vehdyn.ride.QuarterCar built from the same ratios: the same matrices."""
    from vehdyn.ride import QuarterCar

    g = road.GOLDEN_CAR
    quarter = QuarterCar.from_parameters(sprung_mass=1.0, unsprung_mass=g["mass_ratio"],
                                         spring_rate=g["spring_stiffness_ratio"], damping=g["damping_ratio"],
                                         tire_stiffness=g["tire_stiffness_ratio"])
    golden = road.golden_car()
    states = [quarter.index(name) for name in golden.state_names]
    np.testing.assert_allclose(quarter.A[np.ix_(states, states)], golden.A, rtol=1e-15, atol=0)
    k = quarter.index("road_displacement", "inputs")
    np.testing.assert_allclose(quarter.B[states, k], golden.B[:, 0], rtol=1e-15, atol=0)
    j = quarter.index("suspension_velocity", "outputs")
    np.testing.assert_allclose(quarter.C[j, states], golden.C[0], rtol=1e-15, atol=0)
