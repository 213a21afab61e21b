# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd capability``: rigid vs flexible K&C per event and quantity (thesis Tables 5.2.x)."""
from __future__ import annotations

import argparse
import json
import os
from pathlib import Path

from rich.table import Table as RichTable

from vd_data_server.errors import DataError
from vd_data_server.files import numbered_folder
from vd_data_server.overview import console
from vd_events.cli import options
from vd_events.studies.capability import QUANTITIES, run_study


def cmd_capability(args: argparse.Namespace) -> int:
    master, study = options.study(args.master)
    name = args.config or study.configuration_names[0]
    if name not in study.configurations:
        raise DataError(f"configuration '{name}' does not exist (available: "
                        f"{', '.join(study.configuration_names)})", file=str(master))
    if args.axle not in ('', 'front', 'rear'):
        raise DataError(f"--axle must be front or rear, found '{args.axle}'")
    axles = [args.axle] if args.axle else ['front', 'rear']
    steps = [p for p in args.parameters if p.partition('=')[0].strip() == 'steps']
    if len(steps) != len(args.parameters):
        raise DataError("vd capability takes only the parameter 'steps' (every event has it)")
    # the default: a new numbered folder per run, so a second run never meets the first's
    out = Path(args.out) if args.out else numbered_folder(Path('out') / 'capability' / name)
    progress = options.progress_bar(args)
    try:
        tables = options.with_progress(progress, lambda: run_study(
            master, study, name, axles, out, args.parameters, progress=progress))
    except BaseException:
        if not args.out and not any(out.iterdir()):
            os.removedirs(out)  # the folders this run made, left empty: nothing written
        raise
    if args.json:
        print(json.dumps({'configuration': name, 'out': str(out),
                          'tables': [t.to_json() for t in tables]}))
        return 0
    # the report's sections import the measured-data stack (scipy.signal, scipy.stats):
    # only the table printed needs them, not --json
    from vd_events.reports.sections import capability_rows

    term = console()
    for t in tables:
        table = RichTable(title=f"capability - {t.configuration} - {t.axle} axle "
                          f"(flexible: {', '.join(t.components)})", title_justify='left')
        table.add_column('event')
        for q in QUANTITIES:
            table.add_column(q)
        for row in capability_rows(t):
            table.add_row(*[c if i == 0 else (f'[red]{c}[/red]' if c.startswith('Flexible')
                                              else f'[green]{c}[/green]')
                            for i, c in enumerate(row)])
        term.print(table)
        for note in t.notes:
            term.print(note)
    term.print(f'bag (both runs of every event and the tables): {out}/capability_{name}')
    return 0


__all__ = ['cmd_capability']
