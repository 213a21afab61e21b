# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Master files (studies): configurations that pick variants and override values.

Layout::

    study:
      name: Sample sedan study
      vehicle: sedan            # folder of the vehicle under the data root
      data_root: ..             # relative to this file (default: ..)
    defaults:                   # variant per input group, for every configuration
      front_spring: X
    configurations:
      baseline:
        description: reference car
      soft_front:
        variants: {front_spring: Y}
        overrides:
          front_alignment.camber: -1.2 deg
          front_hardpoints.points.lca_outer.z: -170 mm
        flexible: false

A variant ``V`` of group ``G`` is the file ``<data_root>/<vehicle>/<G>/<V>.yaml``.
Only files under the data root are ever read.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
import hashlib
import os
from pathlib import Path
from typing import Any

from . import schema
from .datafile import _check_range, load_group_file, parse_override
from .errors import DataError, DataErrors
from .model import Configuration, GroupData, Value
from .plausibility import check_point
from .reads import note_read
from .shape import PLAIN_NAME, Collector, check
from .shared import check_shared_facts
from .tir import read_tir
from .tire_group import tire_properties, with_tire
from .yamlio import load_file

COORDS = {'x': 0, 'y': 1, 'z': 2}


@dataclass(frozen=True)
class ConfigurationSpec:
    name: str
    description: str
    variants: Mapping[str, str]
    overrides: Mapping[str, Any]
    flexible: bool
    flexible_components: tuple[str, ...]


@dataclass(frozen=True)
class MasterFile:
    path: Path
    name: str
    description: str
    vehicle: str
    data_root: Path
    configurations: Mapping[str, ConfigurationSpec]

    @property
    def display(self) -> str:
        return str(self.path)


def inside(root: Path, path: Path) -> bool:
    """
    Return True if ``path`` lies under ``root`` once '..', '.' and symbolic links are resolved.

    Names such as ``../../etc/passwd`` are refused, and so is a link inside the data
    root that points out of it (checked before the file is opened, so its content is
    never read or quoted). A symlink install of the whole data root is fine: the root
    is resolved too.
    """
    root_real = os.path.realpath(root)
    path_real = os.path.realpath(path)
    return os.path.commonpath([root_real, path_real]) == root_real


def load_master(path: str | Path, *, data_root: str | Path | None = None) -> MasterFile:
    """Read and check a master file (``schema.MASTER``); every problem is reported."""
    path = Path(path)
    display = str(path)
    raw = load_file(path, display=display)
    if not isinstance(raw, Mapping):
        raise DataError("expected a mapping with 'study', 'defaults' and 'configurations'",
                        file=display)
    col = Collector(display)
    check(schema.MASTER, raw, '', col)
    study = raw.get('study')
    if not isinstance(study, Mapping):
        col.raise_if_any()
        raise DataError("missing required mapping 'study' (name, vehicle)", file=display,
                        key='study')
    vehicle = str(study.get('vehicle') or '')
    # real paths: a master file linked from elsewhere (a symlink install links every
    # file) names its data root relative to where it really is
    if data_root is None:
        root = Path(os.path.realpath(Path(os.path.realpath(path)).parent /
                                     str(study.get('data_root') or '..')))
    else:
        root = Path(os.path.realpath(data_root))
    try:
        root_is_dir = root.is_dir()
    except OSError:  # a name too long, a loop of links
        root_is_dir = False
    if not root_is_dir:
        col.add('study.data_root', f'the data root {root} is not a folder', study, 'data_root')
    defaults = _mapping(raw.get('defaults'))
    configs_raw = raw.get('configurations')
    configs: dict[str, ConfigurationSpec] = {}
    for name, body in (configs_raw.items() if isinstance(configs_raw, Mapping) else ()):
        if not isinstance(name, str) or not PLAIN_NAME.match(name):
            continue  # reported by the walker
        if not isinstance(body, Mapping):
            body = {}
        variants = _mapping(body.get('variants'))
        overrides = _mapping(body.get('overrides'))
        merged = {**defaults, **variants}
        where = f'configurations.{name}'
        for group in schema.REQUIRED_GROUPS:
            if group not in merged:
                col.add(f'{where}.variants.{group}', "no variant chosen (neither in 'defaults' "
                        "nor in the configuration)", configs_raw, name)
        flexible = body.get('flexible') or False
        components = tuple(flexible) if isinstance(flexible, list) else ()
        chosen = body.get('flexible_components')
        if isinstance(chosen, list) and chosen:  # anything else is reported by the walker
            if components:
                col.add(f'{where}.flexible_components', "give the components either as the "
                        "'flexible' list or here, not both", body, 'flexible_components')
            components = tuple(str(c) for c in chosen)
        configs[name] = ConfigurationSpec(name, str(body.get('description') or ''),
                                          {str(k): str(v) for k, v in merged.items()},
                                          dict(overrides), bool(flexible or components),
                                          components)
    col.raise_if_any()
    return MasterFile(path=path, name=str(study['name']), description=str(study.get(
        'description') or ''), vehicle=vehicle, data_root=root, configurations=configs)


def _mapping(node: Any) -> Mapping[str, Any]:
    return node if isinstance(node, Mapping) else {}


class GroupCache:
    """Loads each (group, variant) file once per study load."""

    def __init__(self, master: MasterFile) -> None:
        self.master = master
        self._cache: dict[tuple[str, str], GroupData] = {}
        self.extra_hashes: dict[str, str] = {}

    def variant_path(self, group: str, variant: str) -> tuple[Path, str]:
        rel = f'{self.master.vehicle}/{group}/{variant}.yaml'
        return self.master.data_root / rel, rel

    def get(self, group: str, variant: str) -> GroupData:
        key = (group, variant)
        if key not in self._cache:
            path, rel = self.variant_path(group, variant)
            if not inside(self.master.data_root, path):
                raise DataError(f'resolves outside the data root {self.master.data_root} '
                                '(a symbolic link?): not read', file=rel)
            if not _is_file(path):
                available = self.available(group)
                raise DataError(
                    f"variant '{variant}' of group '{group}' does not exist (no file {rel}; "
                    f"available: {', '.join(available) or 'none'})", file=self.master.display)
            data = load_group_file(path, display=rel, group=group, variant=variant)
            if data.kind == 'tire':
                data = self._with_tire(data)
            elif data.kind == 'flex':
                data = self._with_imported(data)
            elif data.kind == 'road' and data.has('file'):
                self._road_file(data)
            self._cache[key] = data
        return self._cache[key]

    def loaded(self) -> list[GroupData]:
        """Every data file read so far, as read (before overrides)."""
        return list(self._cache.values())

    def available(self, group: str) -> list[str]:
        folder = self.master.data_root / self.master.vehicle / group
        return sorted(p.stem for p in folder.glob('*.yaml')) if folder.is_dir() else []

    def _with_imported(self, data: GroupData) -> GroupData:
        return _read_imported(self, data) if _imported_keys(data) else data

    def _road_file(self, data: GroupData) -> None:
        """Check an OpenCRG file: inside the data root, present; its hash joins the data's."""
        rel, path = self._data_file(data, 'data.file')
        if not _is_file(path):
            raise DataError(f"road file '{rel}' does not exist", file=data.file,
                            key='data.file')
        self.extra_hashes[rel] = hashlib.sha256(path.read_bytes()).hexdigest()[:16]

    def _data_file(self, data: GroupData, key: str) -> tuple[str, Path]:
        """Return a group's ``file`` as written and its path, refused outside the data root."""
        rel = data.text('file')
        path = self.master.data_root / rel
        if not inside(self.master.data_root, path):
            raise DataError(f"'{rel}' is outside the data root {self.master.data_root}",
                            file=data.file, key=key)
        return rel, path

    def _with_tire(self, data: GroupData) -> GroupData:
        rel, path = self._data_file(data, 'file')
        props = read_tir(path)
        raw = path.read_bytes()
        note_read(path, raw)
        self.extra_hashes[rel] = hashlib.sha256(raw).hexdigest()[:16]
        return with_tire(data, props, rel)


def _is_file(path: Path) -> bool:
    try:
        return path.is_file()
    except OSError:  # a name too long for the file system
        return False


def _imported_keys(data: GroupData) -> list[str]:
    return sorted(k for k in data.values if k.startswith('components.')
                  and k.endswith('.imported.file'))


def _read_imported(cache: "GroupCache", data: GroupData) -> GroupData:
    values = dict(data.values)
    for key in _imported_keys(data):
        rel = data.text(key)
        path = cache.master.data_root / rel
        if not inside(cache.master.data_root, path):
            raise DataError(f"'{rel}' is outside the data root {cache.master.data_root}",
                            file=data.file, key=key)
        if not _is_file(path):
            raise DataError(f"reduced stiffness file '{rel}' does not exist", file=data.file,
                            key=key)
        raw = path.read_bytes()
        note_read(path, raw)
        if len(raw) > IMPORTED_MAX_BYTES:
            raise DataError(f"reduced stiffness file '{rel}' is larger than "
                            f"{IMPORTED_MAX_BYTES // 1_000_000} MB", file=data.file, key=key)
        try:
            text = raw.decode('utf-8')
        except UnicodeDecodeError:
            raise DataError(f"reduced stiffness file '{rel}' is not UTF-8 text", file=data.file,
                            key=key) from None
        cache.extra_hashes[rel] = hashlib.sha256(raw).hexdigest()[:16]
        content = key[: -len('file')] + 'content'
        values[content] = Value(content, 'text', text, source=rel)
    return GroupData(data.group, data.kind, data.variant, data.file, values, data.description)


#: largest reduced stiffness file read (a 50-node superelement in text is ~2 MB)
IMPORTED_MAX_BYTES = 20_000_000


def resolve(master: MasterFile, name: str, cache: GroupCache | None = None,
            extra_overrides: Mapping[str, Any] | None = None,
            extra_source: str = '--set') -> Configuration:
    """
    Resolve one configuration, each value keeping its source.

    Variants, then master overrides, then ``extra_overrides`` (``vd run --set``, or edits
    over ROS: ``extra_source`` names them in messages and in each value's source).
    """
    if name not in master.configurations:
        raise DataError(f"configuration '{name}' does not exist (available: "
                        f"{', '.join(master.configurations)})", file=master.display)
    spec = master.configurations[name]
    cache = cache or GroupCache(master)
    groups: dict[str, GroupData] = {}
    errors: list[DataError] = []
    for group, variant in spec.variants.items():
        try:
            groups[group] = cache.get(group, variant)
        except DataErrors as err:
            errors += err.errors
        except DataError as err:
            errors.append(err)
    if errors:  # every broken file of the configuration, not only the first
        raise errors[0] if len(errors) == 1 else DataErrors(errors)
    groups = apply_overrides(groups, spec.overrides, file=master.display,
                             where=f'configurations.{name}.overrides')
    if extra_overrides:
        groups = apply_overrides(groups, extra_overrides, file=extra_source, where='')
    check_geometry(groups, file=master.display, configuration=name)
    check_flexible(groups, spec.flexible_components, file=master.display, configuration=name)
    check_shared_facts(groups)
    for data in groups.values():
        if data.kind == 'tire':
            tire_properties(data)  # the coefficients after overrides, as a solver reads them
    tire_files = {g.text('file') for g in groups.values() if g.kind == 'tire'}
    tire_files |= {g.text(k) for g in groups.values() if g.kind == 'flex'
                   for k in _imported_keys(g)}
    tire_files |= {g.text('file') for g in groups.values() if g.kind == 'road' and g.has('file')}
    hashes = {k: v for k, v in cache.extra_hashes.items() if k in tire_files}
    return Configuration(name=name, master_file=master.display, description=spec.description,
                         groups=groups, flexible=spec.flexible,
                         flexible_components=spec.flexible_components, extra_hashes=hashes)


#: how far the geometry group may disagree with the wheel-centre hard points, m
GEOMETRY_TOLERANCE = 0.001


def check_geometry(groups: Mapping[str, GroupData], *, file: str, configuration: str) -> None:
    """
    Wheelbase and tracks must describe the car the hard points describe.

    The geometry group states them for the models that do not read hard points; a
    designer who moves a wheel centre (or edits the geometry) must keep both in step.
    """
    geo = groups.get('geometry')
    front, rear = groups.get('front_hardpoints'), groups.get('rear_hardpoints')
    if geo is None or front is None or rear is None:
        return
    wc_f, wc_r = front.point('points.wheel_centre'), rear.point('points.wheel_centre')
    checks = (('wheelbase', wc_f[0] - wc_r[0], 'the x distance of the front and rear wheel '
               'centres'),
              ('track_front', 2.0 * wc_f[1], 'twice the front wheel-centre y'),
              ('track_rear', 2.0 * wc_r[1], 'twice the rear wheel-centre y'))
    errors = [
        DataError(f'{key} = {geo.scalar(key) * 1e3:.1f} mm but {what} is {value * 1e3:.1f} mm '
                  f'(hard points {front.file}, {rear.file}); keep them within '
                  f'{GEOMETRY_TOLERANCE * 1e3:g} mm', file=file,
                  key=f'configurations.{configuration}: geometry.{key}')
        for key, value, what in checks if abs(geo.scalar(key) - value) > GEOMETRY_TOLERANCE]
    if errors:
        raise errors[0] if len(errors) == 1 else DataErrors(errors)


def flex_components(groups: Mapping[str, GroupData]) -> dict[str, tuple[str, ...]]:
    """Flexible components defined per axle (from the ``<axle>_flex`` groups)."""
    out = {}
    for axle in schema.AXLES:
        g = groups.get(f'{axle}_flex')
        if g is not None:
            out[axle] = tuple(sorted({k.split('.')[1] for k in g.values
                                      if k.startswith('components.')}))
    return out


def check_flexible(groups: Mapping[str, GroupData], chosen: Sequence[str], *, file: str,
                   configuration: str) -> None:
    """
    Check the flexible components of the flex groups and of a configuration.

    Flex components must exist in the axle's template, and a configuration's
    chosen ``flexible_components`` in its flex groups.
    """
    errors = []
    defined = flex_components(groups)
    for axle, names in defined.items():
        hp = groups.get(f'{axle}_hardpoints')
        if hp is None:
            continue
        template = hp.text('template')
        known = schema.TEMPLATE_COMPONENTS[template]
        with_bar = f'{axle}_stabilizer' in groups
        flex = groups[f'{axle}_flex']
        points = {k.split('.', 1)[1] for k in hp.values if k.startswith('points.')}
        for name in names:
            if name == schema.SUBFRAME_COMPONENT:
                missing = [p for p in schema.SUBFRAME_POINTS if p not in points]
                if missing:
                    errors.append(DataError(
                        f"a flexible subframe needs its body mounts: hard point(s) "
                        f"{', '.join(missing)} missing in {hp.file}", file=flex.file,
                        key=f'components.{name}'))
            elif name == schema.BAR_COMPONENT and not with_bar:
                errors.append(DataError(f'the {axle} axle has no anti-roll bar '
                                        f'({axle}_stabilizer) to make flexible', file=flex.file,
                                        key=f'components.{name}'))
            elif name != schema.BAR_COMPONENT and name not in known:
                offered = (known + ((schema.BAR_COMPONENT,) if with_bar else ())
                           + (schema.SUBFRAME_COMPONENT,))
                errors.append(DataError(
                    f"template '{template}' has no component '{name}' (components: "
                    f"{', '.join(offered)})",
                    file=flex.file, key=f'components.{name}'))
    every = {n for names in defined.values() for n in names}
    for name in chosen:
        if name not in every:
            errors.append(DataError(
                f"flexible component '{name}' is not defined in the configuration's flex "
                f"data (defined: {', '.join(sorted(every)) or 'none'})", file=file,
                key=f'configurations.{configuration}.flexible_components'))
    if errors:
        raise errors[0] if len(errors) == 1 else DataErrors(errors)


def apply_overrides(groups: Mapping[str, GroupData], overrides: Mapping[str, Any], *, file: str,
                    where: str) -> dict[str, GroupData]:
    out = dict(groups)
    errors: list[DataError] = []
    for dotted, raw in overrides.items():
        key_label = f'{where}.{dotted}' if where else str(dotted)
        try:
            out = _apply_one(out, str(dotted), raw, file=file, label=key_label)
        except DataError as err:
            errors.append(err)
    if errors:
        raise errors[0] if len(errors) == 1 else DataErrors(errors)
    return out


def _apply_one(groups: dict[str, GroupData], dotted: str, raw: Any, *, file: str,
               label: str) -> dict[str, GroupData]:
    group_name, _, key = dotted.partition('.')
    if group_name not in groups or not key:
        raise DataError(f"override of unknown group '{group_name}' (groups: "
                        f"{', '.join(groups)}); write GROUP.KEY", file=file, key=label)
    group = groups[group_name]
    source = f'master override {label}' if label != dotted else f'{file} {dotted}'
    coord = None
    if key not in group.values and key[-2:] in ('.x', '.y', '.z') and key[:-2] in group.values:
        key, coord = key[:-2], key[-1]
    if key not in group.values:
        raise DataError(f"key '{key}' does not exist in group '{group_name}' ({group.file}); "
                        f"keys: {', '.join(sorted(group.values))}", file=file, key=label)
    old = group.values[key]
    if coord is not None:
        if old.type != 'point':
            raise DataError(f"'{key}' is a {old.type}, not a point", file=file, key=label)
        axis = Value(key, 'scalar', 0.0, 'm', display_unit=old.display_unit)
        number = parse_override(raw, axis, file=file, key=label).number()
        xyz = list(old.triple())
        xyz[COORDS[coord]] = number
        check_point((xyz[0], xyz[1], xyz[2]), file=file, key=label, raw=raw)
        new = Value(key, 'point', tuple(xyz), 'm', display_unit=old.display_unit, source=source)
    else:
        new = parse_override(raw, old, file=file, key=label).with_source(source)
        spec = schema.leaf_spec(group.kind, key)
        if isinstance(spec, schema.Scalar):
            _check_range(new.number(), spec, file, label, raw)
        if isinstance(spec, schema.Text) and spec.choices and new.si not in spec.choices:
            raise DataError(f"'{new.si}' is not one of: {', '.join(spec.choices)}", file=file,
                            key=label)
    values = dict(group.values)
    values[key] = new
    groups[group_name] = GroupData(group.group, group.kind, group.variant, group.file, values,
                                   group.description)
    return groups


def with_overrides(config: Configuration, overrides: Mapping[str, Any],
                   source: str = '--set') -> Configuration:
    """
    Return ``config`` with temporary overrides (``vd run --set``, action goals) applied.

    ``source`` names where they came from in messages (``--set``, ``overrides`` of a goal).
    """
    if not overrides:
        return config
    groups = apply_overrides(config.groups, overrides, file=source, where='')
    check_geometry(groups, file=source, configuration=config.name)
    check_shared_facts(groups)
    for group in groups.values():
        if group.kind == 'tire':
            tire_properties(group)
    return Configuration(name=config.name, master_file=config.master_file,
                         description=config.description, groups=groups,
                         flexible=config.flexible, flexible_components=config.flexible_components,
                         extra_hashes=config.extra_hashes)


def parse_set(items: Sequence[str], source: str = '--set') -> dict[str, str]:
    """``["front_alignment.camber=-1 deg"]`` -> ``{"front_alignment.camber": "-1 deg"}``."""
    out: dict[str, str] = {}
    for item in items:
        key, sep, value = item.partition('=')
        if not sep or not key.strip() or not value.strip():
            raise DataError(f'expected GROUP.KEY=VALUE, found {item!r}', file=source)
        out[key.strip()] = value.strip()
    return out
