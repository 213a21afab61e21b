# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The beam element, sections and condensation against closed forms.

Closed forms: Timoshenko cantilever (Timoshenko & Gere, Mechanics of Materials,
tip deflection P L^3 / (3 E I) + P L / (kappa G A), tip rotation P L^2 / (2 E I)),
axial P L / (E A), Saint-Venant torsion T L / (G J). A two-node Timoshenko
element with these stiffness terms is exact for end loads, so one element must
reproduce them to round-off.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from vd_solvers.errors import SolverError
from vd_solvers.flex import section as sec
from vd_solvers.flex.beam import element_stiffness
from vd_solvers.flex.component import ShapePoint, build, condense

STEEL = sec.Material.from_poisson(210e9, 0.3, 7850.0)
L = 0.35


def _cantilever(direction: np.ndarray, section: sec.Section, load: np.ndarray) -> np.ndarray:
    """Tip displacement (6,) of a one-element cantilever along ``direction``."""
    k = element_stiffness(np.zeros(3), L * direction, STEEL, section)
    return np.linalg.solve(k[6:, 6:], load)


@pytest.mark.parametrize('shape', ['solid_round', 'tube', 'rectangle', 'i_beam'])
def test_cantilever_bending_in_both_planes(shape):
    s = {'solid_round': lambda: sec.solid_round(0.02, 0.3),
         'tube': lambda: sec.tube(0.025, 0.0025, 0.3),
         'rectangle': lambda: sec.rectangle(0.03, 0.05, 0.3),
         'i_beam': lambda: sec.i_beam(0.06, 0.04, 0.006, 0.005)}[shape]()
    e, g, p = STEEL.youngs_modulus, STEEL.shear_modulus, 1000.0
    x = np.array([1.0, 0.0, 0.0])  # local y = vehicle y, local z = vehicle z
    tip = _cantilever(x, s, np.array([0, 0, p, 0, 0, 0.0]))  # vertical load: bends about y
    assert tip[2] == pytest.approx(p * L**3 / (3 * e * s.iy) + p * L / (g * s.shear_area_z),
                                   rel=1e-12)
    assert tip[4] == pytest.approx(-p * L**2 / (2 * e * s.iy), rel=1e-12)
    tip = _cantilever(x, s, np.array([0, p, 0, 0, 0, 0.0]))  # lateral load: bends about z
    assert tip[1] == pytest.approx(p * L**3 / (3 * e * s.iz) + p * L / (g * s.shear_area_y),
                                   rel=1e-12)
    assert tip[5] == pytest.approx(p * L**2 / (2 * e * s.iz), rel=1e-12)


def test_axial_and_torsion():
    s = sec.tube(0.025, 0.0025, 0.3)
    d = np.array([0.3, 0.5, -0.2]) / np.linalg.norm([0.3, 0.5, -0.2])  # any direction
    tip = _cantilever(d, s, np.r_[5000.0 * d, 0, 0, 0])
    assert tip[:3] @ d == pytest.approx(5000.0 * L / (STEEL.youngs_modulus * s.area), rel=1e-12)
    tip = _cantilever(d, s, np.r_[0, 0, 0, 50.0 * d])
    assert tip[3:] @ d == pytest.approx(50.0 * L / (STEEL.shear_modulus * s.j), rel=1e-12)


def test_section_properties_closed_forms():
    d = 0.022
    s = sec.solid_round(d, 0.3)
    assert s.area == pytest.approx(math.pi * d**2 / 4)
    assert s.j == pytest.approx(math.pi * d**4 / 32)
    # Cowper (1966), solid circle: kappa = 6(1+nu)/(7+6nu) = 0.886 for nu = 0.3
    assert s.shear_area_y / s.area == pytest.approx(6 * 1.3 / 8.8)
    r = sec.rectangle(0.02, 0.02, 0.3)  # square: Roark J = 0.1406 a^4
    assert r.j == pytest.approx(0.1406 * 0.02**4, rel=2e-3)


def test_euler_bernoulli_when_no_shear_area():
    s = sec.Section(4e-4, 5e-8, 8e-8, 3e-8)  # general section without shear areas
    tip = _cantilever(np.array([1.0, 0, 0]), s, np.array([0, 0, 100.0, 0, 0, 0]))
    assert tip[2] == pytest.approx(100.0 * L**3 / (3 * STEEL.youngs_modulus * s.iy), rel=1e-12)


def test_condensation_reproduces_the_full_model():
    """
    Check that the condensed stiffness gives the full model's attachment displacements.

    The loads are static loads at the attachment nodes (Guyan reduction is exact for
    statics).
    """
    pts = {'front': np.array([0.26, 0.2, 0.2]), 'rear': np.array([-0.26, 0.19, 0.22]),
           'outer': np.array([0.02, 0.62, 0.18]), 'seat': np.array([0.0, 0.45, 0.25])}
    comp = build('arm', pts, [('front', 'outer'), ('rear', 'outer')], STEEL,
                 sec.tube(0.03, 0.003, 0.3), attachments=['seat'], elements_per_member=5,
                 shape_points=[ShapePoint('front', 'outer', 0.4, (0.0, 0.0, 0.03))])
    frame = comp.full
    assert frame is not None and frame.positions.shape[0] > len(comp.nodes)
    rng = np.random.default_rng(1)
    load = rng.normal(size=6 * len(comp.nodes)) * 1e3
    load[:6] = 0.0  # node 'front' clamped
    n = frame.positions.shape[0]
    f_full = np.zeros(6 * n)
    f_full[: 6 * len(comp.nodes)] = load
    u_full = np.linalg.solve(frame.stiffness[6:, 6:], f_full[6:])
    u_red = np.linalg.solve(comp.stiffness[6:, 6:], load[6:])
    np.testing.assert_allclose(u_red, u_full[: 6 * len(comp.nodes) - 6], rtol=1e-9, atol=1e-15)


def test_condensed_component_has_exactly_six_rigid_modes():
    pts = {'a': np.zeros(3), 'b': np.array([0.4, 0.0, 0.0]), 'c': np.array([0.2, 0.3, 0.0])}
    comp = build('tri', pts, [('a', 'c'), ('b', 'c')], STEEL, sec.solid_round(0.02, 0.3))
    values = np.linalg.eigvalsh(comp.stiffness)
    assert np.sum(np.abs(values) < 1e-10 * values.max()) == 6
    # the rigid modes are the null space: a rigid rotation of all nodes stores nothing
    w = np.array([0.1, -0.2, 0.3])
    u = np.concatenate([np.r_[np.cross(w, comp.positions[i]), w] for i in range(3)])
    assert u @ comp.stiffness @ u == pytest.approx(0.0, abs=1e-9 * (values.max() * u @ u))


def test_mass_and_centre_of_mass_from_the_elements():
    pts = {'a': np.zeros(3), 'b': np.array([0.5, 0.0, 0.0])}
    s = sec.solid_round(0.02, 0.3)
    comp = build('rod', pts, [('a', 'b')], STEEL, s, elements_per_member=3)
    assert comp.mass == pytest.approx(STEEL.density * s.area * 0.5)
    np.testing.assert_allclose(comp.cog, [0.25, 0.0, 0.0], atol=1e-15)


def test_condense_keeps_masters_only():
    k = element_stiffness(np.zeros(3), np.array([1.0, 0, 0]), STEEL, sec.solid_round(0.02, 0.3))
    assert condense(k, np.array([0, 1])).shape == (12, 12)


@pytest.mark.parametrize('make, message', [
    (lambda: sec.solid_round(0.0, 0.3), 'solid_round section: diameter must be positive, got 0.0'),
    (lambda: sec.tube(0.02, 0.01, 0.3), 'tube section: wall 0.01 m leaves no bore in outer '
                                         'diameter 0.02 m (use solid_round)'),
    (lambda: sec.Section(-1e-4, 1e-8, 1e-8, 1e-8), 'general section: area must be positive, '
                                                   'got -0.0001'),
])
def test_bad_sections_are_refused(make, message):
    with pytest.raises(SolverError) as err:
        make()
    assert str(err.value) == message


def test_coincident_member_points_are_refused():
    pts = {'a': np.zeros(3), 'b': np.array([0.004, 0.0, 0.0])}
    with pytest.raises(SolverError) as err:
        build('lca', pts, [('a', 'b')], STEEL, sec.solid_round(0.02, 0.3))
    assert (
        str(err.value)
        == "component 'lca': hard points 'a' and 'b' coincide (a member needs length)"
    )


def test_disconnected_frame_is_refused():
    pts = {'a': np.zeros(3), 'b': np.array([0.3, 0, 0]), 'c': np.array([0, 1, 0]),
           'd': np.array([0.3, 1, 0])}
    with pytest.raises(SolverError, match='zero-stiffness deformation mode'):
        build('two', pts, [('a', 'b'), ('c', 'd')], STEEL, sec.solid_round(0.02, 0.3))
