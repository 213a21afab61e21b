# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
A loaded study: master file + every resolved configuration + the feedback.

The feedback is the thesis' overview tab (§2.3, Figs. 2.3.1-2.3.3): per
configuration and input group, the variant, whether the data fed to the models
is ``UNCHANGED`` from the shared data file or ``MODIFIED`` (with the modified
keys: data-file value, master value, unit), and whether all configurations use
the ``SAME`` data for the group or it ``DIFFERS``.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

from . import schema
from .errors import DataError, DataErrors
from .master import GroupCache, MasterFile, load_master, resolve
from .model import Configuration, Value
from .units import SI_UNITS, si_factor

State = Literal['UNCHANGED', 'MODIFIED']
#: the variant shown for an optional group a configuration does not use
NOT_USED = ''
Consistency = Literal['SAME', 'DIFFERS']


@dataclass(frozen=True)
class ModifiedKey:
    key: str
    data_value: str
    master_value: str
    unit: str


@dataclass(frozen=True)
class GroupStatus:
    configuration: str
    group: str
    variant: str
    state: State
    consistency: Consistency
    modified_keys: tuple[ModifiedKey, ...]


@dataclass(frozen=True)
class Study:
    master: MasterFile
    configurations: Mapping[str, Configuration]
    status: tuple[GroupStatus, ...]
    groups: tuple[str, ...]
    #: unusual values of the data files read (plausibility warnings), once each
    warnings: tuple[str, ...] = ()

    @property
    def configuration_names(self) -> list[str]:
        return list(self.configurations)

    def configurations_in(self, target: str | Path) -> list[str]:
        """Return the configuration names of master file ``target`` (none if it is new)."""
        target = Path(target)
        if target.resolve() == self.master.path.resolve():
            return self.configuration_names
        return load_study(target).configuration_names if target.exists() else []

    def status_of(self, configuration: str, group: str) -> GroupStatus:
        for entry in self.status:
            if entry.configuration == configuration and entry.group == group:
                return entry
        raise KeyError((configuration, group))

    def flexible_switches(self) -> dict[str, tuple[bool, tuple[str, ...]]]:
        """Per configuration: flexible components on, and the chosen subset (empty: all)."""
        return {n: (c.flexible, tuple(c.flexible_components))
                for n, c in self.configurations.items()}

    def to_json(self) -> dict[str, Any]:
        """Return the ``vd data status --json`` contract (ARCHITECTURE §5)."""
        switches = self.flexible_switches()
        consistency = 'SAME' if len(set(switches.values())) == 1 else 'DIFFERS'
        return {
            'flexible': [{'configuration': n, 'flexible': on, 'components': list(comps),
                          'consistency': consistency} for n, (on, comps) in switches.items()],
            'master': str(self.master.path),
            'configurations': self.configuration_names,
            'groups': list(self.groups),
            'status': [
                {'configuration': s.configuration, 'group': s.group, 'variant': s.variant,
                 'state': s.state, 'consistency': s.consistency,
                 'modified_keys': [vars(m) for m in s.modified_keys]}
                for s in self.status
            ],
        }


def load_study(master_path: str | Path, *, data_root: str | Path | None = None,
               extra_overrides: Mapping[str, Mapping[str, Any]] | None = None,
               extra_source: str = '--set') -> Study:
    """
    Load and resolve everything; all problems of all configurations are collected.

    ``extra_overrides`` maps configuration name -> {group.key: value} (edits made
    over ROS, ``--set``; ``extra_source`` names them); they count as master-file
    modifications.
    """
    master = load_master(master_path, data_root=data_root)
    cache = GroupCache(master)
    configs: dict[str, Configuration] = {}
    errors: list[DataError] = []
    for name in master.configurations:
        try:
            configs[name] = resolve(master, name, cache, (extra_overrides or {}).get(name),
                                    extra_source)
        except DataErrors as err:
            errors += err.errors
        except DataError as err:
            errors.append(err)
    # a broken file shared by several groups or configurations is reported once
    errors = list({str(e): e for e in errors}.values())
    if errors:
        raise errors[0] if len(errors) == 1 else DataErrors(errors)
    for config in configs.values():
        try:
            config.data_hash  # noqa: B018 - computed here as a run computes it
        except ValueError as err:
            raise DataError(f'cannot compute the data hash: {err}', file=master.display,
                            key=f'configurations.{config.name}') from None
    groups = _ordered_groups(configs.values())
    status = feedback(master, configs, cache, groups)
    warnings = tuple(dict.fromkeys(w for g in cache.loaded() for w in g.warnings))
    return Study(master=master, configurations=configs, status=status, groups=groups,
                 warnings=warnings)


def _ordered_groups(configs: Any) -> tuple[str, ...]:
    present = {g for c in configs for g in c.groups}
    return tuple(g for g in schema.all_group_names() if g in present)


def feedback(master: MasterFile, configs: Mapping[str, Configuration], cache: GroupCache,
             groups: Sequence[str]) -> tuple[GroupStatus, ...]:
    rows: list[GroupStatus] = []
    for group in groups:
        users = [c for c in configs.values() if group in c.groups]
        first = users[0].groups[group]
        same = len(users) == len(configs) and all(
            _same_group(first.values, c.groups[group].values) for c in users)
        for config in configs.values():
            if group not in config.groups:
                # the group is optional and this configuration does without it
                rows.append(GroupStatus(config.name, group, NOT_USED, 'UNCHANGED', 'DIFFERS', ()))
                continue
            data = config.groups[group]
            shared = cache.get(group, data.variant)
            modified = tuple(modified_keys(shared.values, data.values))
            rows.append(GroupStatus(config.name, group, data.variant,
                                    'MODIFIED' if modified else 'UNCHANGED',
                                    'SAME' if same else 'DIFFERS', modified))
    return tuple(rows)


def _same_group(a: Mapping[str, Value], b: Mapping[str, Value]) -> bool:
    return a.keys() == b.keys() and all(a[k].same_data(b[k]) for k in a)


def modified_keys(shared: Mapping[str, Value], fed: Mapping[str, Value]) -> list[ModifiedKey]:
    out = []
    for key, value in fed.items():
        ref = shared.get(key)
        if ref is not None and ref.same_data(value):
            continue
        unit = value.display_unit or value.unit
        out.append(ModifiedKey(key, format_value(ref, unit) if ref else '-',
                               format_value(value, unit), unit))
    return out


def format_value(value: Value, unit: str) -> str:
    """Return a value in a display unit, as a short text for tables."""
    if value.type == 'text':
        return str(value.si)
    if value.type == 'curve':
        xs, ys = value.table()
        return f'curve of {len(xs)} points, y {min(ys):.6g}..{max(ys):.6g} {value.unit}'
    quantity = _quantity_of(value.unit)
    factor = 1.0
    if unit and quantity is not None:
        try:
            factor = si_factor(unit, quantity)
        except ValueError:
            factor = 1.0
    if value.type in ('point', 'vector'):
        return '[' + ', '.join(f'{c / factor:.6g}' for c in value.triple()) + ']'
    return f'{value.number() / factor:.6g}'


def _quantity_of(unit: str) -> str | None:
    for quantity, si in SI_UNITS.items():
        if si == unit:
            return quantity
    return None
