# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Facts that two input groups of one configuration both describe.

The rigid K&C model reads the anti-roll bar from the ``<axle>_stabilizer`` group and
the part masses from ``rigid_mass`` of the ``<axle>_flex`` group; the flexible model
builds the same bar as a beam frame from the flex group and the hard points. One
physical part has one description: the flexible bar takes its section (a solid round
bar of the stabilizer's ``bar_radius``) and its shear modulus from the stabilizer, and
where the flex data state such a fact as well they must agree. A contradiction is
refused here, at check time, naming both files, keys and values:

* bar diameter: a flex ``section`` of the bar vs 2 x ``bar_radius``;
* bar shear modulus: the flex material's G (given, or E / (2 (1 + nu))) vs
  ``shear_modulus``;
* torsion length: the distance of the two ``arb_pivot`` hard points (where the beam
  bar's torsion part runs) vs ``torsion_length``;
* a bar given only by its ``torsional_stiffness``: the flex section's G J / L;
* the corner's unsprung mass (mass group) must hold the parts' ``rigid_mass``;
* within one group, after the master file's overrides too: a ``driveline`` states its
  layout once (``front_share`` agrees with FWD/RWD, lies strictly between 0 and 1 for
  AWD), has no differential on an axle it does not drive, a positive locking torque on
  a limited-slip differential, gears numbered 1..n and an upshift speed on its engine
  map; a ``brakes`` group's anti-lock controller rebuilds pressure below the slip it
  dumps at (:func:`group_facts`);
* a brake's pads work inside the wheel: the ``brakes`` group's ``effective_radius`` of an
  axle lies below the rim radius (``RIM_RADIUS``) of that axle's tire property file.
"""
from __future__ import annotations

from collections.abc import Mapping
import math

from . import schema
from .errors import DataError, DataErrors
from .model import GroupData
from .tire_group import PREFIX

#: relative difference at which two statements of one quantity contradict each other:
#: three significant figures, the precision a data file writes a value to
RELATIVE = 0.005
#: the torsion length against the pivot distance, m (the geometry check's tolerance)
LENGTH = 0.001


def _differ(a: float, b: float) -> bool:
    return abs(a - b) > RELATIVE * max(abs(a), abs(b))


def material_shear_modulus(flex: GroupData, material: str) -> float:
    """G of a flex material, Pa: given, or E / (2 (1 + nu))."""
    base = f'materials.{material}'
    given = flex.get_scalar(f'{base}.shear_modulus')
    if given is not None:
        return given
    return flex.scalar(f'{base}.youngs_modulus') / (
        2.0 * (1.0 + flex.scalar(f'{base}.poissons_ratio')))


def _bar(flex: GroupData, stab: GroupData, hp: GroupData | None) -> list[DataError]:
    base = f'components.{schema.BAR_COMPONENT}'
    if not flex.has(f'{base}.material'):
        return []  # imported: its own stiffness, refused by the solver for the bar
    errors = []
    section = flex.text(f'{base}.section') if flex.has(f'{base}.section') else None
    radius = stab.get_scalar('bar_radius')
    key = f'{base}.section'
    if radius is None:
        if section is None:
            return [DataError(f"the bar's section is needed: {stab.file} gives only its "
                              'torsional_stiffness, not bar_radius', file=flex.file, key=key)]
    elif section is not None:
        shape = flex.text(f'sections.{section}.shape')
        diameter = (flex.scalar(f'sections.{section}.diameter') if shape == 'solid_round'
                    else None)
        if diameter is None or _differ(diameter, 2.0 * radius):
            found = (f'diameter {diameter * 1e3:g} mm' if diameter is not None
                     else f"shape '{shape}'")
            errors.append(DataError(
                f"section '{section}' ({found}) contradicts {stab.file} bar_radius "
                f'{radius * 1e3:g} mm (a solid bar of diameter {2e3 * radius:g} mm): one bar, '
                f'one description; leave the section out (the flexible bar takes the '
                f"stabilizer's) or make them agree", file=flex.file, key=key))
    material = flex.text(f'{base}.material')
    g_flex = material_shear_modulus(flex, material)
    g_stab = stab.scalar('shear_modulus')
    if radius is not None and _differ(g_flex, g_stab):
        errors.append(DataError(
            f"material '{material}' has shear modulus {g_flex / 1e9:.4g} GPa, {stab.file} "
            f'shear_modulus is {g_stab / 1e9:.4g} GPa: one bar, one material; make them agree',
            file=flex.file, key=f'materials.{material}'))
    if hp is None or not hp.has('points.arb_pivot'):
        return errors
    span = 2.0 * abs(hp.point('points.arb_pivot')[1])
    length = stab.get_scalar('torsion_length')
    if length is not None and abs(span - length) > LENGTH:
        errors.append(DataError(
            f'torsion_length {length * 1e3:g} mm but the arb_pivot hard points of {hp.file} are '
            f'{span * 1e3:g} mm apart (where the flexible bar twists); keep them within '
            f'{LENGTH * 1e3:g} mm', file=stab.file, key='torsion_length'))
    given = stab.get_scalar('torsional_stiffness')
    if given is not None and section is not None and span > 0.0:
        torsion = flex.get_scalar(f'sections.{section}.torsion_constant')
        if torsion is None:
            torsion = _polar(flex, section)
        rate = g_flex * torsion / span
        if _differ(rate, given):
            errors.append(DataError(
                f"section '{section}' and material '{material}' give the bar G J / L = "
                f'{rate:.5g} N*m/rad over the {span * 1e3:g} mm between the arb_pivot hard '
                f'points, {stab.file} torsional_stiffness is {given:.5g} N*m/rad: one bar, one '
                f'stiffness; make them agree', file=flex.file, key=key))
    return errors


def _polar(flex: GroupData, section: str) -> float:
    """Torsion constant of a round section, m^4 (solid_round or tube)."""
    base = f'sections.{section}'
    shape = flex.text(f'{base}.shape')
    if shape == 'solid_round':
        return math.pi * flex.scalar(f'{base}.diameter') ** 4 / 32.0
    if shape == 'tube':
        outer = flex.scalar(f'{base}.outer_diameter')
        inner = outer - 2.0 * flex.scalar(f'{base}.wall')
        return math.pi * (outer ** 4 - inner ** 4) / 32.0
    raise DataError(f"a bar given by its torsional_stiffness needs a round or 'general' "
                    f"section to compare with, found shape '{shape}'", file=flex.file,
                    key=f'{base}.shape')


def _masses(axle: str, flex: GroupData, mass: GroupData) -> list[DataError]:
    parts = sum(flex.get_scalar(f'components.{c}.rigid_mass', 0.0) or 0.0
                for c in {k.split('.')[1] for k in flex.values if k.startswith('components.')}
                if c not in (schema.BAR_COMPONENT, schema.SUBFRAME_COMPONENT))
    unsprung = mass.scalar(f'unsprung_mass_{axle}')
    if parts < unsprung:
        return []
    return [DataError(f"the parts' rigid_mass add up to {parts:g} kg, not below "
                      f'unsprung_mass_{axle} {unsprung:g} kg of {mass.file} (the corner '
                      f'holds them): lower them or raise the unsprung mass', file=flex.file,
                      key='components')]


def _driveline_facts(g: GroupData) -> list[DataError]:
    errors = []

    def refuse(key: str, message: str) -> None:
        errors.append(DataError(message, file=g.file, key=key))

    layout = g.text('layout')
    share = g.get_scalar('front_share')
    implied = {'FWD': 1.0, 'RWD': 0.0}.get(layout)
    if share is None and implied is None:
        refuse('front_share', "required with layout AWD (the front axle's share of the drive "
               'torque)')
    elif share is not None and implied is not None and share != implied:
        refuse('front_share', f'front_share {share:g} contradicts layout {layout} '
               f'(front_share {implied:g}); leave it out or make them agree')
    elif share is not None and implied is None and not 0.0 < share < 1.0:
        refuse('front_share', 'layout AWD drives both axles: front_share must lie strictly '
               f'between 0 and 1, found {share:g}')
    for axle, driven in (('front', implied != 0.0), ('rear', implied != 1.0)):
        base = f'{axle}_differential'
        if not g.has(f'{base}.type'):
            continue
        if not driven:
            refuse(f'{base}.type', f'the {axle} axle is not driven (layout {layout}): it has '
                   'no differential')
        elif g.text(f'{base}.type') == 'limited_slip' and \
                not g.scalar(f'{base}.locking_torque') > 0.0:
            refuse(f'{base}.locking_torque', 'a limited_slip differential needs a positive '
                   'locking_torque')
    gears, ratios = g.curve('gears')
    if list(gears) != [float(n) for n in range(1, len(gears) + 1)]:
        refuse('gears', "gears x must number the gears 1, 2, 3, ... (found "
               f"{', '.join(f'{x:g}' for x in gears)})")
    if any(r <= 0.0 for r in ratios):
        refuse('gears', 'every gear ratio must be positive')
    shift = g.get_scalar('shift_speed')
    top = g.curve('engine_torque')[0][-1]
    if shift is not None and shift > top:
        refuse('shift_speed', f'shift_speed {shift:.4g} rad/s lies beyond the engine_torque '
               f'curve (up to {top:.4g} rad/s)')
    return errors


def group_facts(g: GroupData) -> list[DataError]:
    """Return the contradictions within one ``driveline`` or ``brakes`` group (module doc)."""
    if g.kind == 'driveline':
        return _driveline_facts(g)
    if g.kind == 'brakes':
        dump, build = g.scalar('abs_dump_slip'), g.scalar('abs_build_slip')
        if not build < dump:
            return [DataError(f'abs_build_slip {build:g} must lie below abs_dump_slip '
                              f'{dump:g}', file=g.file, key='abs_build_slip')]
    return []


def _brake_in_rim(axle: str, brakes: GroupData, tire: GroupData) -> list[DataError]:
    rim = tire.get_scalar(f'{PREFIX}DIMENSION.RIM_RADIUS')
    radius = brakes.scalar(f'{axle}.effective_radius')
    if rim is None or radius < rim:
        return []
    return [DataError(f'{axle}.effective_radius {radius * 1e3:g} mm does not fit inside the '
                      f"rim: {tire.file} -> {tire.text('file')} RIM_RADIUS is {rim * 1e3:g} mm "
                      '(the pads work inside the wheel); lower it or fit a larger rim',
                      file=brakes.file, key=f'{axle}.effective_radius')]


def check_shared_facts(groups: Mapping[str, GroupData]) -> None:
    """Refuse a configuration whose groups state one fact twice, differently (module doc)."""
    errors: list[DataError] = []
    for axle in schema.AXLES:
        flex = groups.get(f'{axle}_flex')
        if flex is None:
            continue
        stab = groups.get(f'{axle}_stabilizer')
        if stab is not None and any(k.startswith(f'components.{schema.BAR_COMPONENT}.')
                                    for k in flex.values):
            errors += _bar(flex, stab, groups.get(f'{axle}_hardpoints'))
        if 'mass' in groups:
            errors += _masses(axle, flex, groups['mass'])
    for g in groups.values():
        errors += group_facts(g)
    for axle in schema.AXLES:
        tire = groups.get(f'{axle}_tire')
        if 'brakes' in groups and tire is not None:
            errors += _brake_in_rim(axle, groups['brakes'], tire)
    if errors:
        raise errors[0] if len(errors) == 1 else DataErrors(errors)


__all__ = ['check_shared_facts', 'group_facts', 'material_shear_modulus', 'RELATIVE', 'LENGTH']
