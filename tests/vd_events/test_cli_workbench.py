# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""`vd gui`, `vd export xlsx`, `vd import xlsx` and "Update marked": exit codes and messages."""
from __future__ import annotations

import http.client
import json
from pathlib import Path
import time

import pytest

from vd_data_server.master import load_master
from vd_events.cli.main import main
from vdtest import tree_snapshot


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def test_export_and_import_from_the_command_line(capsys: pytest.CaptureFixture[str],
                                                 sample_root: Path, sedan_master: Path,
                                                 tmp_path: Path) -> None:
    book = tmp_path / 'sedan.xlsx'
    assert run(capsys, 'export', 'xlsx', '--master', str(sedan_master), '--out', str(book)) == (
        0, f'{book}\n', '')
    target = sample_root / 'studies' / 'sedan_copy.yaml'
    assert run(capsys, 'import', 'xlsx', str(book), '--out', str(target)) == (
        0, f'{target}: written from {book}\n', '')
    assert load_master(target).configurations == load_master(sedan_master).configurations


def test_bad_input_exits_2_and_writes_nothing(capsys: pytest.CaptureFixture[str],
                                              sample_root: Path, sedan_master: Path,
                                              tmp_path: Path) -> None:
    before = tree_snapshot(sample_root)
    assert run(capsys, 'export', 'xlsx', '--master', str(sedan_master), '--out',
               str(tmp_path / 'sedan.csv')) == (
        2, '', f"{tmp_path / 'sedan.csv'}: the workbook must end in .xlsx, found 'sedan.csv'\n")
    missing = tmp_path / 'none.xlsx'
    assert run(capsys, 'import', 'xlsx', str(missing), '--out',
               str(sample_root / 'studies' / 'x.yaml')) == (2, '', f'{missing}: file not found\n')
    assert run(capsys, 'gui', '--master', str(sedan_master), '--port', '70000') == (
        2, '', '--port must be 0..65535, found 70000\n')
    assert tree_snapshot(sample_root) == before
    assert list(tmp_path.iterdir()) == [sample_root.parent / 'data']


@pytest.mark.ros
@pytest.mark.slow
def test_update_marked_runs_the_events_and_shows_the_metrics(sedan_master: Path) -> None:
    from vd_data_server.workbench.server import Workbench, WorkbenchServer
    from vd_events.cli.workbench import marked_runner

    server = WorkbenchServer(Workbench(sedan_master, runner=marked_runner(sedan_master)))
    server.start()
    try:
        conn = http.client.HTTPConnection('127.0.0.1', server.port, timeout=30)
        body = json.dumps({'configurations': ['stiff_rear']})
        conn.request('POST', '/api/run', body=body, headers={
            'Host': f'127.0.0.1:{server.port}', 'Origin': server.origin,
            'Content-Type': 'application/json'})
        answer = json.loads(conn.getresponse().read())
        conn.close()
        assert answer['message'] == 'running the events of stiff_rear'
        assert answer['state']['runs'] == {
            'stiff_rear': {'status': 'running', 'metrics': [], 'error': ''}}
        deadline = time.monotonic() + 600
        state = answer['state']
        while state['running'] and time.monotonic() < deadline:
            state = server.workbench.wait_change(state['version'], 5.0) or state
        run_ = state['runs']['stiff_rear']
        assert (run_['status'], run_['error']) == ('done', '')
        metrics = {(m['event'], m['label']): m for m in run_['metrics']}
        kus = metrics[('steady_state_circular', 'understeer_gradient')]  # shown in deg/g
        assert kus['unit'] == 'deg/g' and 0.5 < kus['value'] < 5.0
        assert kus['text'] == f"{kus['value']:.4g} deg/g"
        assert ('handling_diagram', 'max_lateral_acceleration') in metrics
    finally:
        server.stop()
