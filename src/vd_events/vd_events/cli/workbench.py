# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd gui``, ``vd export xlsx`` and ``vd import xlsx``: the master-file workbench."""
from __future__ import annotations

import argparse
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from vd_data_server.errors import DataError
from vd_data_server.masteredit import load_document
from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_data_server.workbench.server import serve
from vd_data_server.xlsx import export_workbook, import_workbook
from vd_data_server.yamlio import read_bytes
from vd_events.errors import RunError
from vd_events.orchestration.inprocess import run_inprocess
from vd_events.orchestration.requests import RunRequest, validate
from vd_events.reports.display import HEADLINE_NAMES, display

#: the events "Update marked" runs for each marked configuration: (event, model)
MARKED_EVENTS = (('steady_state_circular', 'bicycle'), ('handling_diagram', 'two_track'))
#: how many headline metrics of each run the page shows
HEADLINE_COUNT = 4


def _master(path: str | None) -> Path:

    return Path(path) if path else default_master()


def marked_runner(master: Path) -> Callable[[Sequence[str]], Mapping[str, Any]]:
    """Run :data:`MARKED_EVENTS` for configurations through the ordinary runner."""
    def run(names: Sequence[str]) -> Mapping[str, Any]:

        study = load_study(master)
        requests = []
        for name in names:
            for event, model in MARKED_EVENTS:
                try:
                    requests.append(validate(study, RunRequest(event=event, configuration=name,
                                                               model=model)))
                except RunError as err:
                    raise DataError(str(err)) from None
        results: dict[str, Any] = {n: {'status': 'done', 'metrics': [], 'error': ''}
                                   for n in names}
        for result in run_inprocess(master, requests, study=study):
            entry = results[result.request.configuration]
            if result.error or result.outcome is None:
                entry['status'] = 'failed'
                entry['error'] = result.error or 'no result'
                continue
            metrics = result.outcome.metrics
            for key in [m for m in HEADLINE_NAMES if m in metrics][:HEADLINE_COUNT]:
                metric = metrics[key]
                value, unit = display(metric.value, metric.unit, key)  # SI -> display
                entry['metrics'].append({'event': result.request.event,
                                         'model': result.request.model, 'label': key,
                                         'value': value, 'unit': unit,
                                         'text': _text(value, unit)})
        return results
    return run


def _text(value: float, unit: str) -> str:
    """Format a metric for the page in its display unit."""
    return f'{value:.4g} {unit}' if unit not in ('', '-') else f'{value:.4g}'


def cmd_gui(args: argparse.Namespace) -> int:

    master = _master(args.master)
    if not 0 <= args.port <= 65535:
        raise DataError(f'--port must be 0..65535, found {args.port}')
    if args.screenshots:
        from vd_data_server.workbench.browser import save_screenshots

        for path in save_screenshots(master, Path(args.screenshots), edits=args.edits):
            print(path)
        return 0
    serve(master, port=args.port, edits=args.edits, runner=marked_runner(master))
    return 0


def cmd_export(args: argparse.Namespace) -> int:

    master = _master(args.master)
    study = load_study(master)
    raw = load_document(read_bytes(master, display=str(master)).decode('utf-8'),
                        file=str(master))
    out = Path(args.out) if args.out else Path('out') / f'{master.stem}.xlsx'
    if out.suffix.lower() != '.xlsx':
        raise DataError(f"the workbook must end in .xlsx, found '{out.name}'", file=str(out))
    print(export_workbook(study, raw, out))
    return 0


def import_xlsx(workbook: Path, out: Path) -> int:
    """``vd import xlsx WORKBOOK --out MASTER``: a master workbook into a master file."""
    import_workbook(workbook, out)
    print(f'{out}: written from {workbook}')
    return 0
