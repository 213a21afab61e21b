# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Units at the file boundary: every value is converted to SI once, at load.

A data file declares the units it is written in with a ``units:`` block, like the
``[UNITS]`` block of Adams/TeimOrbit property files. The block names *base*
quantities (length, force, angle, mass, time); derived quantities (stiffness,
damping, inertia, ...) follow from them unless the block names them too, as
Adams does. A single value may also carry its own unit as a string
(``"36.9 N/mm"``); master-file overrides always do.

Conversion and dimension checks use the ``pint`` library, imported at the first
conversion (:func:`ureg`): importing it and building its registry costs about half a
second of CPU, which a command that converts nothing (a study read from the cache of
``vd_data_server.study_cache``) does not pay.
"""
from __future__ import annotations

from collections.abc import Mapping
from functools import lru_cache
import math
from pathlib import Path
import re
import sys
from typing import TYPE_CHECKING, cast

from .errors import DataError

if TYPE_CHECKING:
    import pint


@lru_cache(maxsize=1)
def ureg() -> pint.UnitRegistry:
    """
    Return the one unit registry of vd, built at the first call.

    Its parsed definitions are cached on disk (~7x faster after the first).

    The cache lives in this Python environment (``<prefix>/var/cache/vd-pint``), not in
    the user's cache folder: pint's cache records the paths of the definition files, so a
    cache shared between environments breaks when the one that wrote it is removed.
    Without a writable folder the registry is built without a cache.
    """
    import pint

    folder = Path(sys.prefix) / 'var' / 'cache' / 'vd-pint'
    try:
        folder.mkdir(parents=True, exist_ok=True)
        return pint.UnitRegistry(cache_folder=folder)
    except OSError:
        return pint.UnitRegistry()

#: "40m", "-1.5deg", "3e4 N/m": a number and an optional unit, with or without a space
_NUMBER_UNIT = re.compile(r'^([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*([A-Za-z%].*)?$')

#: largest integer read as a number (a float holds no more; 400 digits would overflow)
_LARGEST_INT = 10**308

#: quantity -> SI unit used inside vd (and in messages and ``--json`` output)
SI_UNITS: Mapping[str, str] = {
    'length': 'm',
    'road_length': 'm',
    'angle': 'rad',
    'force': 'N',
    'mass': 'kg',
    'time': 's',
    'velocity': 'm/s',
    'stiffness': 'N/m',
    'damping': 'N*s/m',
    'torsional_stiffness': 'N*m/rad',
    'torsional_damping': 'N*m*s/rad',
    'torque': 'N*m',
    'inertia': 'kg*m^2',
    'pressure': 'Pa',
    'density': 'kg/m^3',
    'area': 'm^2',
    'area_moment': 'm^4',
    'rack_ratio': 'm/rad',
    'acceleration': 'm/s^2',
    'frequency': '1/s',
    'angular_velocity': 'rad/s',
    'dimensionless': '',
}

BASE_QUANTITIES = ('length', 'force', 'angle', 'mass', 'time')

#: how derived quantities follow from the base units of a ``units:`` block
_DERIVED: Mapping[str, str] = {
    'velocity': '{length}/{time}',
    'stiffness': '{force}/{length}',
    'damping': '{force}*{time}/{length}',
    'torsional_stiffness': '{force}*{length}/{angle}',
    'torsional_damping': '{force}*{length}*{time}/{angle}',
    'torque': '{force}*{length}',
    'inertia': '{mass}*{length}^2',
    'pressure': '{force}/{length}^2',
    'density': '{mass}/{length}^3',
    'area': '{length}^2',
    'area_moment': '{length}^4',
    'rack_ratio': '{length}/revolution',
    'angular_velocity': '{angle}/{time}',
    'road_length': '{length}',
}

#: the abbreviations printed to users for SI units
SI_SYMBOLS: Mapping[str, str] = {
    'm': 'm', 'rad': 'rad', 'N': 'N', 'kg': 'kg', 's': 's', 'm/s': 'm/s', 'N/m': 'N/m',
    'N*s/m': 'N·s/m', 'N*m/rad': 'N·m/rad', 'N*m*s/rad': 'N·m·s/rad', 'N*m': 'N·m',
    'kg*m^2': 'kg·m²', 'Pa': 'Pa', 'kg/m^3': 'kg/m³', 'm^2': 'm²', 'm^4': 'm⁴',
    'm/rad': 'm/rad', 'm/s^2': 'm/s²', '1/s': '1/s', 'rad/s': 'rad/s',
    '': '-',
}


@lru_cache(maxsize=512)
def parse_unit(text: str) -> pint.Unit:
    """Parse a unit string; raise ``ValueError`` with a readable message."""
    from pint.errors import UndefinedUnitError

    try:
        return ureg().parse_units(text)
    except UndefinedUnitError as err:
        raise ValueError(f"unknown unit '{text}'") from err
    except Exception as err:  # noqa: BLE001 - pint's parser fails in many ways on bad text
        # (SyntaxError, ZeroDivisionError for 'N/(mm*0)', OverflowError, RecursionError...)
        raise ValueError(f"invalid unit '{text}'") from err


@lru_cache(maxsize=512)
def si_factor(unit: str, quantity: str) -> float:
    """
    Factor that converts a number in ``unit`` to the SI unit of ``quantity``.

    Raises ``ValueError`` for an unknown unit or one of the wrong dimension.
    """
    from pint.errors import DimensionalityError

    target = SI_UNITS[quantity]
    units = ureg()
    src = parse_unit(unit) if unit else units.dimensionless
    dst = parse_unit(target) if target else units.dimensionless
    wrong = ValueError(f"unit '{unit}' is not {_a(quantity)} unit (expected e.g. "
                       f"'{target or '-'}')")
    # pint counts angles as dimensionless, so only the radian power tells '%' from 'deg'
    if _radian_power(src) != _radian_power(dst):
        raise wrong
    try:
        factor = float(units.Quantity(1.0, src).to(dst).magnitude)
    except DimensionalityError as err:
        raise wrong from err
    except (ArithmeticError, ValueError) as err:  # 'mm*0' scales by zero, '1e999 m' by inf
        raise ValueError(f"invalid unit '{unit}'") from err
    if not math.isfinite(factor) or factor == 0.0:
        raise ValueError(f"invalid unit '{unit}' (its size is {factor:g} {target or '-'})")
    return factor


def _radian_power(unit: pint.Unit) -> int:
    powers = dict(ureg().Quantity(1.0, unit).to_root_units().unit_items())
    # pint types the exponents as any number; those of a unit are whole numbers
    return int(cast(float, powers.get('radian', 0)))


def _a(quantity: str) -> str:
    """Return the quantity's name with its article ('a length', 'an angle'), for messages."""
    name = quantity.replace('_', ' ')
    return f"{'an' if name[0] in 'aeiou' else 'a'} {name}"


class UnitSystem:
    """The units of one data file: quantity -> unit string."""

    def __init__(self, block: Mapping[str, str] | None, *, file: str) -> None:
        self.file = file
        #: whether the file has a units block: without one, a bare number has no unit
        self.declared = block is not None
        declared = dict(block or {})
        units: dict[str, str] = {}
        for quantity, unit in declared.items():
            if quantity not in SI_UNITS:
                raise DataError(
                    f"unknown quantity '{quantity}' (known: {', '.join(sorted(SI_UNITS))})",
                    file=file, key=f'units.{quantity}')
            if not isinstance(unit, str):
                raise DataError(f'unit must be a string, found {unit!r}', file=file,
                                key=f'units.{quantity}')
            try:
                si_factor(unit, quantity)
            except ValueError as err:
                raise DataError(str(err), file=file, key=f'units.{quantity}') from None
            units[quantity] = unit
        for quantity in BASE_QUANTITIES:
            units.setdefault(quantity, SI_UNITS[quantity])
        for quantity, pattern in _DERIVED.items():
            if quantity not in units:
                units[quantity] = pattern.format(**{q: f'({units[q]})' for q in BASE_QUANTITIES})
        units.setdefault('dimensionless', '')
        self.units = units

    def unit(self, quantity: str) -> str:
        return self.units[quantity]

    def bare_unit(self, quantity: str, *, key: str, value: object) -> str:
        """
        Return the unit of a number written without one.

        A file without a units block gives bare numbers no unit: ``rate: 30`` would
        silently be 30 N/m where the author meant N/mm. Only dimensionless values may then
        be bare.
        """
        if not self.declared and quantity != 'dimensionless':
            raise DataError(f'{value!r} has no unit and the file has no units block (add one, '
                            f"e.g. 'units: {{length: mm, force: N}}', or write the unit with "
                            f"the value, e.g. '{value} {SI_UNITS[quantity]}')", file=self.file,
                            key=key)
        return self.units[quantity]

    def display(self, quantity: str) -> str:
        """Short, readable unit for reports (``N/mm`` rather than ``(N)/(mm)``)."""
        unit = self.units[quantity]
        return format(parse_unit(unit), '~') if unit else '-'


def to_si(value: object, quantity: str, units: UnitSystem, *, key: str) -> float:
    """
    Convert one scalar (number, or ``"number unit"`` string) to SI.

    Raises ``DataError`` naming file and key for non-numbers, unknown units,
    units of the wrong dimension and NaN/inf.
    """
    if isinstance(value, bool):
        raise DataError(f'expected a number, found {value!r}', file=units.file, key=key)
    if isinstance(value, int) and abs(value) > _LARGEST_INT:
        raise DataError(f'number too large ({len(str(abs(value)))} digits)', file=units.file,
                        key=key)
    if isinstance(value, (int, float)):
        number, unit = float(value), units.bare_unit(quantity, key=key, value=value)
    elif isinstance(value, str) and _is_number(value):
        # PyYAML reads YAML 1.1, where '7.0e7' (no exponent sign) is a string.
        number, unit = float(value), units.bare_unit(quantity, key=key, value=value)
    elif isinstance(value, str):
        number, unit = parse_quantity(value, quantity, file=units.file, key=key)
    else:
        raise DataError(f'expected a number, found {type(value).__name__} {value!r}',
                        file=units.file, key=key)
    try:
        result = number * si_factor(unit, quantity)
    except ValueError as err:
        raise DataError(str(err), file=units.file, key=key) from None
    if not math.isfinite(result):
        raise DataError(f'value must be finite, found {value!r}', file=units.file, key=key)
    return result


def parse_quantity(text: str, quantity: str, *, file: str | None, key: str) -> tuple[float, str]:
    """Split ``"-1.5 deg"`` into (number, unit); a bare number only for dimensionless."""
    match = _NUMBER_UNIT.match(text.strip())
    parts = ([match.group(1), match.group(2)] if match and match.group(2)
             else text.strip().split(None, 1))
    try:
        number = float(parts[0])
    except (ValueError, IndexError):
        raise DataError(f'expected a number with a unit, found {text!r}', file=file,
                        key=key) from None
    if not math.isfinite(number):
        raise DataError(f'value must be finite, found {text!r}', file=file, key=key)
    if len(parts) == 1:
        if quantity != 'dimensionless':
            raise DataError(
                f"value {text!r} needs a unit ({_a(quantity)}, e.g. '{parts[0]} "
                f"{SI_UNITS[quantity]}')", file=file, key=key)
        return number, ''
    unit = parts[1].strip()
    try:
        si_factor(unit, quantity)
    except ValueError as err:
        raise DataError(str(err), file=file, key=key) from None
    return number, unit


def display_si(quantity: str) -> str:
    return SI_SYMBOLS[SI_UNITS[quantity]]


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True
