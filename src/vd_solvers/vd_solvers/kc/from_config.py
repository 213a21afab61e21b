# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Build a K&C suspension input from a resolved configuration, and run its events.

Every value comes from the configuration's groups of that axle
(``<axle>_hardpoints``, ``_spring``, ``_damper``, ``_bump_stop``,
``_rebound_stop``, ``_bushings``, ``_stabilizer``, ``_alignment``, ``_tire``,
``steering`` on the front axle) plus the static corner load from the mass data.
The tire's loaded radius is the design wheel-centre height (hard points at
design ride height); its vertical stiffness is the Magic Formula's at the configuration's
inflation pressure (VERTICAL_STIFFNESS (1 + PFZ1 dpi), the tangent at FNOMIN).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
import copy
from dataclasses import replace
import math

import numpy as np

from vd_data_server.model import Configuration, GroupData
from vd_data_server.schema import ARB_POINTS, BAR_COMPONENT, BUSHING_DIRECTIONS
from vd_data_server.tire_group import tire_properties
from vd_data_server.units import si_factor
from vd_data_server.yamlio import loads
from vd_solvers.errors import SolverError
from vd_solvers.event_params import parse_params
from vd_solvers.flex import section as sec
from vd_solvers.flex.component import ShapePoint
from vd_solvers.flex.imported import from_dmig, from_plain
from vd_solvers.results import FIDELITIES, Channel, EventOutcome, Metric
from vd_solvers.tire.magic_formula import vertical_stiffness
from vd_solvers.vehicle_data import mass_properties, static_wheel_loads

from .channels import UNITS, bushing_unit
from .events import EVENT_PARAMS, EVENTS, KCModel, run_suite
from .metrics import derived_metrics
from .model import (
    Axle,
    Bushing,
    Curve,
    DamperSpec,
    FlexSpec,
    SpringSpec,
    StabilizerSpec,
    SteeringSpec,
    StopSpec,
    SuspensionInput,
    without_bar,
)


def _curve(group: GroupData, key: str, scale: float = 1.0) -> Curve:
    xs, ys = group.curve(key)
    return Curve(np.asarray(xs), np.asarray(ys) * scale)


def _optional(config: Configuration, name: str) -> GroupData | None:
    return config.groups.get(name)


def suspension_input(config: Configuration, axle: str, fidelity: str = 'rigid') -> SuspensionInput:
    """
    Build the K&C input of ``axle`` ('front' or 'rear') of ``config``.

    ``fidelity`` 'flexible' makes the components of the ``<axle>_flex`` group
    flexible (the configuration's ``flexible_components`` if it names any on
    this axle, else all of them); 'rigid' uses their ``rigid_mass`` only.
    """
    if fidelity not in FIDELITIES:
        raise SolverError(f"configuration '{config.name}', axle '{axle}': unknown fidelity "
                          f"'{fidelity}' (fidelities: {', '.join(FIDELITIES)})")
    if axle not in ('front', 'rear'):
        raise SolverError(f"configuration '{config.name}': unknown axle '{axle}' (axles: front, "
                          'rear)')
    corner: Axle = 'front' if axle == 'front' else 'rear'
    hp = config.group(f'{axle}_hardpoints')
    points = {k.split('.', 1)[1]: np.asarray(v.si, dtype=float)
              for k, v in hp.values.items() if k.startswith('points.')}
    spring_g = config.group(f'{axle}_spring')
    spring = SpringSpec(
        rate=spring_g.get_scalar('rate'),
        curve=_curve(spring_g, 'curve') if spring_g.has('curve') else None,
        free_length=spring_g.get_scalar('free_length'),
        preload=spring_g.get_scalar('preload'))
    damper_g = config.group(f'{axle}_damper')
    damper = DamperSpec(_curve(damper_g, 'curve', damper_g.get_scalar('scale', 1.0) or 1.0))
    stops = {}
    for kind in ('bump_stop', 'rebound_stop'):
        g = config.group(f'{axle}_{kind}')
        stops[kind] = StopSpec(g.scalar('clearance'), _curve(g, 'curve'))
    bushings = {}
    bush_g = _optional(config, f'{axle}_bushings')
    if bush_g is not None:
        names = sorted({k.split('.')[1] for k in bush_g.values if k.startswith('connections.')})
        for name in names:
            base = f'connections.{name}'
            stiffness = tuple(bush_g.scalar(f'{base}.stiffness.{d}') for d in BUSHING_DIRECTIONS)
            damping = tuple(bush_g.get_scalar(f'{base}.damping.{d}', 0.0) or 0.0
                            for d in BUSHING_DIRECTIONS)
            axis = bush_g.point(f'{base}.axis') if bush_g.has(f'{base}.axis') else None
            bushings[name] = Bushing(stiffness, damping,
                                     None if axis is None else np.asarray(axis, dtype=float))
    stabilizer = None
    stab_g = _optional(config, f'{axle}_stabilizer')
    if stab_g is not None:
        missing = [p for p in ARB_POINTS if p not in points]
        if missing:
            raise SolverError(f"{axle}_stabilizer is given but {hp.file} lacks the anti-roll-bar "
                              f"hard points {', '.join(missing)}")
        stabilizer = StabilizerSpec(bar_stiffness(stab_g))
    steering = None
    if axle == 'front' and 'steering' in config.groups:
        s = config.group('steering')
        steering = SteeringSpec(rack_ratio=s.scalar('rack_ratio'),
                                rack_travel_limit=s.scalar('rack_travel_limit'),
                                rack_stiffness=s.get_scalar('rack_stiffness'),
                                column_stiffness=s.get_scalar('column_stiffness'))
    align = config.group(f'{axle}_alignment')
    tire = config.group(f'{axle}_tire')
    front_load, rear_load = static_wheel_loads(config)
    unsprung = config.group('mass').scalar(f'unsprung_mass_{axle}')
    masses: dict[str, float] = {'wheel': unsprung}
    flexible: dict[str, FlexSpec] = {}
    flex_g = _optional(config, f'{axle}_flex')
    specs = flex_specs(flex_g, stab_g) if flex_g is not None else {}
    for name, (_, rigid_mass) in specs.items():
        if rigid_mass and name not in ('anti_roll_bar', 'subframe'):
            masses[name] = rigid_mass
    # The corner's unsprung mass (mass group) holds the parts: the wheel-centre lump is
    # what the parts' own masses leave of it, so the axle's total mass stays the data's.
    parts = sum(m for k, m in masses.items() if k != 'wheel')
    if parts >= unsprung:
        raise SolverError(f"configuration '{config.name}': the {axle} parts' rigid_mass "
                          f"({parts:.1f} kg, {flex_g.file if flex_g else ''}) must be below the "
                          f"unsprung mass per corner ({unsprung:.1f} kg, mass group)")
    masses['wheel'] = unsprung - parts
    if fidelity == 'flexible':
        if not specs:
            raise SolverError(f"configuration '{config.name}': the {axle} axle has no flexible "
                              f"components (no {axle}_flex group); run it rigid or add the group")
        chosen = [c for c in config.flexible_components if c in specs] or sorted(specs)
        flexible = {c: specs[c][0] for c in chosen}
    return SuspensionInput(
        template=hp.text('template'), axle=corner, hardpoints=points, spring=spring,
        tire_radius=points['wheel_centre'][2],
        tire_vertical_stiffness=vertical_stiffness(tire_properties(tire)),
        corner_load=front_load if axle == 'front' else rear_load,
        damper=damper, bump_stop=stops['bump_stop'], rebound_stop=stops['rebound_stop'],
        bushings=bushings, stabilizer=stabilizer, steering=steering,
        camber=align.scalar('camber'), toe=align.scalar('toe'), masses=masses,
        flexible=flexible)


#: E and G scale of the flexible model's rigid limit. 1e6 pushes the KKT matrix's pivot
#: range (bushings at 1e5 N/m beside components at 1e14 N/m) past the solver's
#: singularity guard (SINGULAR_PIVOT_RATIO, which protects against locked mechanisms);
#: 1e5 already shrinks every component deflection 100 000-fold.
RIGID_LIMIT_SCALE = 1e5
#: the same for the anti-roll bar's arms and bending, whose torsion part keeps its G J:
#: at 1e5 its axial stiffness would be 1e10 times its torsion rate, which the rigid-mode
#: test of a condensed component (RIGID_MODE_RATIO) would take for a mechanism
RIGID_LIMIT_BAR_SCALE = 1e3


def _euler_bernoulli(section: sec.Section, torsion: float = 1.0) -> sec.Section:
    """``section`` without shear strain, its torsion constant ``torsion`` times larger."""
    return sec.Section(section.area, section.iy, section.iz, section.j * torsion,
                       shape=section.shape)


def rigid_limit(inp: SuspensionInput, scale: float = RIGID_LIMIT_SCALE) -> SuspensionInput:
    """
    Return the flexible ``inp`` at its rigid limit: what the rigid model describes.

    Every beam component's E and G are ``scale`` times larger and its shear strain is
    dropped (Euler-Bernoulli), so it deforms ``scale`` times less. The anti-roll bar is
    elastic in the rigid model too -- a torsion spring between rigid arms -- so its
    torsion part keeps its G J while its arms and its bending become
    ``RIGID_LIMIT_BAR_SCALE`` times stiffer: the limit is the rigid model's bar, G J / L
    between the pivots. An imported component's stiffness is scaled whole. Masses are
    left as they are (FE masses).
    """
    out = {}
    for name, spec in inp.flexible.items():
        if spec.imported is not None:
            out[name] = replace(spec, imported=replace(spec.imported,
                                                       stiffness=spec.imported.stiffness * scale))
            continue
        assert spec.material is not None and spec.section is not None
        m = spec.material
        if name == BAR_COMPONENT:
            arm = spec.arm_section or spec.section
            bar = min(scale, RIGID_LIMIT_BAR_SCALE)
            out[name] = replace(
                spec, material=sec.Material(m.youngs_modulus * bar, m.shear_modulus,
                                            m.density),
                section=_euler_bernoulli(spec.section),
                arm_section=_euler_bernoulli(arm, bar))
        else:
            out[name] = replace(spec, material=sec.Material(m.youngs_modulus * scale,
                                                            m.shear_modulus * scale, m.density),
                                section=_euler_bernoulli(spec.section),
                                arm_section=None)
    return replace(inp, flexible=out)


def flex_specs(group: GroupData, stabilizer: GroupData | None = None
               ) -> dict[str, tuple[FlexSpec, float]]:
    """
    Every component of a flex group: its FlexSpec and its rigid-model mass (kg).

    The anti-roll bar is the part the ``stabilizer`` group describes: a bar given by
    ``bar_radius`` is a solid round section of that diameter (unless the flex group
    names a section, which the data check holds to the same diameter) of the
    stabilizer's shear modulus; Young's modulus and density come from the flex material.
    """
    materials = {}
    for name in sorted({k.split('.')[1] for k in group.values if k.startswith('materials.')}):
        base = f'materials.{name}'
        e, rho = group.scalar(f'{base}.youngs_modulus'), group.scalar(f'{base}.density')
        g_mod = group.get_scalar(f'{base}.shear_modulus')
        try:
            materials[name] = (sec.Material(e, g_mod, rho) if g_mod is not None else
                               sec.Material.from_poisson(e, group.scalar(f'{base}.poissons_ratio'),
                                                         rho))
        except SolverError as err:
            raise SolverError(f'{group.file}: {base}: {err}') from None

    def section(name: str, nu: float):
        base = f'sections.{name}'
        shape = group.text(f'{base}.shape')
        get = lambda k: group.scalar(f'{base}.{k}')  # noqa: E731
        try:
            if shape == 'solid_round':
                return sec.solid_round(get('diameter'), nu)
            if shape == 'tube':
                return sec.tube(get('outer_diameter'), get('wall'), nu)
            if shape == 'rectangle':
                return sec.rectangle(get('width'), get('height'), nu)
            if shape == 'i_beam':
                return sec.i_beam(get('height'), get('flange_width'), get('flange_thickness'),
                                  get('web_thickness'))
            return sec.Section(get('area'), get('iy'), get('iz'), get('torsion_constant'),
                               group.get_scalar(f'{base}.shear_area_y'),
                               group.get_scalar(f'{base}.shear_area_z'))
        except SolverError as err:
            raise SolverError(f'{group.file}: {base}: {err}') from None

    out: dict[str, tuple[FlexSpec, float]] = {}
    for comp in sorted({k.split('.')[1] for k in group.values if k.startswith('components.')}):
        base = f'components.{comp}'
        rigid_mass = group.get_scalar(f'{base}.rigid_mass', 0.0) or 0.0
        source = f'{group.file} {base}'
        if group.has(f'{base}.imported.content'):
            spec = FlexSpec(imported=_imported(group, comp, base), source=source)
        else:
            material = materials[group.text(f'{base}.material')]
            shared = (comp == BAR_COMPONENT and stabilizer is not None
                      and stabilizer.has('bar_radius'))
            if shared:
                assert stabilizer is not None
                material = sec.Material(material.youngs_modulus,
                                        stabilizer.scalar('shear_modulus'), material.density)
                source += f', bar diameter and shear modulus of {stabilizer.file}'
            nu = material.poissons_ratio
            shapes = tuple(
                ShapePoint(group.text(f'{base}.shape_points.{sp}.from'),
                           group.text(f'{base}.shape_points.{sp}.to'),
                           group.scalar(f'{base}.shape_points.{sp}.fraction'),
                           group.point(f'{base}.shape_points.{sp}.offset')
                           if group.has(f'{base}.shape_points.{sp}.offset') else (0.0, 0.0, 0.0))
                for sp in sorted({k.split('.')[3] for k in group.values
                                  if k.startswith(f'{base}.shape_points.')}))
            arm = (section(group.text(f'{base}.arm_section'), nu)
                   if group.has(f'{base}.arm_section') else None)
            if shared and not group.has(f'{base}.section'):
                assert stabilizer is not None
                main = sec.solid_round(2.0 * stabilizer.scalar('bar_radius'), nu)
            else:
                main = section(group.text(f'{base}.section'), nu)
            spec = FlexSpec(material, main, shapes,
                            int(group.scalar(f'{base}.elements_per_member')), arm,
                            source=source)
        out[comp] = (spec, rigid_mass)
    return out


def _imported(group: GroupData, comp: str, base: str):
    """Read the reduced stiffness of an imported component (file content in the group)."""
    rel = group.text(f'{base}.imported.file')
    text = group.text(f'{base}.imported.content')
    what = f'{rel} ({group.file} {base}.imported)'
    if group.text(f'{base}.imported.format') == 'plain':
        raw = loads(text, file=what)
        if raw is None:
            raise SolverError(f'{what}: the file is empty (expected units, nodes and '
                              'stiffness)')
        units = (raw or {}).get('units', {}) if isinstance(raw, dict) else {}
    else:
        raw = None
        units = {q: group.text(f'{base}.imported.{q}_unit') for q in ('length', 'force')
                 if group.has(f'{base}.imported.{q}_unit')}
    try:
        factors = {q: si_factor(str(units.get(q, d)), q) for q, d in
                   (('length', 'm'), ('force', 'N'), ('angle', 'rad'), ('mass', 'kg'))}
    except (ValueError, AttributeError) as err:
        raise SolverError(f'{what}: units: {err}') from None
    if raw is not None:
        return from_plain(comp, raw, what=what, factors=factors)
    grids = {}
    for k, v in group.values.items():
        if k.startswith(f'{base}.imported.grids.'):
            try:
                grids[int(k.rsplit('.', 1)[1])] = str(v.si)
            except ValueError:
                raise SolverError(f"{what}: GRID id '{k.rsplit('.', 1)[1]}' is not a whole "
                                  "number") from None
    return from_dmig(comp, text, matrix=group.text(f'{base}.imported.matrix'), grids=grids,
                     what=what, factors=factors)


def bar_stiffness(group: GroupData) -> float:
    """
    Return the torsional stiffness of the anti-roll bar, N*m/rad.

    Given, or G*J/L of a solid round bar (J = pi r^4 / 2).
    """
    given = group.get_scalar('torsional_stiffness')
    if given is not None:
        return given
    r = group.scalar('bar_radius')
    return group.scalar('shear_modulus') * math.pi * r ** 4 / 2.0 / group.scalar('torsion_length')


def _event_kwargs(values: Mapping[str, float]) -> dict[str, float]:
    return {k: (int(v) if k == 'steps' else v) for k, v in values.items()}


def build_kc_model(config: Configuration, axle: str, fidelity: str, label: str,
                   at_rigid_limit: bool = False) -> KCModel:
    """
    Build the K&C model a run of ``config`` solves (``vd data check`` builds the same).

    Everything a K&C run refuses before its first step is refused here: hard points,
    flexible components, imported stiffness files. Messages start with ``label``.
    ``at_rigid_limit``: the flexible model at its rigid limit (:func:`rigid_limit`).
    """
    try:
        inp = suspension_input(config, axle, fidelity)
        if at_rigid_limit:
            inp = rigid_limit(inp)
    except SolverError as err:
        raise SolverError(f'{label}: {err}') from None
    return KCModel(inp, label)


def run_kc_event(config: Configuration, event: str, axle: str,
                 params: Sequence[str] = (),
                 progress: Callable[[float, str], None] | None = None,
                 fidelity: str = 'rigid', at_rigid_limit: bool = False,
                 build: Callable[[Configuration, str, str, str, bool], KCModel] = build_kc_model
                 ) -> EventOutcome:
    """
    One K&C event on one axle, with the derived metrics that event supports.

    ``progress(fraction, stage)`` is called per solved step (it may raise to cancel);
    ``fidelity`` 'rigid' or 'flexible' (see :func:`suspension_input`);
    ``at_rigid_limit``: the flexible model at its rigid limit (:func:`rigid_limit`);
    ``build(config, axle, fidelity, label, at_rigid_limit)`` returns the model to run:
    :func:`build_kc_model` assembles a new one, :func:`.cache.kc_model` the one this
    process already assembled from the same data (a run leaves a model as it was).
    """
    label = f"configuration '{config.name}', event '{event}', axle '{axle}'"
    if event not in EVENT_PARAMS:
        raise SolverError(f"{label}: the K&C solver has no event '{event}' (events: "
                          f"{', '.join(EVENT_PARAMS)})")
    if axle not in ('front', 'rear'):
        raise SolverError(f'{label}: K&C events need --axle front or rear')
    values = parse_params(event, EVENT_PARAMS[event], params)
    # a model from a cache carries the label of the run that built it: this run's
    # messages name its own event
    model = copy.copy(build(config, axle, fidelity, label, at_rigid_limit))
    model.label = label
    inp = model.inp
    if event == 'steering' and inp.steering is None:
        raise SolverError(f'{label}: the {axle} axle has no steering')
    with_bar = event == 'opposite_wheel_travel' and inp.stabilizer is not None
    runs = 2 if with_bar else 1

    def on_step(run: int, stage: str) -> Callable[[int, int], None] | None:
        if progress is None:
            return None
        return lambda done, total: progress((run + done / total) / runs, stage)

    result = model.run(event, on_step(0, 'solving'), **_event_kwargs(values))
    results = {event: result}
    if with_bar:
        bare = KCModel(without_bar(model.inp), label, solved=True)
        results['opposite_wheel_travel_no_bar'] = bare.run(
            event, on_step(1, 'solving without the anti-roll bar'),
            **_event_kwargs(values))
    outcome = _outcome(config, event, axle, inp, model, results, fidelity)
    if not at_rigid_limit:
        return outcome
    return replace(outcome, notes=tuple(outcome.notes) + (
        f"at the rigid limit: components {RIGID_LIMIT_SCALE:g} times stiffer, the bar's "
        'torsion part as it is',))


def _outcome(config, event, axle, inp, model, results, fidelity='rigid') -> EventOutcome:
    geo = config.group('geometry')
    mass_cog = mass_properties(config).cog_height
    metrics = {k: Metric(float(v), u) for k, (v, u) in derived_metrics(
        results, inp.tire_vertical_stiffness, cg_height=mass_cog,
        wheelbase=geo.scalar('wheelbase')).items()}
    raw = results[event].channels
    channels = flatten_channels(raw)
    if event == 'lateral_force':
        channels['applied_force'] = Channel('N', raw['contact_force'][:, 0, 1])
    elif event == 'aligning_torque':
        channels['applied_moment'] = Channel('N*m', raw['contact_moment'][:, 0, 2])
    elif event == 'longitudinal_force':
        channels['applied_force'] = Channel('N', raw['contact_force'][:, 0, 0]
                                            + raw['centre_force'][:, 0, 0])
    residual_c = float(np.max(raw['constraint_residual']))
    residual_f = float(np.max(raw['force_residual']))
    metrics['max_constraint_residual'] = Metric(residual_c, 'm')
    metrics['max_force_residual'] = Metric(residual_f, 'N')
    kind = 'rigid' if fidelity == 'rigid' else (
        'flexible (' + ', '.join(sorted(inp.flexible)) + ')')
    notes = [f'{kind} K&C, {inp.template} {axle}; joints to 1e-9 m, forces to 1e-6 N '
             f'(worst step: {residual_c:.1e} m, {residual_f:.1e} N)',
             f'spring preload at design: {model.inp.spring.preload or 0.0:.0f} N; corner load '
             f'{inp.corner_load:.0f} N from the mass data']
    for comp in model.system.outputs.components:
        metrics[f'component_mass.{comp.name}'] = Metric(comp.mass, 'kg', comp.source)
        for c, axis in enumerate('xyz'):
            metrics[f'component_cog_{axis}.{comp.name}'] = Metric(float(comp.cog[c]), 'm',
                                                                 comp.source)
        rigid = inp.masses.get(comp.name)
        notes.append(f"{comp.name}: {comp.source}, FE mass {comp.mass:.2f} kg at "
                     f"({', '.join(f'{v * 1e3:.0f}' for v in comp.cog)}) mm"
                     + (f'; rigid model {rigid:.2f} kg at the hard-point centroid'
                        if rigid else ''))
    for name, mass in inp.masses.items():
        if name != 'wheel':
            metrics[f'rigid_mass.{name}'] = Metric(mass, 'kg', 'rigid_mass of the flex data')
    return EventOutcome(event=event, configuration=config.name, model='kc', fidelity=fidelity,
                        axle=axle, data_hash=config.data_hash, metrics=metrics,
                        channels=channels, notes=tuple(notes))


#: per-wheel channel suffixes, vector component names
WHEEL = ('left', 'right')
XYZ = ('x', 'y', 'z')

def flatten_channels(raw: Mapping[str, np.ndarray]) -> dict[str, Channel]:
    """(n,), (n, 2), (n, 2, 3) and bushing (n, 2, 6) arrays -> named 1-D channels."""
    out: dict[str, Channel] = {}
    for name, array in raw.items():
        base = name.split('.', 1)[0]
        unit = UNITS.get(base, '')
        a = np.asarray(array, dtype=float)
        if a.ndim == 1:
            out[name] = Channel(unit, a)
        elif a.ndim == 2 and a.shape[1] == 2:
            for s, side in enumerate(WHEEL):
                out[f'{name}_{side}'] = Channel(unit, a[:, s])
        elif a.ndim == 3 and a.shape[2] == 3:
            for s, side in enumerate(WHEEL):
                for c, comp in enumerate(XYZ):
                    out[f'{name}_{comp}_{side}'] = Channel(unit, a[:, s, c])
        elif a.ndim == 3 and a.shape[2] == 6:
            for s, side in enumerate(WHEEL):
                for c, comp in enumerate(BUSHING_DIRECTIONS):
                    out[f'{name}.{comp}_{side}'] = Channel(bushing_unit(base, c), a[:, s, c])
        elif a.ndim == 2:
            for c in range(a.shape[1]):
                out[f'{name}_{c}'] = Channel(unit, a[:, c])
    return out


__all__ = ['EVENT_PARAMS', 'EVENTS', 'build_kc_model', 'run_kc_event', 'run_suite',
           'suspension_input', 'bar_stiffness', 'flatten_channels', 'rigid_limit',
           'RIGID_LIMIT_SCALE', 'RIGID_LIMIT_BAR_SCALE']
