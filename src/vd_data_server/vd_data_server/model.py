# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The resolved vehicle data: flat, SI, every value with its unit and source.

A group's values are keyed by their path inside the data file's ``data:``
block (``rate``, ``points.lca_outer``, ``connections.lca_front.stiffness.x``).
This flat form is what master-file overrides address, what the feedback
compares, what the ROS messages carry, and what the solvers read.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
import hashlib
import json
import math
from typing import Literal, Union

from .errors import DataError

ValueType = Literal['scalar', 'curve', 'point', 'vector', 'text']
SI = Union[float, str, tuple[float, ...], tuple[tuple[float, ...], tuple[float, ...]]]


@dataclass(frozen=True)
class Value:
    """
    One resolved value in SI.

    ``si`` is a float (scalar), a 3-tuple (point, vector), a pair of tuples
    ``(x, y)`` (curve) or a string (text). ``unit`` is the SI unit of the value
    (of y for curves), ``x_unit`` the SI unit of a curve's x. ``display_unit`` /
    ``x_display_unit`` are the units the data file was written in, for
    feedback and reports. ``source`` says where the number came from.
    """

    key: str
    type: ValueType
    si: SI
    unit: str = ''
    x_unit: str = ''
    display_unit: str = ''
    x_display_unit: str = ''
    source: str = ''

    def same_data(self, other: "Value") -> bool:
        """Equal content (the source is not compared)."""
        return self.type == other.type and _close(self.si, other.si)

    def with_source(self, source: str) -> "Value":
        return Value(self.key, self.type, self.si, self.unit, self.x_unit, self.display_unit,
                     self.x_display_unit, source)

    def number(self) -> float:
        """Return a scalar's value (SI); DataError for any other type."""
        si = self.si
        if isinstance(si, (int, float)) and not isinstance(si, bool):
            return float(si)
        raise DataError(f'a {self.type}, not a scalar', key=self.key)

    def triple(self) -> tuple[float, float, float]:
        """Return a point's or a vector's coordinates (SI); DataError for any other type."""
        si = self.si
        coords = [float(c) for c in si if isinstance(c, (int, float))] \
            if isinstance(si, tuple) and len(si) == 3 else []
        if len(coords) != 3:
            raise DataError(f'a {self.type}, not a point', key=self.key)
        return coords[0], coords[1], coords[2]

    def text(self) -> str:
        """Return a text's value; DataError for any other type."""
        if isinstance(self.si, str):
            return self.si
        raise DataError(f'a {self.type}, not a text', key=self.key)

    def table(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """Return a curve's (x, y) values (SI); DataError for any other type."""
        si = self.si
        if isinstance(si, tuple) and len(si) == 2:
            xs, ys = si
            if isinstance(xs, tuple) and isinstance(ys, tuple):
                return xs, ys
        raise DataError(f'a {self.type}, not a curve', key=self.key)


def _close(a: object, b: object) -> bool:
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    if isinstance(a, float) and isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-15)
    if isinstance(a, tuple) and isinstance(b, tuple) and len(a) == len(b):
        return all(_close(x, y) for x, y in zip(a, b))
    return False


@dataclass(frozen=True)
class GroupData:
    """One input group as fed to the models: kind, variant, file, values."""

    group: str
    kind: str
    variant: str
    file: str  # path relative to the data root
    values: Mapping[str, Value]
    description: str = ''
    #: unusual (not impossible) values of the file, ``file: key: message`` (plausibility.py)
    warnings: tuple[str, ...] = ()

    def scalar(self, key: str) -> float:
        return self.values[key].number()

    def get_scalar(self, key: str, default: float | None = None) -> float | None:
        value = self.values.get(key)
        return default if value is None else value.number()

    def point(self, key: str) -> tuple[float, float, float]:
        return self.values[key].triple()

    def curve(self, key: str) -> tuple[tuple[float, ...], tuple[float, ...]]:
        return self.values[key].table()

    def text(self, key: str) -> str:
        return str(self.values[key].si)

    def has(self, key: str) -> bool:
        return key in self.values


@dataclass(frozen=True)
class Configuration:
    """A resolved configuration: every group's data after variants and overrides."""

    name: str
    master_file: str
    description: str
    groups: Mapping[str, GroupData]
    flexible: bool = False
    flexible_components: tuple[str, ...] = ()
    extra_hashes: Mapping[str, str] = field(default_factory=dict)  # e.g. .tir file contents

    def group(self, name: str) -> GroupData:
        return self.groups[name]

    @property
    def data_hash(self) -> str:
        """Hash of everything a model reads (values, flexibility, referenced files)."""
        return configuration_hash(self)


def _canonical(value: Value) -> object:
    return [value.key, value.type, value.si, value.unit, value.x_unit]


def configuration_hash(config: Configuration) -> str:
    payload = {
        'groups': {
            name: {'kind': g.kind, 'values': [_canonical(v) for _, v in sorted(g.values.items())]}
            for name, g in sorted(config.groups.items())
        },
        'flexible': config.flexible,
        'flexible_components': list(config.flexible_components),
        'files': dict(sorted(config.extra_hashes.items())),
    }
    text = json.dumps(payload, sort_keys=True, separators=(',', ':'), allow_nan=False)
    return hashlib.sha256(text.encode()).hexdigest()[:16]
