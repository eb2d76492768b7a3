"""Soils and Bekker's closed forms: the shipped table against its published source, round trips,
and every bad-input path."""

import math
import tomllib

import numpy as np
import pytest

import vehdyn
from vehdyn import ParameterError
from vehdyn.tire.terramechanics import (Soil, bekker_pressure, bulldozing_resistance, compaction_resistance,
                                        load_soil, parabolic_wheel_sinkage, plate_sinkage, rigid_wheel_sinkage,
                                        shipped_soils, soil_source)

SAND = dict(n=1.1, k_c=990.0, k_phi=1528.43e3, cohesion=1040.0, friction_angle=math.radians(28.0),
            shear_modulus=0.025)


def test_dry_sand_matches_wong_table_2_3():
    # Wong, Theory of Ground Vehicles, 4th ed. (2008), Table 2.3: dry sand (LLL), in kN and kPa
    soil = load_soil("dry_sand")
    assert soil.n == 1.1
    assert soil.k_c == pytest.approx(0.99e3)
    assert soil.k_phi == pytest.approx(1528.43e3)
    assert soil.cohesion == pytest.approx(1.04e3)
    assert soil.friction_angle == pytest.approx(math.radians(28.0))
    assert "Wong 2008" in soil_source("dry_sand")


@pytest.mark.parametrize("name, n, k_c, k_phi, cohesion, phi", [
    # the hand-transcribed rows against an independent transcription of the same table (Wong 2008
    # Table 2.3, SI columns: kN/m^(n+1), kN/m^(n+2), kPa, deg; a public Project Chrono SCM script,
    # see data/soils.toml): heavy clay at 40 % moisture (WES) and "Snow (U.S.)"
    ("heavy_clay", 0.11, 1.84, 103.27, 20.69, 6.0),
    ("snow", 1.6, 4.37, 196.72, 1.03, 19.7),
    ("lete_sand", 0.79, 102.0, 5301.0, 1.3, 31.1),
])
def test_hand_transcribed_rows_match_an_independent_transcription(name, n, k_c, k_phi, cohesion, phi):
    soil = load_soil(name)
    assert soil.n == n
    assert (soil.k_c, soil.k_phi, soil.cohesion) == pytest.approx((k_c * 1e3, k_phi * 1e3, cohesion * 1e3), rel=1e-12)
    assert math.degrees(soil.friction_angle) == pytest.approx(phi, rel=1e-12)
    # converted back to U.S. units (lb/in^(n+1), lb/in^(n+2)) the moduli of these rows are values of
    # two significant digits (snow 0.070, 0.080; heavy clay 7.0, 10) to within the rounding of the SI
    # columns (< 0.3 %): a check on the digits, which a mistyped digit would fail. LETE sand is
    # Wong's own measurement, not a conversion.
    if name != "lete_sand":
        lbf, inch = 4.4482216152605, 0.0254
        for value in (soil.k_c * inch ** (n + 1) / lbf, soil.k_phi * inch ** (n + 2) / lbf):
            two_digits = round(value, 1 - math.floor(math.log10(value)))
            assert abs(value / two_digits - 1.0) < 3e-3


def test_every_shipped_soil_loads_in_si_with_its_source():
    with open(vehdyn.data_path("soils.toml"), "rb") as f:
        raw = tomllib.load(f)
    assert {"dry_sand", "sandy_loam", "clayey_soil", "heavy_clay", "snow", "lunar_soil"} <= set(shipped_soils())
    for name in shipped_soils():
        entry, soil = raw[name], load_soil(name)
        assert entry["source"] and entry["units"]
        # kN -> N, kPa -> Pa, deg -> rad, cm -> m: independent of the loader's table
        assert soil.k_phi == pytest.approx(entry["k_phi"] * 1e3)
        assert soil.cohesion == pytest.approx(entry["cohesion"] * 1e3)
        assert math.degrees(soil.friction_angle) == pytest.approx(entry["friction_angle"])
        assert soil.shear_modulus == pytest.approx(entry["shear_modulus"] / 100.0)
        assert soil.name == name


def test_user_file_round_trip(tmp_path):
    path = tmp_path / "my_soils.toml"
    path.write_text('[wet]\nn = 0.5\nk_c = 2.0\nk_phi = 300.0\ncohesion = 3.0\nfriction_angle = 0.2\n'
                    'shear_modulus = 0.01\n[wet.units]\nk_c = "kN/m^(n+1)"\nk_phi = "kN/m^(n+2)"\n'
                    'cohesion = "kPa"\nfriction_angle = "rad"\nshear_modulus = "m"\n')
    soil = load_soil(path)
    assert soil == load_soil(f"{path}:wet")
    assert soil == Soil(n=0.5, k_c=2e3, k_phi=3e5, cohesion=3e3, friction_angle=0.2, shear_modulus=0.01, name="wet")


@pytest.mark.parametrize("field, value", [("n", 0.0), ("n", -0.5), ("friction_angle", math.pi / 2),
                                          ("friction_angle", 1.7), ("cohesion", -1.0), ("shear_modulus", 0.0),
                                          ("k_phi", math.nan)])
def test_bad_soil_names_field_and_value(field, value):
    with pytest.raises(ParameterError) as info:
        Soil(**{**SAND, field: value})
    assert info.value.key == field
    assert repr(value) in str(info.value) or str(value) in str(info.value)


def test_bad_table_entries(tmp_path):
    with pytest.raises(ParameterError, match="no shipped soil 'quicksand'"):
        load_soil("quicksand")
    path = tmp_path / "s.toml"
    path.write_text('[a]\nn = 1.0\nk_c = 1.0\nk_phi = 1.0\ncohesion = 1.0\nfriction_angle = 95.0\n'
                    'shear_modulus = 1.0\n[a.units]\nk_c = "kN/m^(n+1)"\nk_phi = "kN/m^(n+2)"\ncohesion = "kPa"\n'
                    'friction_angle = "deg"\nshear_modulus = "furlong"\n')
    with pytest.raises(ParameterError, match="furlong") as info:
        load_soil(path)
    assert info.value.key == "a.units.shear_modulus"
    path.write_text(path.read_text().replace("furlong", "cm"))
    with pytest.raises(ParameterError) as info:  # 95 degrees
        load_soil(path)
    assert info.value.key == "a.friction_angle"


def test_pressure_sinkage_round_trip_and_errors():
    soil = load_soil("sandy_loam")
    z = np.array([0.0, 0.01, 0.05])
    p = bekker_pressure(soil, z, 0.3)
    assert p[1] == pytest.approx((5.27e3 / 0.3 + 1515.04e3) * 0.01**0.7)
    assert plate_sinkage(soil, p, 0.3) == pytest.approx(z)
    with pytest.raises(ParameterError, match="sinkage") as info:
        bekker_pressure(soil, -0.01, 0.3)
    assert info.value.value == -0.01
    with pytest.raises(ParameterError, match="width"):
        bekker_pressure(soil, 0.01, 0.0)
    with pytest.raises(ParameterError, match="load") as info:
        rigid_wheel_sinkage(soil, -100.0, 0.6, 0.2)
    assert info.value.key == "load"


def test_closed_forms_agree_with_each_other():
    # n = 1: Bekker's (3 - n)/3 equals the exact parabola integral B(2, 1/2)/2 = 2/3
    soil = load_soil("lunar_soil")
    assert rigid_wheel_sinkage(soil, 800.0, 0.5, 0.15) == pytest.approx(parabolic_wheel_sinkage(soil, 800.0, 0.5, 0.15),
                                                                       rel=1e-12)
    # compaction resistance = work per unit length of pressing the plate to z0: b int_0^z0 p dz
    from scipy.integrate import quad

    z0 = rigid_wheel_sinkage(soil, 800.0, 0.5, 0.15)
    work = 0.15 * quad(lambda z: bekker_pressure(soil, z, 0.15), 0.0, z0)[0]
    assert compaction_resistance(soil, 800.0, 0.5, 0.15) == pytest.approx(work, rel=1e-10)


def test_bulldozing_is_rankine_passive_pressure():
    soil = load_soil("dry_sand")
    z, b = 0.05, 0.2
    # Rankine: the passive pressure grows linearly with depth, integrate over the wall
    n_phi = math.tan(math.pi / 4 + soil.friction_angle / 2) ** 2
    gamma = soil.density * vehdyn.units.GRAVITY
    from scipy.integrate import quad

    force = b * quad(lambda d: gamma * d * n_phi + 2 * soil.cohesion * math.sqrt(n_phi), 0, z)[0]
    assert bulldozing_resistance(soil, z, b) == pytest.approx(force, rel=1e-12)
