# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Human-readable views of a study: the thesis' overview tab as a coloured table."""
from __future__ import annotations

from typing import Any

from rich.console import Console
from rich.table import Table
from rich.text import Text

from .model import Configuration
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
