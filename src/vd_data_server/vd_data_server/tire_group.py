# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
A tire group carries its whole .tir file as values.

The data server reads the TeimOrbit file named by the tire group's ``file`` key
and adds every entry as ``tir.<BLOCK>.<KEY>`` (numbers in SI, text as text).
Solvers on any machine of the ROS graph thus get the tire from the
configuration message alone; a changed .tir shows in the feedback like any
other data; and single coefficients can be overridden in master files
(``front_tire.tir.SCALING_COEFFICIENTS.LMUY: 0.9``), among them the inflation pressure
of an MF 6.x file (``front_tire.tir.OPERATING_CONDITIONS.INFLPRES: 2.4 bar``).

The group's own key ``aligning_normalisation`` (``mf-tyre``, the default, or ``book``)
picks the load the Magic Formula normalises the pneumatic trail and the Fx arm by
(vd_solvers.tire.magic_formula); the group always carries it, so a configuration can
override it like any value.
"""
from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType

from .errors import DataErrors
from .model import GroupData, Value
from .tir import DIMENSIONAL_KEYS, TireProperties, check_values

PREFIX = 'tir.'
FORMAT_KEY = 'tir.FORMAT'
NORMALISATION_KEY = 'aligning_normalisation'
#: its value where the data file gives none (vd_solvers.tire.magic_formula, module doc)
DEFAULT_NORMALISATION = 'mf-tyre'
#: [UNITS] quantity exponents -> SI unit text used in vd
_SI_OF = {
    (('LENGTH', 1), ('TIME', -1)): 'm/s',
    (('LENGTH', 1),): 'm',
    (('FORCE', 1),): 'N',
    (('FORCE', 1), ('LENGTH', -1)): 'N/m',
    (('FORCE', 1), ('TIME', 1), ('LENGTH', -1)): 'N*s/m',
    (('ANGLE', 1),): 'rad',
    (('PRESSURE', 1),): 'Pa',
    (('MASS', 1),): 'kg',
    (('MASS', 1), ('LENGTH', 2)): 'kg*m^2',
    (('LENGTH', 1), ('TIME', -2)): 'm/s^2',
    (('FORCE', 1), ('LENGTH', 1), ('ANGLE', -1)): 'N*m/rad',
    (('TIME', -1),): '1/s',
    (('TIME', 1),): 's',
}


def tire_values(props: TireProperties, source: str) -> dict[str, Value]:
    values: dict[str, Value] = {FORMAT_KEY: Value(FORMAT_KEY, 'text', props.file_format,
                                                  source=source)}
    for block, entries in props.sections.items():
        for key, raw in entries.items():
            name = f'{PREFIX}{block}.{key}'
            if isinstance(raw, str):
                values[name] = Value(name, 'text', raw, source=source)
            else:
                unit = _SI_OF[DIMENSIONAL_KEYS[key]] if key in DIMENSIONAL_KEYS else ''
                values[name] = Value(name, 'scalar', float(raw), unit, display_unit=unit,
                                     source=source)
    return values


def with_tire(group: GroupData, props: TireProperties, source: str) -> GroupData:
    values = {**group.values, **tire_values(props, source)}
    if NORMALISATION_KEY not in values:
        values[NORMALISATION_KEY] = Value(NORMALISATION_KEY, 'text', DEFAULT_NORMALISATION,
                                          source=f'{group.file} (default)')
    return GroupData(group.group, group.kind, group.variant, group.file, values,
                     group.description)


def tire_properties(group: GroupData) -> TireProperties:
    """Rebuild the tire property set from a tire group's values (after overrides)."""
    sections: dict[str, dict[str, float | str]] = {}
    for name, value in group.values.items():
        if not name.startswith(PREFIX) or name == FORMAT_KEY:
            continue
        block, key = name[len(PREFIX):].split('.', 1)
        sections.setdefault(block, {})[key] = value.text() if value.type == 'text' \
            else value.number()
    frozen: Mapping[str, Mapping[str, float | str]] = MappingProxyType(
        {b: MappingProxyType(v) for b, v in sections.items()})
    path = f"{group.file} -> {group.text('file')}"
    file_format = group.text(FORMAT_KEY)
    errors = check_values(frozen, path, file_format=file_format)
    if errors:
        raise errors[0] if len(errors) == 1 else DataErrors(errors)
    normalisation = (group.text(NORMALISATION_KEY) if NORMALISATION_KEY in group.values
                     else DEFAULT_NORMALISATION)
    return TireProperties(path=path, file_format=file_format, sections=frozen,
                          aligning_normalisation=normalisation)
