# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Human-readable views of a study: the thesis' overview tab as a coloured table."""
from __future__ import annotations

from typing import Any, cast

from rich.console import Console
from rich.table import Table
from rich.text import Text

from .model import Configuration, Value
from .study import NOT_USED, Study, format_value

GREEN = 'bold green'
#: width used when the output is not a terminal (pipes, CI logs): wide enough that
#: group names and values are never cut
PIPE_WIDTH = 140


def console():
    """Return a rich console: the terminal's width, or PIPE_WIDTH when piped."""
    probe = Console()
    return Console(highlight=False, width=None if probe.is_terminal else PIPE_WIDTH)
RED = 'bold red'


def status_table(study: Study) -> Table:
    """
    Return the overview table of a study.

    Rows: input groups; columns: configurations (variant, green unchanged / red
    modified) and the SAME/DIFFERS consistency across configurations.
    """
    table = Table(title=f'{study.master.name}  ({study.master.path})', title_justify='left')
    table.add_column('input group', style='bold')
    for name in study.configuration_names:
        table.add_column(name, justify='center')
    table.add_column('all configurations', justify='center')
    for group in study.groups:
        cells: list[Any] = [group]
        consistency = 'SAME'
        for name in study.configuration_names:
            entry = study.status_of(name, group)
            consistency = entry.consistency
            if entry.variant == NOT_USED:
                cells.append(Text('-', style='dim'))
            elif entry.state == 'MODIFIED':
                cells.append(Text(f'{entry.variant} MODIFIED', style=RED))
            else:
                cells.append(Text(f'{entry.variant} UNCHANGED', style=GREEN))
        cells.append(Text(consistency, style='yellow' if consistency == 'DIFFERS' else 'dim'))
        table.add_row(*cells)
    # the flexible-components switch of each configuration (thesis Fig. 2.3.2)
    switches = study.flexible_switches()
    cells = [Text('flexible components', style='bold')]
    for name in study.configuration_names:
        on, components = switches[name]
        label = ('on (' + ', '.join(components) + ')' if components else 'on') if on else 'off'
        cells.append(Text(label, style='cyan' if on else 'dim'))
    same = len(set(switches.values())) == 1
    cells.append(Text('SAME' if same else 'DIFFERS', style='dim' if same else 'yellow'))
    table.add_row(*cells)
    return table


def modified_table(study: Study) -> Table | None:
    rows = [(s, m) for s in study.status for m in s.modified_keys]
    if not rows:
        return None
    table = Table(title='Modified values (master file against the shared data file)',
                  title_justify='left')
    for col in ('configuration', 'group', 'key', 'data file', 'master', 'unit'):
        table.add_column(col)
    for entry, key in rows:
        table.add_row(entry.configuration, entry.group, key.key, key.data_value,
                      Text(key.master_value, style=RED), key.unit)
    return table


def print_status(study: Study, console: Console) -> None:
    console.print(status_table(study))
    modified = modified_table(study)
    if modified is not None:
        console.print(modified)
    else:
        console.print('No configuration modifies the shared data.', style=GREEN)


def configuration_json(config: Configuration) -> dict[str, Any]:
    """Return the ``vd data show --json`` contract: SI values, each with unit and source."""
    groups: dict[str, Any] = {}
    for name, group in config.groups.items():
        values: dict[str, Any] = {}
        for key, value in sorted(group.values.items()):
            entry: dict[str, Any] = {'type': value.type, 'unit': value.unit,
                                     'source': value.source}
            if value.type == 'curve':
                xs, ys = value.table()
                entry.update({'x': list(xs), 'y': list(ys), 'x_unit': value.x_unit})
            elif value.type in ('point', 'vector'):
                entry['value'] = list(value.triple())
            else:
                entry['value'] = value.si
            values[key] = entry
        groups[name] = {'kind': group.kind, 'variant': group.variant, 'file': group.file,
                        'values': values}
    return {'configuration': config.name, 'master': config.master_file,
            'description': config.description, 'data_hash': config.data_hash,
            'flexible': config.flexible, 'flexible_components': list(config.flexible_components),
            'groups': groups}


def print_configuration(config: Configuration, console: Console) -> None:
    console.print(f'[bold]{config.name}[/bold]  {config.description}  (data hash '
                  f'{config.data_hash})')
    for name, group in config.groups.items():
        table = Table(title=f'{name}  [{group.kind}, variant {group.variant}, {group.file}]',
                      title_justify='left', show_header=True)
        for col in ('key', 'value (SI)', 'unit', 'as written', 'source'):
            table.add_column(col)
        for key, value in sorted(group.values.items()):
            written = format_value(value, value.display_unit) if value.display_unit else ''
            style = RED if 'override' in value.source or '--set' in value.source else None
            table.add_row(key, Text(format_value(value, ''), style=style or ''), value.unit or '-',
                          f'{written} {value.display_unit}'.strip() if written else '',
                          value.source)
        console.print(table)


def _display(value: Value) -> tuple[str, str]:
    """(text, unit) of a value in the unit its data file was written in."""
    unit = value.display_unit or value.unit
    if value.type == 'curve':
        return format_value(value, ''), value.unit
    return format_value(value, unit), unit if value.type != 'text' else ''


def study_state(study: Study) -> dict[str, Any]:
    """
    Return the overview and group tabs of a study as plain JSON.

    What the workbench page shows and the Excel export writes: the feedback, every
    value of every group per configuration with its source, the hard points.
    """
    names = study.configuration_names
    status = study.to_json()
    modified = {(s.configuration, s.group): {m.key: m for m in s.modified_keys}
                for s in study.status}
    groups: dict[str, Any] = {}
    hardpoints: dict[str, Any] = {}
    for group in study.groups:
        users = {n: study.configurations[n].groups[group] for n in names
                 if group in study.configurations[n].groups}
        keys = sorted({k for g in users.values() for k in g.values})
        rows = []
        for key in keys:
            cells: dict[str, Any] = {}
            values = [g.values.get(key) for g in users.values()]
            for name, data in users.items():
                value = data.values.get(key)
                if value is None:
                    continue
                text, unit = _display(value)
                mod = modified[(name, group)].get(key)
                cells[name] = {'text': text, 'unit': unit, 'source': value.source,
                               'modified': mod is not None,
                               'data_value': mod.data_value if mod else text}
            first = values[0]
            differs = len(users) != len(names) or any(
                v is None or first is None or not v.same_data(first) for v in values)
            rows.append({'key': key, 'type': first.type if first else '', 'cells': cells,
                         'consistency': 'DIFFERS' if differs else 'SAME'})
        kinds = {g.kind for g in users.values()}
        groups[group] = {'kind': kinds.pop() if len(kinds) == 1 else '',
                         'files': {n: g.file for n, g in users.items()}, 'rows': rows}
        if 'hardpoints' in {g.kind for g in users.values()}:
            hardpoints[group] = {
                n: {k.split('.', 1)[1]: [1e3 * c for c in cast(tuple[float, ...], v.si)]
                    for k, v in g.values.items() if v.type == 'point'}
                for n, g in users.items()}
    configs = []
    for name in names:
        spec = study.master.configurations[name]
        config = study.configurations[name]
        overrides = []
        for key, raw in spec.overrides.items():
            group, _, rest = str(key).partition('.')
            grp = config.groups.get(group)
            unit = ''
            if grp is not None:
                base = rest[:-2] if rest not in grp.values and rest[-2:] in (
                    '.x', '.y', '.z') else rest
                if base in grp.values:
                    unit = grp.values[base].display_unit or grp.values[base].unit
            overrides.append({'key': str(key), 'value': str(raw), 'unit': unit})
        configs.append({'name': name, 'description': spec.description,
                        'flexible': config.flexible,
                        'components': list(config.flexible_components),
                        'variants': {g: study.status_of(name, g).variant for g in study.groups
                                     if study.status_of(name, g).variant != NOT_USED},
                        'overrides': overrides})
    available = {}
    root = study.master.data_root / study.master.vehicle
    for group in study.groups:
        folder = root / group
        available[group] = sorted(p.stem for p in folder.glob('*.yaml')) if folder.is_dir() \
            else []
    return {'name': study.master.name, 'description': study.master.description,
            'status': status, 'configurations': configs, 'groups': groups,
            'hardpoints': hardpoints, 'available': available}
