# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Event parameters ``NAME=VALUE`` with units, validated against an event's spec."""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
import math

from vd_data_server.errors import DataError
from vd_data_server.units import SI_UNITS, parse_quantity, si_factor


@dataclass(frozen=True)
class Param:
    quantity: str  # a vd_data_server.units quantity, or "integer"
    default: float  # SI
    doc: str
    minimum: float | None = None
    maximum: float | None = None


def parse_params(event: str, spec: Mapping[str, Param], items: Sequence[str]) -> dict[str, float]:
    """
    Defaults from ``spec``, replaced by ``items`` (``["radius=100 m", "steps=51"]``).

    Raises DataError naming the event and the parameter.
    """
    values = {name: p.default for name, p in spec.items()}
    for item in items:
        name, sep, text = item.partition('=')
        name = name.strip()
        if not sep or name not in spec:
            raise DataError(f"unknown parameter '{name}' (parameters of {event}: "
                            f"{', '.join(spec) or 'none'})", file=f'event {event}')
        p = spec[name]
        if p.quantity == 'integer':
            try:
                value = float(int(text.strip()))
            except (ValueError, OverflowError):
                raise DataError(f'expected a whole number, found {text.strip()!r}',
                                file=f'event {event}', key=name) from None
        else:
            number, unit = parse_quantity(text, p.quantity, file=f'event {event}', key=name)
            value = number * si_factor(unit, p.quantity)
            if not math.isfinite(value):
                raise DataError(f'value must be finite, found {text.strip()!r}',
                                file=f'event {event}', key=name)
        if (p.minimum is not None and value < p.minimum) or (
                p.maximum is not None and value > p.maximum):
            low = '-inf' if p.minimum is None else f'{p.minimum:g}'
            high = 'inf' if p.maximum is None else f'{p.maximum:g}'
            raise DataError(f"{text.strip()} is outside [{low}, {high}] "
                            f"{SI_UNITS.get(p.quantity, '')}".rstrip(), file=f'event {event}',
                            key=name)
        values[name] = value
    return values
