# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Tests of the flexible components inside the K&C model.

Covered: objectivity of the co-rotational embedding, the rigid limit, softening,
the beam anti-roll bar against G J / L, imported stiffness equal to the generated
one, and the thesis' trends (5.1).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from vd_data_server.study import load_study
from vd_solvers.errors import SolverError
from vd_solvers.flex import section as sec
from vd_solvers.flex.imported import from_dmig, from_plain, mirror_stiffness
from vd_solvers.kc.assembly import assemble
from vd_solvers.kc.events import KCModel
from vd_solvers.kc.forces import MatrixLaw
from vd_solvers.kc.from_config import suspension_input
from vd_solvers.kc.metrics import derived_metrics
from vd_solvers.kc.model import FlexSpec, StabilizerSpec
from vd_solvers.kc.solver import rotation_vectors_to_matrices
from vd_solvers.kc.system import LoadCase

EVENTS = ('parallel_wheel_travel', 'opposite_wheel_travel', 'lateral_force',
          'longitudinal_force')
STEPS = 11


@pytest.fixture(scope='module')
def studies():
    from pathlib import Path

    root = Path(__file__).resolve().parents[3] / 'src' / 'vd_data_server' / 'data' / 'studies'
    return {v: load_study(root / f'{v}.yaml') for v in ('sedan', 'hmmwv')}


def _inputs(studies, fidelity):
    for vehicle, study in studies.items():
        for name, config in study.configurations.items():
            for axle in ('front', 'rear'):
                yield f'{vehicle}/{name}/{axle}', suspension_input(config, axle, fidelity)


def test_rigid_rotation_of_a_component_stores_no_energy(studies):
    """
    Check objectivity: a rigid rotation of a component stores no energy.

    Rotate every node of the flexible lower arm rigidly by 30 deg, deformed or not;
    the component's strain energy and internal force are unchanged.
    """
    inp = suspension_input(studies['sedan'].configurations['baseline'], 'front', 'flexible')
    system = assemble(inp)
    law_idx = [i for law, i in system.laws if isinstance(law, MatrixLaw)]
    # round-off floor: the stiffest entry times a position error of ~50 ulp of 1 m
    floor = system.coupled_max * 1e-14
    nodes = [k for k, n in enumerate(system.part_names) if n.startswith('lca.left@')]
    assert len(nodes) == 3
    # the lca's measures are the ones that change when only its nodes move
    state = system.design_state()
    rng = np.random.default_rng(7)
    deformed = state.copy()
    deformed.p[nodes] += rng.normal(scale=2e-4, size=(3, 3))
    deformed.R[nodes] = (
        rotation_vectors_to_matrices(rng.normal(scale=2e-3, size=(3, 3))) @ deformed.R[nodes]
    )
    q = rotation_vectors_to_matrices(np.array([[np.radians(30.0) / np.sqrt(3.0)] * 3]))[0]
    centre = state.p[nodes[0]]
    for base in (state, deformed):
        turned = base.copy()
        turned.p[nodes] = centre + (base.p[nodes] - centre) @ q.T
        turned.R[nodes] = q @ base.R[nodes]
        e0 = system.evaluate(base, LoadCase())
        e1 = system.evaluate(turned, LoadCase())
        for i in law_idx:
            assert e1.energy[i].sum() == pytest.approx(e0.energy[i].sum(), rel=1e-9,
                                                       abs=floor * 1e-14)
            # internal forces in the reference node's frame: unchanged by the rotation
            np.testing.assert_allclose(e1.d1[i], e0.d1[i], rtol=1e-7, atol=floor)
    undeformed = system.evaluate(state, LoadCase())
    for i in law_idx:
        assert np.abs(undeformed.energy[i]).max() == 0.0


#: E and G scale of the rigid limit. 1e6 pushes the KKT matrix's pivot range (bushings
#: at 1e5 N/m beside components at 1e14 N/m) past the solver's singularity guard
#: (SINGULAR_PIVOT_RATIO, which protects against locked mechanisms); 1e5 already
#: shrinks every component deflection 100 000-fold.
RIGID_LIMIT_SCALE = 1e5


def _stiffened(inp, factor=RIGID_LIMIT_SCALE):
    """
    Return ``inp`` with every flexible component except the bar far stiffer and massless.

    The rigid model's part masses are removed as well (so both carry the same weights).
    """
    flex = {}
    for name, spec in inp.flexible.items():
        if name == 'anti_roll_bar':
            continue
        m = spec.material
        flex[name] = replace(spec, material=sec.Material(m.youngs_modulus * factor,
                                                         m.shear_modulus * factor, 0.0))
    return replace(inp, flexible=flex, masses={'wheel': inp.masses['wheel']})


def test_rigid_limit_equals_the_rigid_model(studies):
    """
    Check that with E and G x 1e5 the flexible K&C equals the rigid K&C.

    They agree within 1e-4 deg and 1e-3 mm on every event, every configuration of
    both sample vehicles.
    """
    checked = 0
    for label, inp in _inputs(studies, 'flexible'):
        stiff = _stiffened(inp)
        rigid = replace(inp, flexible={}, masses={'wheel': inp.masses['wheel']})
        m_rigid, m_flex = KCModel(rigid, label), KCModel(stiff, label)
        for event in EVENTS:
            a, b = m_rigid.run(event, steps=STEPS), m_flex.run(event, steps=STEPS)
            for ch in ('toe', 'camber'):
                assert np.degrees(np.abs(a.channels[ch] - b.channels[ch]).max()) < 1e-4, (
                    label, event, ch)
            for ch in ('wheel_centre', 'contact_point'):
                assert np.abs(a.channels[ch] - b.channels[ch]).max() < 1e-6, (label, event, ch)
            checked += 1
    assert checked == 4 * 2 * (3 + 2)  # events x axles x configurations (sedan 3, hmmwv 2)


def _metrics(inp, label):
    model = KCModel(inp, label)
    results = {e: model.run(e, steps=11) for e in EVENTS}
    return derived_metrics(results, inp.tire_vertical_stiffness)


def test_flexibility_can_only_soften(studies):
    """
    Check that the flexible components can only lower the work-conjugate stiffnesses.

    Compliance added in series can only increase the flexibility of a loaded point in
    the direction of its load (Rayleigh): the work-conjugate stiffnesses -- lateral at the
    contact point, traction at the wheel centre, roll -- cannot rise. (Braking acts on the
    locked wheel at the contact patch while its metric follows the wheel centre, which a
    softer knuckle may let move less: not a conjugate pair, so not part of the property.)
    """
    for label, inp in _inputs(studies, 'flexible'):
        rigid = replace(inp, flexible={})
        mr, mf = _metrics(rigid, label), _metrics(inp, label)
        for key in ('lateral_stiffness', 'longitudinal_stiffness_traction', 'roll_stiffness'):
            assert mf[key][0] <= mr[key][0] * (1 + 1e-9), (label, key, mf[key][0], mr[key][0])


def test_straight_beam_bar_matches_torsion_spring(studies):
    """
    Check that a straight beam anti-roll bar matches the torsion-spring model.

    A straight bar with stiff arms running along x: its roll stiffness equals the
    torsion-spring model's with k = G J / L (L the distance between the mounts), within 1 %.
    """
    inp = suspension_input(studies['sedan'].configurations['baseline'], 'front', 'rigid')
    hp = dict(inp.hardpoints)
    upper = hp['arb_link_upper']
    hp['arb_pivot'] = np.array([hp['arb_pivot'][0], upper[1], upper[2]])  # arm along x
    bar = sec.solid_round(0.022, 0.3)
    steel = sec.Material(206e9, 79.3e9, 0.0)  # massless: the stiff arms would weigh 90 kg
    length = 2.0 * hp['arb_pivot'][1]
    base = replace(inp, hardpoints=hp, masses={'wheel': inp.masses['wheel']})
    rigid = replace(base, stabilizer=StabilizerSpec(steel.shear_modulus * bar.j / length))
    stiff_arm = sec.solid_round(0.2, 0.3)
    flex = replace(base, flexible={'anti_roll_bar': FlexSpec(steel, bar, arm_section=stiff_arm,
                                                             elements_per_member=4)})
    bare = replace(base, stabilizer=None)

    def roll(i):
        r = KCModel(i).run('opposite_wheel_travel', steps=11, amplitude=0.02)
        return derived_metrics({'opposite_wheel_travel': r},
                               i.tire_vertical_stiffness)['roll_stiffness'][0]

    k0 = roll(bare)
    assert roll(flex) - k0 == pytest.approx(roll(rigid) - k0, rel=0.01)


def _plain(comp, length=1e-3):
    """Return the condensed component written in the plain format in mm and N."""
    from vd_solvers.flex.imported import dof_scales

    k = comp.stiffness / dof_scales(len(comp.nodes), length, 1.0, 1.0)
    return {'units': {'length': 'mm'}, 'mass': comp.mass, 'cog': list(comp.cog / length),
            'nodes': {n: list(p / length) for n, p in zip(comp.nodes, comp.positions)},
            'stiffness': k.tolist()}


def _dmig(comp, grids):
    lines = [f"DMIG*   {'KAAX':<16}{0:>16}{6:>16}{2:>16}", '*       ' + f'{0:>16}']
    for j in range(comp.stiffness.shape[0]):
        lines.append(f"DMIG*   {'KAAX':<16}{grids[j // 6]:>16}{j % 6 + 1:>16}")
        for i in range(j + 1):
            lines.append(f'*       {grids[i // 6]:>16}{i % 6 + 1:>16}'
                         f'{comp.stiffness[i, j]:>16.9E}'.replace('E', 'D'))
    return '\n'.join(lines) + '\n'


def test_imported_stiffness_equals_the_generated_frame(studies):
    """
    Check that imported stiffness gives the same results as the generated beam frame.

    The lower arm's condensed stiffness written as a plain file and as a Nastran DMIG
    punch, read back and used in the K&C model: the same results as the beam frame.
    """
    inp = suspension_input(studies['sedan'].configurations['baseline'], 'front', 'flexible')
    model = KCModel(replace(inp, flexible={'lca': inp.flexible['lca']}))
    (comp,) = [c for c in model.system.outputs.components if c.name == 'lca']
    factors = {'length': 1.0, 'force': 1.0, 'angle': 1.0, 'mass': 1.0}
    plain = from_plain('lca', _plain(comp), what='test', factors={**factors, 'length': 1e-3})
    np.testing.assert_allclose(plain.stiffness, comp.stiffness, rtol=1e-12)
    grids = {101 + i: n for i, n in enumerate(comp.nodes)}
    dmig = from_dmig('lca', _dmig(comp, list(grids)), matrix='KAAX', grids=grids, what='test',
                     factors=factors)
    np.testing.assert_allclose(dmig.stiffness, comp.stiffness, rtol=1e-8,
                               atol=1e-8 * np.abs(comp.stiffness).max())
    ref = model.run('lateral_force', steps=STEPS)
    for imported in (plain, replace(dmig, mass=comp.mass, cog=comp.cog)):
        spec = FlexSpec(imported=imported)
        got = KCModel(replace(inp, flexible={'lca': spec})).run('lateral_force', steps=STEPS)
        np.testing.assert_allclose(got.channels['toe'], ref.channels['toe'], atol=1e-9)


def test_mirrored_stiffness_is_the_mirror_image():
    k = np.diag(np.arange(1.0, 13.0))
    k[0, 1] = k[1, 0] = 0.5  # x-y coupling flips sign in the mirror image
    m = mirror_stiffness(k)
    assert m[0, 1] == -0.5 and m[0, 0] == 1.0


def test_malformed_dmig_is_refused():
    with pytest.raises(SolverError) as err:
        from_dmig('lca', 'DMIG    KGG     0       6       2\n', matrix='KAAX', grids={1: 'a'},
                  what='f.pch', factors={'length': 1.0, 'force': 1.0, 'angle': 1.0})
    assert str(err.value) == "f.pch: no DMIG matrix 'KAAX' (found: KGG)"
    text = ('DMIG    KAAX    0       6       2\n'
            'DMIG    KAAX    101     1               101     1       1.0x+3\n')
    with pytest.raises(SolverError) as err:
        from_dmig('lca', text, matrix='KAAX', grids={101: 'a'}, what='f.pch',
                  factors={'length': 1.0, 'force': 1.0, 'angle': 1.0})
    assert str(err.value) == "f.pch: '1.0x+3' is not a number"


def test_unknown_component_for_the_template_is_refused(studies):
    inp = suspension_input(studies['sedan'].configurations['baseline'], 'front', 'flexible')
    with pytest.raises(SolverError) as err:
        KCModel(replace(inp, flexible={'crossmember': inp.flexible['lca']}), 'cfg')
    assert str(err.value) == ("cfg: unknown flexible component 'crossmember' (components of "
                              "template 'macpherson': upright, lca, strut, tierod, "
                              'anti_roll_bar, subframe)')


def test_thesis_trends(studies):
    """
    Check the trends of thesis 5.1 between the rigid and the flexible model.

    The force events differ between rigid and flexible; the steering event
    (kinematics) nearly agrees. On the sedan's MacPherson front (a stiff cast knuckle)
    the lateral force shows it in the camber, which the bending strut carries.
    """
    config = studies['sedan'].configurations['baseline']
    inp = suspension_input(config, 'front', 'flexible')
    rigid, flex = KCModel(replace(inp, flexible={})), KCModel(inp)

    def gap(event, channel, **kw):
        """Worst difference of a channel's change, and that relative to its range."""
        a, b = rigid.run(event, steps=STEPS, **kw), flex.run(event, steps=STEPS, **kw)
        da = a.channels[channel] - a.channels[channel][STEPS // 2]
        db = b.channels[channel] - b.channels[channel][STEPS // 2]
        worst = np.abs(da - db).max()
        return np.degrees(worst), worst / np.ptp(da)

    lateral, lateral_rel = gap('lateral_force', 'camber')
    _, steering_rel = gap('steering', 'toe')
    assert lateral > 0.05 and lateral_rel > 0.10  # a designer would see it
    assert steering_rel < 0.01  # the steering response is the kinematics


def test_tangent_is_consistent_with_the_internal_forces(studies):
    """
    Check the assembled tangent of the flexible model against finite differences.

    The tangent is compared with central finite differences of the force residual at
    an equilibrium (opposite pad travel: the bar, springs and every component loaded).
    At equilibrium the symmetric exponential-map chart is exact; away from it the
    tangent lacks the (vanishing) skew term of the residual moment, by design. Pad
    loads only: a force at the contact point has a documented approximate tangent (the
    contact point rolls along the tread; system.System._applied).
    """
    from vd_solvers.kc.solver import solve_static

    inp = suspension_input(studies['sedan'].configurations['baseline'], 'rear', 'flexible')
    system = assemble(inp)
    load = LoadCase(pad=np.array([0.01, -0.006]))
    state, _, _ = solve_static(system, load, 'tangent check')
    rng = np.random.default_rng(3)
    k = system.evaluate(state, load).tangent(state.lam)

    def residual(dq):
        s = state.copy()
        s.p = s.p + dq[:, :3]
        s.R = rotation_vectors_to_matrices(dq[:, 3:]) @ s.R
        return system.evaluate(s, load).force_residual(s.lam)

    h = 1e-7
    direction = rng.normal(size=(system.n_parts, 6))
    fd = (residual(h * direction) - residual(-h * direction)) / (2 * h)
    exact = k @ direction.ravel()
    np.testing.assert_allclose(fd, exact, rtol=1e-6, atol=1e-7 * np.abs(k).max())


def test_flexible_subframe_carries_the_arm_pivots(studies):
    """
    Check that a flexible subframe carries the lower-arm pivots.

    The subframe alone: the lower-arm joints sit on its nodes, so it adds lateral
    compliance at the contact patch; made 1e5 times stiffer it is the body again.
    """
    inp = suspension_input(studies['sedan'].configurations['baseline'], 'front', 'flexible')
    spec = inp.flexible['subframe']
    rigid = replace(inp, flexible={})
    only = replace(inp, flexible={'subframe': spec})
    stiff = replace(inp, flexible={'subframe': replace(spec, material=sec.Material(
        spec.material.youngs_modulus * 1e5, spec.material.shear_modulus * 1e5, 0.0))})
    m_rigid, m_only = _metrics(rigid, 'rigid'), _metrics(only, 'subframe')
    assert m_only['lateral_stiffness'][0] < m_rigid['lateral_stiffness'][0]
    a = KCModel(rigid).run('lateral_force', steps=STEPS)
    b = KCModel(stiff).run('lateral_force', steps=STEPS)
    assert np.degrees(np.abs(a.channels['toe'] - b.channels['toe']).max()) < 1e-4
    assert np.abs(a.channels['contact_point'] - b.channels['contact_point']).max() < 1e-6
    names = KCModel(only).system.part_names
    assert 'subframe.left@lca_front.right' in names


def _roll(inp, amplitude=0.02):
    r = KCModel(inp).run('opposite_wheel_travel', steps=11, amplitude=amplitude)
    return derived_metrics({'opposite_wheel_travel': r},
                           inp.tire_vertical_stiffness)['roll_stiffness'][0]


@pytest.mark.parametrize('axle', ['front', 'rear'])
def test_rigid_limit_keeps_the_stabilizers_bar(studies, axle):
    """
    Check that the flexible model at its rigid limit has the rigid model's bar.

    Components 1e5 times stiffer and the bar's arms 1e3 times, its torsion part as it is:
    the roll stiffness is the rigid model's (torsion spring G J / L between rigid arms)
    within 0.1 %, the bar included. A flexible bar of another diameter would show: a
    22 mm beam bar on the 24 mm stabilizer (the sample data before the flexible bar took
    the stabilizer's section) gives a bar roll stiffness (22/24)^4 of the rigid one.
    """
    from vd_solvers.kc.from_config import rigid_limit

    config = studies['sedan'].configurations['baseline']
    rigid = suspension_input(config, 'front' if axle == 'front' else 'rear', 'rigid')
    limit = rigid_limit(suspension_input(config, axle, 'flexible'))
    k_rigid, k_limit = _roll(rigid), _roll(limit)
    assert k_limit == pytest.approx(k_rigid, rel=1e-3)
    if axle == 'rear':
        return
    bare = _roll(replace(rigid, stabilizer=None))
    bar = limit.flexible['anti_roll_bar']
    thin = replace(limit, flexible={**limit.flexible, 'anti_roll_bar': replace(
        bar, section=sec.Section(*(getattr(sec.solid_round(0.022, 0.3), k) for k in
                                   ('area', 'iy', 'iz', 'j'))))})
    assert _roll(thin) - bare == pytest.approx((22 / 24) ** 4 * (k_rigid - bare), rel=0.01)


def _lateral(inp):
    r = KCModel(inp).run('lateral_force', steps=11)
    metrics = derived_metrics({'lateral_force': r}, inp.tire_vertical_stiffness)
    return metrics['lateral_stiffness'][0]


# the sample knuckles: cast or steel box sections, outer width x depth and wall (m), E (Pa)
KNUCKLES = [('sedan', 'front', (0.050, 0.070, 0.008), 169e9),
            ('sedan', 'rear', (0.040, 0.055, 0.007), 169e9),
            ('hmmwv', 'front', (0.090, 0.110, 0.010), 210e9),
            ('hmmwv', 'rear', (0.090, 0.110, 0.010), 210e9)]


@pytest.mark.parametrize('vehicle, axle, box, youngs_modulus', KNUCKLES)
def test_sample_knuckle_section_is_the_box_its_comment_describes(studies, vehicle, axle, box,
                                                                 youngs_modulus):
    """
    Each sample knuckle section is the box its data file's comment describes.

    Thin-walled closed section written out: A = B H - b h, I = (B H^3 - b h^3) / 12,
    Bredt's J = 4 A_m^2 t / p_m (A_m, p_m: area and length of the wall's mid-line).
    """
    inp = suspension_input(studies[vehicle].configurations['baseline'], axle, 'flexible')
    s = inp.flexible['upright'].section
    width, depth, t = box
    b, h = width - 2 * t, depth - 2 * t
    a_m, p_m = (width - t) * (depth - t), 2 * (width - t + depth - t)
    expected = (width * depth - b * h, (width * depth**3 - b * h**3) / 12,
                (depth * width**3 - h * b**3) / 12, 4 * a_m**2 * t / p_m)
    np.testing.assert_allclose((s.area, s.iy, s.iz, s.j), expected, rtol=1e-5)
    assert inp.flexible['upright'].material.youngs_modulus == pytest.approx(youngs_modulus)


@pytest.mark.parametrize('vehicle, name, axle', [('sedan', 'baseline', 'front'),
                                                   ('sedan', 'baseline', 'rear'),
                                                   ('hmmwv', 'bushings', 'front')])
def test_sample_knuckle_is_much_stiffer_than_the_bushings_path(studies, vehicle, name, axle):
    """
    Check that each sample knuckle alone is far stiffer laterally than the rest.

    Lateral stiffness at the contact point (K&C lateral_force event): rigid model (the
    bushings, rack and joints path) k_r, knuckle alone flexible k_u. The knuckle acts in
    series, 1/k_u = 1/k_r + 1/k_knuckle: a knuckle must be several times stiffer than the
    bushings path (the design rule the box sections were sized to; the 36 mm round spokes
    of earlier sedan data gave k_knuckle 1.7 kN/mm against a 4.4 kN/mm bushings path, the
    60 mm round spokes of the HMMWV 15.8 kN/mm against 24.4). The HMMWV's baseline has
    no bushings (an infinitely stiff path); its `bushings` configuration has them in front.
    """
    inp = suspension_input(studies[vehicle].configurations[name], axle, 'flexible')
    k_r = _lateral(replace(inp, flexible={}))
    k_u = _lateral(replace(inp, flexible={'upright': inp.flexible['upright']}))
    k_knuckle = 1.0 / (1.0 / k_u - 1.0 / k_r)
    assert k_knuckle > 4.0 * k_r, (k_knuckle, k_r)
