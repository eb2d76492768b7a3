"""Inertia tensors: primitives against numerical integration, composites against the hand result."""

import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vehdyn import ParameterError
from vehdyn.mechanics import (
    InertiaTensor,
    MassProperties,
    composite,
    hollow_cylinder,
    hollow_sphere,
    inertia_matrix,
    parallel_axis_shift,
    slender_rod,
    solid_box,
    solid_cone,
    solid_cylinder,
    solid_sphere,
)

DATA = Path(__file__).resolve().parents[1] / "data" / "rigid_body_reference.json"


# ----------------------------------------------------------------------------- sign convention
def test_products_of_inertia_enter_the_matrix_negated():
    """The pitfall H-NE-1 of the shared reference README: matrix entries are -Ixy, -Ixz, -Iyz."""
    tensor = InertiaTensor(1.0, 2.0, 2.5, ixy=0.1, ixz=0.2, iyz=0.3)
    np.testing.assert_array_equal(tensor.matrix, [[1.0, -0.1, -0.2], [-0.1, 2.0, -0.3], [-0.2, -0.3, 2.5]])
    assert InertiaTensor.from_matrix(tensor.matrix) == tensor
    np.testing.assert_array_equal(np.asarray(tensor), tensor.matrix)


def test_point_masses_give_products_as_integrals_x_z_dm():
    """Ixz = sum m x z for point masses: two masses at (+1, 0, +1) and (-1, 0, -1) give Ixz = +2 m."""
    body = composite([MassProperties(1.0, (1.0, 0.0, 1.0)), MassProperties(1.0, (-1.0, 0.0, -1.0))])
    assert body.inertia.ixz == pytest.approx(2.0)
    assert body.inertia.matrix[0, 2] == pytest.approx(-2.0)
    assert body.inertia.iyy == pytest.approx(4.0)


# ----------------------------------------------------------------------------- primitives
def voxel_tensor(inside, half_extent, n=96):
    """Inertia per unit mass of a uniform solid from a midpoint voxel sum over its bounding box."""
    c = (np.arange(n) + 0.5) / n * 2 - 1
    x, y, z = np.meshgrid(c * half_extent[0], c * half_extent[1], c * half_extent[2], indexing="ij")
    mask = inside(x, y, z)
    x, y, z = x[mask], y[mask], z[mask]
    centre = np.array([x.mean(), y.mean(), z.mean()])
    x, y, z = x - centre[0], y - centre[1], z - centre[2]
    per_mass = np.array([np.mean(y * y + z * z), np.mean(z * z + x * x), np.mean(x * x + y * y)])
    return per_mass, centre


@pytest.mark.parametrize("name, tensor, inside, half_extent", [
    ("box", solid_box(1.0, 0.6, 0.4, 0.2), lambda x, y, z: np.ones_like(x, bool), (0.3, 0.2, 0.1)),
    ("cylinder", solid_cylinder(1.0, 0.3, 0.5, axis="x"), lambda x, y, z: y * y + z * z <= 0.09, (0.25, 0.3, 0.3)),
    ("tube", hollow_cylinder(1.0, 0.3, 0.2, 0.8, axis="y"),
     lambda x, y, z: (x * x + z * z <= 0.09) & (x * x + z * z >= 0.04), (0.3, 0.4, 0.3)),
    ("sphere", solid_sphere(1.0, 0.25), lambda x, y, z: x * x + y * y + z * z <= 0.0625, (0.25, 0.25, 0.25)),
    # cone along z, base at z = -0.3 (radius 0.2), apex at z = +0.3
    ("cone", solid_cone(1.0, 0.2, 0.6, axis="z"),
     lambda x, y, z: np.sqrt(x * x + y * y) <= 0.2 * (0.3 - z) / 0.6, (0.2, 0.2, 0.3)),
])
def test_primitives_against_voxel_integration(name, tensor, inside, half_extent):
    per_mass, centre = voxel_tensor(inside, half_extent)
    np.testing.assert_allclose([tensor.ixx, tensor.iyy, tensor.izz], per_mass, rtol=1.5e-2)
    if name == "cone":  # centre of mass a quarter of the height above the base
        assert centre[2] == pytest.approx(-0.3 + 0.6 / 4, abs=2e-3)


def test_thin_shells_and_rod_closed_forms():
    # thin-walled tube: m r^2 about its axis; hollow sphere 2/3 m r^2; rod about its end m L^2/3
    assert hollow_cylinder(2.0, 0.5, 0.5, 0.0, axis="z").izz == pytest.approx(2.0 * 0.25)
    shell = hollow_sphere(3.0, 0.4)
    # shell from a fine Fibonacci lattice on the sphere
    k = np.arange(200000) + 0.5
    polar = np.arccos(1 - 2 * k / k.size)
    azimuth = np.pi * (1 + 5**0.5) * k
    x, y = 0.4 * np.sin(polar) * np.cos(azimuth), 0.4 * np.sin(polar) * np.sin(azimuth)
    assert shell.izz == pytest.approx(3.0 * np.mean(x * x + y * y), rel=1e-4)
    rod = slender_rod(2.0, 1.5, axis="x")
    assert rod.ixx == 0.0 and not rod.is_positive_definite
    about_end = rod.shifted(2.0, [0.75, 0.0, 0.0])
    assert about_end.iyy == pytest.approx(2.0 * 1.5**2 / 3) and about_end.izz == pytest.approx(2.0 * 1.5**2 / 3)


# ----------------------------------------------------------------------------- composites
def test_composite_of_two_boxes_against_the_hand_result():
    box_a = MassProperties(3.0, (0.0, 0.0, 0.0), solid_box(3.0, 0.4, 0.2, 0.1))
    box_b = MassProperties(1.0, (0.5, 0.0, -0.3), solid_box(1.0, 0.2, 0.2, 0.2))
    body = composite([box_a, box_b])
    # by hand: m = 4 kg, G = (3*0 + 1*0.5, 0, 3*0 + 1*(-0.3)) / 4 = (0.125, 0, -0.075) m
    assert body.mass == 4.0
    np.testing.assert_allclose(body.centre_of_mass, [0.125, 0.0, -0.075], atol=1e-15)
    # offsets of the part centres from G: d_a = (-0.125, 0, 0.075), d_b = (0.375, 0, -0.225)
    own_a = (3 * (0.2**2 + 0.1**2) / 12, 3 * (0.1**2 + 0.4**2) / 12, 3 * (0.4**2 + 0.2**2) / 12)
    own_b = 1 * (0.2**2 + 0.2**2) / 12
    ixx = own_a[0] + 3 * 0.075**2 + own_b + 1 * 0.225**2
    iyy = own_a[1] + 3 * (0.125**2 + 0.075**2) + own_b + 1 * (0.375**2 + 0.225**2)
    izz = own_a[2] + 3 * 0.125**2 + own_b + 1 * 0.375**2
    ixz = 3 * (-0.125) * 0.075 + 1 * 0.375 * (-0.225)  # sum m dx dz = -0.1125 kg m^2
    assert (ixx, iyy, izz, ixz) == pytest.approx((0.0866666667, 0.3041666667, 0.2441666667, -0.1125), rel=1e-9)
    got = body.inertia
    assert (got.ixx, got.iyy, got.izz, got.ixz) == pytest.approx((ixx, iyy, izz, ixz), rel=1e-13)
    assert got.ixy == 0.0 and got.iyz == 0.0
    # about the origin (box A's centre) by the parallel-axis shift of the composite
    about_origin = body.inertia_about((0.0, 0.0, 0.0))
    assert about_origin.ixz == pytest.approx(1 * 0.5 * (-0.3), rel=1e-13)


@settings(max_examples=50, deadline=None)
@given(dims=st.lists(st.floats(0.05, 3.0), min_size=3, max_size=3), fraction=st.floats(0.05, 0.95),
       axis=st.integers(0, 2), mass=st.floats(0.1, 1000.0))
def test_box_cut_in_two_recomposes_to_the_box(dims, fraction, axis, mass):
    """Two slices of one homogeneous box, composed, are the whole box (closed form)."""
    parts = []
    for share, sign in ((fraction, -1.0), (1 - fraction, 1.0)):
        part_dims = list(dims)
        part_dims[axis] = dims[axis] * share
        centre = np.zeros(3)
        centre[axis] = sign * (dims[axis] / 2 - part_dims[axis] / 2)
        parts.append(MassProperties(mass * share, centre, solid_box(mass * share, *part_dims)))
    body = composite(parts)
    whole = solid_box(mass, *dims)
    np.testing.assert_allclose(body.centre_of_mass, 0.0, atol=1e-12 * max(dims))
    np.testing.assert_allclose(body.inertia.matrix, whole.matrix, rtol=1e-10, atol=1e-12 * np.max(whole.matrix))


def test_parallel_axis_round_trip_and_point_mass():
    tensor = InertiaTensor(2.0, 3.0, 4.0, ixy=0.2, ixz=-0.3, iyz=0.1)
    offset = [0.3, -0.5, 0.7]
    shifted = tensor.shifted(5.0, offset)
    assert shifted.ixx == pytest.approx(2.0 + 5.0 * (0.25 + 0.49))
    assert shifted.ixz == pytest.approx(-0.3 + 5.0 * 0.3 * 0.7)
    back = shifted.to_centre_of_mass(5.0, offset)
    np.testing.assert_allclose(back.matrix, tensor.matrix, rtol=1e-13, atol=1e-14)
    np.testing.assert_allclose(parallel_axis_shift(5.0, offset), shifted.matrix - tensor.matrix, atol=1e-14)
    batch = parallel_axis_shift(np.array([1.0, 2.0]), np.array([[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]))
    np.testing.assert_allclose(batch[..., 1], np.diag([2.0, 0.0, 2.0]))


# ----------------------------------------------------------------------------- principal axes
def test_principal_moments_and_axes_of_H_EULER_FULLTENSOR():
    case = next(c for c in json.loads(DATA.read_text())["cases"] if c["id"] == "H-EULER-FULLTENSOR")
    tensor = InertiaTensor.from_matrix(case["inputs"]["I_body_tensor"][0])
    moments, axes = tensor.principal()
    np.testing.assert_allclose(moments, [case["expected"][k][0] for k in ("eig_min", "eig_mid", "eig_max")],
                               rtol=1e-11)
    # the case's construction: I = R diag(1, 2, 3) R^T with R = Rz(30 deg) Rx(20 deg)
    a, b = np.radians(30.0), np.radians(20.0)
    rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    rx = np.array([[1, 0, 0], [0, np.cos(b), -np.sin(b)], [0, np.sin(b), np.cos(b)]])
    expected_axes = rz @ rx
    for k in range(3):
        assert abs(axes[:, k] @ expected_axes[:, k]) == pytest.approx(1.0, abs=1e-10)
    assert np.linalg.det(axes) == pytest.approx(1.0)
    np.testing.assert_allclose(axes @ np.diag(moments) @ axes.T, tensor.matrix, atol=1e-12)
    rebuilt = InertiaTensor.from_principal([1.0, 2.0, 3.0], expected_axes)
    np.testing.assert_allclose(rebuilt.matrix, tensor.matrix, atol=1e-10)
    # rotating into the principal axes diagonalizes it
    np.testing.assert_allclose(tensor.rotated(axes.T).matrix, np.diag(moments), atol=1e-12)
    assert tensor.moment_about(axes[:, 2]) == pytest.approx(3.0, rel=1e-12)


def test_radius_of_gyration_round_trip():
    # E-BP-1600 (shared reference cases): a 1600 kg car with pitch radius of gyration 0.95 m
    tensor = InertiaTensor.from_radii_of_gyration(1600.0, 0.5, 0.95, 1.0)
    assert tensor.iyy == pytest.approx(1600.0 * 0.95**2)
    np.testing.assert_allclose(tensor.radius_of_gyration(1600.0), [0.5, 0.95, 1.0], rtol=1e-15)


# ----------------------------------------------------------------------------- validation
@pytest.mark.parametrize("args, kwargs, key", [
    ((-1.0, 2.0, 2.0), {}, "ixx"),
    ((1.0, 1.0, 3.0), {}, "izz"),  # triangle inequality about the given axes
    ((1.0, 1.0, 1.0), {"ixy": 0.6}, "ixy, ixz, iyz"),  # principal moments 0.4, 1, 1.6 break it
    ((1.0, 1.0, 1.0), {"ixy": 1.5}, "ixy, ixz, iyz"),  # not positive semi-definite
    ((float("nan"), 1.0, 1.0), {}, "ixx"),
    (("1", 1.0, 1.0), {}, "ixx"),
    ((1.0, 1.0, 1.0), {"iyz": float("inf")}, "iyz"),
])
def test_inertia_tensor_rejects_unphysical_values(args, kwargs, key):
    with pytest.raises(ParameterError) as info:
        InertiaTensor(*args, **kwargs)
    assert info.value.key == key


def test_thin_plate_on_the_triangle_equality_is_accepted():
    plate = solid_box(1.0, 0.3, 0.7, 1e-9)  # Izz = Ixx + Iyy up to rounding
    assert plate.izz == pytest.approx(plate.ixx + plate.iyy)


@pytest.mark.parametrize("call, key", [
    (lambda: InertiaTensor.from_matrix([[1, 0.5, 0], [0, 1, 0], [0, 0, 1]]), "inertia"),
    (lambda: InertiaTensor.from_matrix(np.eye(2)), "inertia"),
    (lambda: InertiaTensor.from_principal([1.0, 2.0]), "moments"),
    (lambda: InertiaTensor(1, 1, 1).rotated(np.diag([1.0, 1.0, -1.0])), "rotation"),
    (lambda: InertiaTensor(1, 1, 1).moment_about([0.0, 0.0, 0.0]), "direction"),
    (lambda: InertiaTensor(1, 1, 1).radius_of_gyration(0.0), "mass"),
    (lambda: InertiaTensor(1, 1, 1).to_centre_of_mass(10.0, [1.0, 0.0, 0.0]), "iyy"),
    (lambda: solid_box(0.0, 1, 1, 1), "mass"),
    (lambda: solid_box(1.0, 1, -1, 1), "width_y"),
    (lambda: hollow_cylinder(1.0, 0.2, 0.3, 1.0), "inner_radius"),
    (lambda: solid_cylinder(1.0, 0.2, 1.0, axis="w"), "axis"),
    (lambda: solid_cone(1.0, 0.2, 0.0), "height"),
    (lambda: solid_sphere(1.0, float("nan")), "radius"),
    (lambda: composite([]), "parts"),
    (lambda: MassProperties(1.0, (0.0, 0.0)), "centre_of_mass"),
    (lambda: MassProperties(-1.0), "mass"),
    (lambda: parallel_axis_shift(-1.0, [1, 0, 0]), "mass"),
    (lambda: parallel_axis_shift(1.0, [1, 0]), "offset"),
    (lambda: inertia_matrix(slender_rod(1.0, 1.0)), "inertia"),
    (lambda: inertia_matrix(np.full((3, 3), np.nan)), "inertia"),
])
def test_error_paths_name_the_parameter(call, key):
    with pytest.raises(ParameterError) as info:
        call()
    assert info.value.key == key


def test_inertia_tensor_is_frozen():
    tensor = InertiaTensor(1.0, 1.0, 1.0)
    with pytest.raises(AttributeError):
        tensor.ixx = 2.0
    moved = MassProperties(2.0, (1.0, 0.0, 0.0), solid_sphere(2.0, 0.1)).moved([0.0, 1.0, 0.0])
    assert moved.centre_of_mass == (1.0, 1.0, 0.0)
    turned = MassProperties(2.0, (1.0, 0.0, 0.0), solid_box(2.0, 1, 0.5, 0.2)).rotated(
        [[0, -1, 0], [1, 0, 0], [0, 0, 1]])
    np.testing.assert_allclose(turned.centre_of_mass, (0.0, 1.0, 0.0), atol=1e-15)
    assert turned.inertia.ixx == pytest.approx(solid_box(2.0, 1, 0.5, 0.2).iyy)


def test_tensors_about_one_point_add_and_round_trip_through_a_dict():
    half = solid_box(1.0, 0.4, 0.2, 0.2)
    np.testing.assert_allclose((half + half).matrix, solid_box(2.0, 0.4, 0.2, 0.2).matrix, rtol=1e-15)
    tensor = InertiaTensor(2.0, 3.0, 4.0, ixz=-0.3)
    assert InertiaTensor.from_dict(tensor.to_dict()) == tensor
    assert InertiaTensor.units()["ixz"] == "kg*m^2"
