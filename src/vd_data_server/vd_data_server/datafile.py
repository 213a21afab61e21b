# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Load one vehicle data file (one variant of one input group) into SI values.

File layout::

    kind: spring                # one of schema.KINDS
    description: ...            # optional
    source: ...                 # optional, where the numbers come from
    units: {length: mm, force: N}
    mirror: true                # hardpoints only: left side given, right mirrored
    data:
      rate: 36.9                # in the units block's stiffness unit (N/mm here)
      free_length: 306

Every problem is reported as ``file: key: message (line N)``; all problems of a
file are collected before raising.
"""
from __future__ import annotations

from collections.abc import Mapping
import math
from pathlib import Path
from typing import Any

from . import plausibility, schema
from .errors import DataError, DataErrors
from .model import GroupData, Value
from .shape import Collector, join, kind_of, section_keys
from .shared import group_facts
from .units import SI_UNITS, UnitSystem, parse_quantity, parse_unit, si_factor, to_si
from .yamlio import line_of, load_file

TOP_KEYS = ('kind', 'description', 'source', 'units', 'mirror', 'data')


def load_group_file(path: Path, *, display: str, group: str, variant: str) -> GroupData:
    """Read, validate and convert one data file. ``display`` is the path users see."""
    raw = load_file(path, display=display)
    return parse_group(raw, display=display, group=group, variant=variant)


def parse_group(raw: Any, *, display: str, group: str, variant: str) -> GroupData:
    col = Collector(display)
    if not isinstance(raw, Mapping):
        raise DataError("expected a mapping with 'kind', 'units' and 'data'", file=display)
    for key in raw:
        if key not in TOP_KEYS:
            col.add(key, f"unknown key (expected one of: {', '.join(TOP_KEYS)})", raw, key)
    expected_kind = schema.group_kind(group)
    kind = raw.get('kind')
    if kind is None:
        col.add('kind', f"missing required key (expected '{expected_kind}')")
    elif kind != expected_kind:
        col.add('kind', f"file is of kind '{kind}' but group '{group}' needs kind "
                f"'{expected_kind}'", raw, 'kind')
    if 'data' not in raw:
        col.add('data', 'missing required key')
    col.raise_if_any()
    if raw.get('units') is not None and not isinstance(raw.get('units'), Mapping):
        raise DataError('expected a mapping of quantity: unit', file=display, key='units')
    units = UnitSystem(raw.get('units'), file=display)
    mirror = raw.get('mirror', True)
    if 'mirror' in raw and kind != 'hardpoints':
        col.add('mirror', "only hardpoints files may set 'mirror'", raw, 'mirror')
    if not isinstance(mirror, bool):
        col.add('mirror', f'expected true or false, found {mirror!r}', raw, 'mirror')
    elif mirror is False:
        col.add('mirror', 'only left-side hard points mirrored to the right are supported '
                '(mirror: true); asymmetric suspensions are not', raw, 'mirror')
    values: dict[str, Value] = {}
    _walk(schema.KINDS[expected_kind], raw['data'], '', units, col, values, raw, 'data')
    if expected_kind == 'hardpoints' and not col.errors:
        _check_template_points(values, col, raw['data'])
    if expected_kind == 'flex' and not col.errors:
        _check_flex(values, col, raw['data'])
    if expected_kind == 'road' and not col.errors:
        _check_road(values, col, raw['data'])
    if expected_kind == 'stabilizer' and 'bar_radius' in values \
            and 'torsion_length' not in values:
        col.add('data.torsion_length', "required with bar_radius (the bar's torsional "
                "stiffness is G*pi*r^4/(2*L))", raw, 'data')
    col.raise_if_any()
    source = display if variant == '' else f'{display} (variant {variant})'
    values = {k: v.with_source(source) for k, v in values.items()}
    data = GroupData(group=group, kind=expected_kind, variant=variant, file=display,
                     values=values, description=str(raw.get('description') or ''),
                     warnings=tuple(col.warnings))
    errors = group_facts(data)
    if errors:
        raise errors[0] if len(errors) == 1 else DataErrors(errors)
    return data


#: the keys each road surface needs, and the keys it uses
ROAD_KEYS = {'flat': ((), ('friction', 'friction_left')),
             'iso8608': (('road_class', 'seed', 'length'),
                         ('friction', 'friction_left', 'tracks')),
             'obstacle': (('obstacle', 'height', 'obstacle_length', 'start', 'length'),
                          ('friction', 'friction_left', 'side')),
             'crg': (('file',), ('friction', 'friction_left'))}


def _check_road(values: dict[str, Value], col: Collector, data: Any) -> None:
    """Check that a road names what its surface needs and nothing another surface needs."""
    surface = values['surface'].text()
    needed, optional = ROAD_KEYS[surface]
    for key in needed:
        if key not in values:
            col.add(f'data.{key}', f"required for surface '{surface}'", data, 'surface')
    for key in values:
        if key != 'surface' and key not in needed and key not in optional:
            col.add(f'data.{key}', f"not used by surface '{surface}' (it uses: "
                    f"{', '.join(needed + optional)})", data, key)
    if 'seed' in values and values['seed'].number() != int(values['seed'].number()):
        col.add('data.seed', f"the seed must be an integer, found {values['seed'].number():g}",
                data, 'seed')
    if surface == 'obstacle' and not col.errors:
        start, length = values['start'].number(), values['length'].number()
        end = start + values['obstacle_length'].number()
        if end >= length:
            col.add('data.length', f'the road ({length:g} m) must reach beyond the obstacle '
                    f'(which ends at {end:g} m)', data, 'length')


def _walk(spec: schema.Spec, node: Any, path: str, units: UnitSystem, col: Collector,
          out: dict[str, Value], parent: Any, name: str) -> None:
    key = path or name  # the top-level section is named by its file key, 'data'
    if isinstance(spec, schema.Section):
        if not isinstance(node, Mapping):
            col.add(key, f'expected a mapping, found {kind_of(node)}', parent, name)
            return
        section_keys(spec, node, path, col, parent, name)
        for sub, sub_spec in spec.fields.items():
            if sub in node:
                _walk(sub_spec, node[sub], join(path, sub), units, col, out, node, sub)
            elif sub_spec.required and not any(sub in g for g in spec.one_of):
                continue  # reported by section_keys
            elif isinstance(sub_spec, schema.Scalar) and sub_spec.default is not None:
                out[join(path, sub)] = _scalar_value(join(path, sub), sub_spec.default,
                                                      sub_spec.quantity, units)
        return
    if isinstance(spec, schema.MapOf):
        if not isinstance(node, Mapping) or not node:
            col.add(key, f'expected a non-empty mapping of names, found {kind_of(node)}',
                    parent, name)
            return
        for sub, value in node.items():
            _walk(spec.value, value, join(path, sub), units, col, out, node, sub)
        return
    line = line_of(parent, name)
    where = f' (line {line})' if line else ''
    try:
        out[key] = _leaf(spec, node, key, units)
    except DataError as err:
        col.errors.append(DataError(err.detail + where, file=col.file, key=key))
        return
    value = out[key]
    warning = None
    if isinstance(spec, schema.Scalar):
        warning = plausibility.unusual_scalar(value.number(), spec.quantity)
    elif isinstance(spec, schema.Point):
        warning = plausibility.unusual_point(value.triple())
    if warning:
        col.warnings.append(f'{col.file}: {key}: {warning}{where}')


def _leaf(spec: schema.Spec, node: Any, key: str, units: UnitSystem) -> Value:
    file = units.file
    if isinstance(spec, schema.Scalar):
        si = to_si(node, spec.quantity, units, key=key)
        _check_range(si, spec, file, key, node)
        return _scalar_value(key, si, spec.quantity, units)
    if isinstance(spec, schema.Point):
        xyz = _triple(node, file, key)
        factor = si_factor(units.bare_unit('length', key=key, value=node), 'length')
        si_xyz = (xyz[0] * factor, xyz[1] * factor, xyz[2] * factor)
        plausibility.check_point(si_xyz, file=file, key=key, raw=node)
        return Value(key, 'point', si_xyz, 'm', display_unit=units.display('length'))
    if isinstance(spec, schema.Vector):
        xyz = _triple(node, file, key)
        norm = math.sqrt(sum(c * c for c in xyz))
        if norm == 0.0:
            raise DataError('direction must not be zero', file=file, key=key)
        return Value(key, 'vector', tuple(c / norm for c in xyz), '', display_unit='-')
    if isinstance(spec, schema.Text):
        if not isinstance(node, str) or not node:
            raise DataError(f'expected a text, found {kind_of(node)}', file=file, key=key)
        if spec.choices and node not in spec.choices:
            raise DataError(spec.refusal.format(value=node, choices=', '.join(spec.choices)),
                            file=file, key=key)
        return Value(key, 'text', node)
    if isinstance(spec, schema.Curve):
        return _curve(spec, node, key, units)
    raise TypeError(spec)  # pragma: no cover - the schema only holds the types above


def _scalar_value(key: str, si: float, quantity: str, units: UnitSystem) -> Value:
    return Value(key, 'scalar', float(si), SI_UNITS[quantity],
                 display_unit=units.unit(quantity) and units.display(quantity))


def _check_range(si: float, spec: schema.Scalar, file: str, key: str, raw: Any) -> None:
    plausibility.check_scalar(si, spec.quantity, file=file, key=key, raw=raw)
    if spec.positive and not si > 0.0:
        raise DataError(f'must be positive, found {raw!r}', file=file, key=key)
    if spec.minimum is not None and si < spec.minimum:
        raise DataError(f'must be >= {spec.minimum:g} {SI_UNITS[spec.quantity]}, found {raw!r}',
                        file=file, key=key)
    if spec.maximum is not None and si > spec.maximum:
        unit = SI_UNITS[spec.quantity]
        raise DataError(f"must be <= {spec.maximum:g}{' ' + unit if unit else ''}, found {raw!r}",
                        file=file, key=key)


def _triple(node: Any, file: str, key: str) -> tuple[float, float, float]:
    if (not isinstance(node, (list, tuple)) or len(node) != 3
            or not all(isinstance(c, (int, float)) and not isinstance(c, bool) for c in node)):
        raise DataError(f'expected [x, y, z] numbers, found {node!r}', file=file, key=key)
    if not all(_finite(c) for c in node):
        raise DataError(f'coordinates must be finite, found {node!r}', file=file, key=key)
    return (float(node[0]), float(node[1]), float(node[2]))


def _finite(number: float) -> bool:
    """Return True for a finite number, also for integers too large for a float."""
    try:
        return math.isfinite(float(number))
    except OverflowError:
        return False


def _curve(spec: schema.Curve, node: Any, key: str, units: UnitSystem) -> Value:
    file = units.file
    if not isinstance(node, Mapping) or set(node) - {'x', 'y', 'x_unit', 'y_unit'} \
            or 'x' not in node or 'y' not in node:
        raise DataError('expected a curve {x: [...], y: [...]} (optional x_unit, y_unit)',
                        file=file, key=key)
    x_unit = node.get('x_unit', units.unit(spec.x_quantity))
    y_unit = node.get('y_unit', units.unit(spec.y_quantity))
    try:
        fx = si_factor(str(x_unit), spec.x_quantity)
        fy = si_factor(str(y_unit), spec.y_quantity)
    except ValueError as err:
        raise DataError(str(err), file=file, key=key) from None
    xs, ys = node['x'], node['y']
    for axis, seq in (('x', xs), ('y', ys)):
        if (not isinstance(seq, list) or len(seq) < 2
                or not all(isinstance(c, (int, float)) and not isinstance(c, bool) for c in seq)):
            raise DataError(f'curve {axis} must be a list of at least 2 numbers', file=file,
                            key=key)
        if not all(_finite(c) for c in seq):
            raise DataError(f'curve {axis} values must be finite (no NaN)', file=file, key=key)
    if len(xs) != len(ys):
        raise DataError(f'curve x has {len(xs)} values but y has {len(ys)}', file=file, key=key)
    if any(b <= a for a, b in zip(xs, xs[1:])):
        raise DataError('curve x must be strictly increasing', file=file, key=key)
    if spec.increasing and any(b < a for a, b in zip(ys, ys[1:])):
        raise DataError('curve y must not decrease (non-monotonic force curve)', file=file,
                        key=key)
    x_si = tuple(float(c) * fx for c in xs)
    y_si = tuple(float(c) * fy for c in ys)
    if spec.x_minimum is not None and x_si[0] < spec.x_minimum:
        raise DataError(f'curve x must start at >= {spec.x_minimum:g}', file=file, key=key)
    if spec.y_minimum is not None and min(y_si) < spec.y_minimum:
        raise DataError(f'curve y must be >= {spec.y_minimum:g}', file=file, key=key)
    for axis, seq, quantity in (('x', x_si, spec.x_quantity), ('y', y_si, spec.y_quantity)):
        extreme = max(seq, key=abs)
        plausibility.check_scalar(extreme, quantity, file=file, key=f'{key}.{axis}',
                                  raw=f'{extreme:g} {SI_UNITS[quantity]}')
    return Value(key, 'curve', (x_si, y_si),
                 SI_UNITS[spec.y_quantity], SI_UNITS[spec.x_quantity],
                 display_unit=_short(str(y_unit)), x_display_unit=_short(str(x_unit)))


def _short(unit: str) -> str:
    return format(parse_unit(unit), '~') if unit else '-'


def _check_template_points(values: Mapping[str, Value], col: Collector, data: Any) -> None:
    template = str(values['template'].si)
    given = {k.split('.', 1)[1] for k in values if k.startswith('points.')}
    allowed = set(schema.TEMPLATE_POINTS[template]) | set(schema.OPTIONAL_POINTS)
    for missing in schema.TEMPLATE_POINTS[template]:
        if missing not in given:
            col.add(f'points.{missing}', f"missing hard point required by template "
                    f"'{template}'", data, 'points')
    points = data.get('points', {}) if isinstance(data, Mapping) else {}
    for extra in sorted(given - allowed):
        col.add(f'points.{extra}', f"unknown hard point for template '{template}' (expected: "
                f"{', '.join(sorted(allowed))})", points, extra)


def _names(values: Mapping[str, Value], prefix: str) -> set[str]:
    return {k.split('.')[1] for k in values if k.startswith(prefix + '.')}


def _check_flex(values: Mapping[str, Value], col: Collector, data: Any) -> None:
    """
    Check the cross-references of a flex file.

    Materials and sections named by components exist, every section has the dimensions
    of its shape, a component is either a beam frame (material + section) or imported,
    shape points lie along their member.
    """
    materials, sections = _names(values, 'materials'), _names(values, 'sections')
    for name in sorted(sections):
        shape = str(values[f'sections.{name}.shape'].si)
        given = {k.split('.')[2] for k in values if k.startswith(f'sections.{name}.')} - {'shape'}
        needed = set(schema.SECTION_SHAPES[shape])
        allowed = needed | ({'shear_area_y', 'shear_area_z'} if shape == 'general' else set())
        for key in sorted(needed - given):
            col.add(f'sections.{name}.{key}', f"required by shape '{shape}'")
        for key in sorted(given - allowed):
            col.add(f'sections.{name}.{key}', f"not a dimension of shape '{shape}' (expected: "
                    f"{', '.join(sorted(allowed))})")
    for comp in sorted(_names(values, 'components')):
        base = f'components.{comp}'
        imported = any(k.startswith(f'{base}.imported.') for k in values)
        beam = [k for k in ('material', 'section') if f'{base}.{k}' in values]
        if imported and beam:
            col.add(base, "give either 'imported' or a beam frame (material and section), "
                    "not both")
        elif not imported and len(beam) < 2 and not (comp == schema.BAR_COMPONENT
                                                     and beam == ['material']):
            # the bar's section may come from its stabilizer group (shared.py)
            col.add(base, "a beam frame needs both 'material' and 'section' (or give "
                    "'imported')")
        for key, known, what in (('material', materials, 'materials'),
                                 ('section', sections, 'sections'),
                                 ('arm_section', sections, 'sections')):
            if f'{base}.{key}' in values:
                ref = str(values[f'{base}.{key}'].si)
                if ref not in known:
                    col.add(f'{base}.{key}', f"'{ref}' is not in {what} (known: "
                            f"{', '.join(sorted(known)) or 'none'})")
        if f'{base}.arm_section' in values and comp != schema.BAR_COMPONENT:
            col.add(f'{base}.arm_section', f'only the {schema.BAR_COMPONENT} has arms')
        n = values[f'{base}.elements_per_member'].number()
        if n != int(n) or not 1 <= int(n) <= 50:
            col.add(f'{base}.elements_per_member', f'must be a whole number 1..50, found {n}')
        for sp in sorted(_names({k[len(base) + 1:]: v for k, v in values.items()
                                 if k.startswith(base + '.')}, 'shape_points')):
            f = values[f'{base}.shape_points.{sp}.fraction'].number()
            if not 0.0 < f < 1.0:
                col.add(f'{base}.shape_points.{sp}.fraction', f'must lie strictly between 0 '
                        f'and 1, found {f:g}')
        fmt = values.get(f'{base}.imported.format')
        if fmt is not None and fmt.si == 'dmig':
            for key in ('matrix', 'grids'):
                if not any(k.startswith(f'{base}.imported.{key}') for k in values):
                    col.add(f'{base}.imported.{key}', "required for format 'dmig'")


def parse_override(value: Any, template: Value, *, file: str, key: str) -> Value:
    """Convert a master-file override of an existing value, keeping its display unit."""
    if template.type == 'scalar':
        quantity = next((q for q, u in SI_UNITS.items() if u == template.unit), None)
        if quantity is None:
            raise DataError(f'values in {template.unit} cannot be overridden', file=file, key=key)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            if quantity != 'dimensionless':
                raise DataError(f"override {value!r} needs a unit (e.g. '{value} "
                                f"{template.display_unit or SI_UNITS[quantity]}')",
                                file=file, key=key)
            if not _finite(value):
                raise DataError(f'value must be finite, found {value!r}', file=file, key=key)
            number, unit = float(value), ''
        elif isinstance(value, str):
            number, unit = parse_quantity(value, quantity, file=file, key=key)
        else:
            raise DataError(f'expected a number with a unit, found {value!r}', file=file, key=key)
        si = number * si_factor(unit, quantity)
        if not math.isfinite(si):
            raise DataError(f'value must be finite, found {value!r}', file=file, key=key)
        return Value(template.key, 'scalar', si, template.unit, display_unit=template.display_unit)
    if template.type == 'text':
        if not isinstance(value, str) or not value:
            raise DataError(f'expected a text, found {value!r}', file=file, key=key)
        return Value(template.key, 'text', value)
    raise DataError(f"a {template.type} cannot be overridden as a whole; override a single "
                    "value (e.g. a coordinate '.x', '.y' or '.z' of a point)", file=file, key=key)
