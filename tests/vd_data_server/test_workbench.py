# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The workbench server (vd gui) over HTTP: state, edits, live push and its security defaults.

Every refused request checks the exact message and that nothing under the data root changed.
"""
from __future__ import annotations

from collections.abc import Iterator
import http.client
import json
from pathlib import Path
from typing import Any

import pytest

from vd_data_server.errors import DataError
from vd_data_server.study import load_study
from vd_data_server.workbench.server import EDITS_OFF, Workbench, WorkbenchServer
from vdtest import line_no, replace_once, tree_snapshot

CAMBER = {'op': 'override', 'configuration': 'baseline', 'key': 'front_alignment.camber',
          'value': '-1.2 deg'}


@pytest.fixture
def server(sedan_master: Path) -> Iterator[WorkbenchServer]:
    bench = WorkbenchServer(Workbench(sedan_master, edits=True))
    bench.start()
    yield bench
    bench.stop()


def call(server: WorkbenchServer, method: str, path: str, body: Any = None,
         headers: dict[str, str] | None = None) -> tuple[int, Any]:
    conn = http.client.HTTPConnection('127.0.0.1', server.port, timeout=30)
    sent = {'Host': f'127.0.0.1:{server.port}', 'Origin': server.origin,
            'Content-Type': 'application/json', **(headers or {})}
    sent = {k: v for k, v in sent.items() if v is not None}
    data = json.dumps(body).encode() if body is not None else None
    conn.request(method, path, body=data, headers=sent)
    response = conn.getresponse()
    raw = response.read()
    conn.close()
    kind = response.getheader('Content-Type', '')
    return response.status, json.loads(raw) if kind == 'application/json' else raw.decode()


def test_the_state_carries_the_status_contract(server: WorkbenchServer,
                                               sedan_master: Path) -> None:
    status, state = call(server, 'GET', '/api/state')
    assert status == 200
    assert state['status'] == load_study(sedan_master).to_json()
    assert state['edits'] is True
    sport = next(c for c in state['configurations'] if c['name'] == 'sport')
    assert sport['overrides'][0] == {'key': 'front_alignment.camber', 'value': '-1.5 deg',
                                     'unit': 'deg'}
    rows = {r['key']: r for r in state['groups']['front_alignment']['rows']}
    assert rows['camber']['consistency'] == 'DIFFERS'
    assert rows['camber']['cells']['sport'] == {
        'text': '-1.5', 'unit': 'deg', 'source': 'master override '
        'configurations.sport.overrides.front_alignment.camber', 'modified': True,
        'data_value': '-0.5'}
    lca = state['hardpoints']['front_hardpoints']['sport']['lca_outer']
    assert lca == pytest.approx([18.4, 706.0, 171.0])
    assert state['available']['front_spring'] == ['X', 'Y']
    status, page = call(server, 'GET', '/')
    assert status == 200 and '<script src="workbench.js"' in page


def test_an_edit_lands_in_the_master_file(server: WorkbenchServer, sedan_master: Path) -> None:
    status, answer = call(server, 'POST', '/api/edit', CAMBER)
    assert (status, answer['ok'], answer['message']) == (
        200, True, 'baseline: front_alignment.camber = -1.2 deg')
    assert 'front_alignment.camber: -1.2 deg' in sedan_master.read_text()
    entry = next(s for s in answer['state']['status']['status']
                 if (s['configuration'], s['group']) == ('baseline', 'front_alignment'))
    assert entry['state'] == 'MODIFIED'


def refused(server: WorkbenchServer, root: Path, *args: Any, **kwargs: Any) -> tuple[int, str]:
    before = tree_snapshot(root)
    status, answer = call(server, *args, **kwargs)
    assert tree_snapshot(root) == before
    return status, answer['error']


def test_a_bad_value_is_refused(server: WorkbenchServer, sample_root: Path,
                                sedan_master: Path) -> None:
    assert refused(server, sample_root, 'POST', '/api/edit', {**CAMBER, 'value': '-1.2 kg'}) == (
        422, f'{sedan_master}: configurations.baseline.overrides.front_alignment.camber: unit '
        "'kg' is not an angle unit (expected e.g. 'rad')")
    assert refused(server, sample_root, 'POST', '/api/edit', {**CAMBER, 'value': 3}) == (
        400, "'value' must be a text")
    assert refused(server, sample_root, 'POST', '/api/edit', [1]) == (
        400, 'the request body must be a JSON object')


def test_a_foreign_origin_or_host_is_refused(server: WorkbenchServer,
                                             sample_root: Path) -> None:
    assert refused(server, sample_root, 'POST', '/api/edit', CAMBER,
                   headers={'Origin': 'http://evil.example'}) == (
        403, "origin 'http://evil.example' refused (edits are accepted only from "
        f'{server.origin})')
    assert refused(server, sample_root, 'POST', '/api/edit', CAMBER,
                   headers={'Origin': None}) == (
        403, f"origin 'none' refused (edits are accepted only from {server.origin})")
    assert refused(server, sample_root, 'GET', '/api/state',
                   headers={'Host': f'evil.example:{server.port}'}) == (
        403, f"host 'evil.example:{server.port}' refused (the workbench answers only as "
        f'{server.origin})')


def test_edits_are_off_by_default(sedan_master: Path, sample_root: Path) -> None:
    bench = WorkbenchServer(Workbench(sedan_master))
    bench.start()
    try:
        assert refused(bench, sample_root, 'POST', '/api/edit', CAMBER) == (403, EDITS_OFF)
        assert call(bench, 'GET', '/api/state')[1]['edits'] is False
    finally:
        bench.stop()


def test_only_files_under_the_data_root_are_served(server: WorkbenchServer,
                                                   sample_root: Path) -> None:
    root = server.workbench.data_root
    status, text = call(server, 'GET', '/api/file?path=sedan/front_spring/X.yaml')
    assert status == 200 and text.startswith('kind: spring')
    assert refused(server, sample_root, 'GET', '/api/file?path=../../etc/passwd') == (
        403, f"'../../etc/passwd' is outside the data root {root}: not read")
    assert refused(server, sample_root, 'GET', '/api/file?path=/etc/passwd') == (
        403, f"'/etc/passwd' is outside the data root {root}: not read")


def test_a_master_file_outside_its_data_root_is_refused(sample_root: Path,
                                                        tmp_path: Path) -> None:
    outside = tmp_path / 'elsewhere.yaml'
    outside.write_text((sample_root / 'studies' / 'sedan.yaml').read_text().replace(
        'data_root: ..', f'data_root: {sample_root}'))
    with pytest.raises(DataError) as info:
        Workbench(outside, edits=True)
    assert str(info.value) == (f'{outside}: is outside its data root {sample_root}: the '
                               'workbench edits only files under the data root')


def test_a_change_on_disk_is_pushed(server: WorkbenchServer, sample_root: Path) -> None:
    conn = http.client.HTTPConnection('127.0.0.1', server.port, timeout=30)
    conn.request('GET', '/api/events', headers={'Host': f'127.0.0.1:{server.port}'})
    stream = conn.getresponse()
    assert stream.getheader('Content-Type') == 'text/event-stream'

    def next_state() -> dict[str, Any]:
        lines = []
        while True:
            line = stream.fp.readline().decode()
            if line == '\n' and lines:
                break
            if line.startswith('data: '):
                lines.append(line[6:])
        return json.loads(''.join(lines))

    first = next_state()
    replace_once(sample_root / 'sedan/front_spring/X.yaml', 'rate: 30.0', 'rate: 31.0')
    pushed = next_state()
    conn.close()
    assert pushed['version'] > first['version']
    rate = next(r for r in pushed['groups']['front_spring']['rows'] if r['key'] == 'rate')
    assert rate['cells']['baseline']['text'] == '31'
    # a broken file: the last good data stays, with the loader's message
    replace_once(sample_root / 'sedan/front_spring/X.yaml', 'rate: 31.0', 'rate: -31.0')
    spring = sample_root / 'sedan/front_spring/X.yaml'
    assert server.workbench.wait_change(pushed['version'], 10.0)['errors'] == [
        f"sedan/front_spring/X.yaml: rate: must be positive, found -31.0 (line "
        f"{line_no(spring, '  rate:')})"]


def _serve_without_watching(bench: Workbench) -> WorkbenchServer:
    """Serve a workbench that reloads only when it edits: it keeps the page it read."""
    import threading

    server = WorkbenchServer(bench)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server


def test_an_edit_from_a_stale_page_is_a_conflict(sedan_master: Path, sample_root: Path) -> None:
    """Two workbenches on one master file: the second's edit is refused, not applied blind."""
    first = _serve_without_watching(Workbench(sedan_master, edits=True))
    second = _serve_without_watching(Workbench(sedan_master, edits=True))
    try:
        assert call(first, 'POST', '/api/edit', CAMBER)[0] == 200
        after_first = tree_snapshot(sample_root)
        toe = {'op': 'override', 'configuration': 'sport', 'key': 'front_alignment.toe',
               'value': '0.1 deg'}
        status, answer = call(second, 'POST', '/api/edit', toe)
        assert (status, answer) == (409, {'ok': False, 'error': (
            f'{sedan_master}: changed on disk since it was read (another workbench, vd command '
            'or editor wrote it): this edit is not written; look at the file as it is now and '
            'edit again')})
        assert tree_snapshot(sample_root) == after_first
        status, answer = call(second, 'POST', '/api/edit', toe)  # now from the file as it is
        assert status == 200
        text = sedan_master.read_text()
        assert 'front_alignment.camber: -1.2 deg' in text
        assert 'front_alignment.toe: 0.1 deg' in text
    finally:
        for server in (first, second):
            server.stop()


def test_concurrent_workbenches_lose_no_acknowledged_edit(sedan_master: Path) -> None:
    """Each edit is answered 200 and kept, or 409 and not written: none vanishes."""
    from concurrent.futures import ThreadPoolExecutor

    from vd_data_server.errors import WorkbenchError

    benches = [Workbench(sedan_master, edits=True) for _ in range(2)]

    def add(n: int) -> str | None:
        bench = benches[n % 2]
        name = f'copy_{n}'
        try:
            bench.edit({'op': 'add', 'configuration': name, 'source': 'baseline'})
        except WorkbenchError as err:
            assert err.status == 409
            return None
        return name

    with ThreadPoolExecutor(max_workers=6) as pool:
        acknowledged = [n for n in pool.map(add, range(18)) if n]
    assert acknowledged  # the first edit of each workbench meets the file it read
    kept = set(load_study(sedan_master).configuration_names)
    assert set(acknowledged) <= kept
    assert {n for n in kept if n.startswith('copy_')} == set(acknowledged)


def test_nul_characters_and_nested_lists_are_bad_requests(server: WorkbenchServer,
                                                          sample_root: Path) -> None:
    assert refused(server, sample_root, 'GET', '/api/file?path=sedan/%00') == (
        400, 'a file name holds no NUL character')
    assert refused(server, sample_root, 'POST', '/api/edit', {**CAMBER, 'value': '1\x00 deg'}) \
        == (400, "'value' holds a NUL character")
    assert refused(server, sample_root, 'POST', '/api/edit', {**CAMBER, 'value': [[1]]}) == (
        400, "'value' must be a text")
    runs = WorkbenchServer(Workbench(server.workbench.master_file, runner=lambda names: {}))
    runs.start()
    try:
        assert refused(runs, sample_root, 'POST', '/api/run',
                       {'configurations': [['baseline']]}) == (
            400, "'configurations' must be a list of configuration names (texts)")
    finally:
        runs.stop()


def test_a_deeply_nested_body_is_a_bad_request(server: WorkbenchServer,
                                               sample_root: Path) -> None:
    before = tree_snapshot(sample_root)
    conn = http.client.HTTPConnection('127.0.0.1', server.port, timeout=30)
    body = b'[' * 30000 + b']' * 30000
    conn.request('POST', '/api/edit', body=body, headers={
        'Host': f'127.0.0.1:{server.port}', 'Origin': server.origin,
        'Content-Length': str(len(body))})
    response = conn.getresponse()
    answer = json.loads(response.read())
    conn.close()
    assert (response.status, answer['error']) == (400, 'the request body is nested too deeply')
    assert tree_snapshot(sample_root) == before


def test_an_absolute_url_for_another_host_is_refused(server: WorkbenchServer,
                                                     sample_root: Path) -> None:
    assert refused(server, sample_root, 'GET', 'http://evil.example/api/state') == (
        403, f"request for 'evil.example' refused (the workbench answers only as "
        f'{server.origin})')
    status, state = call(server, 'GET', f'http://127.0.0.1:{server.port}/api/state')
    assert status == 200 and state['edits'] is True


def test_a_stalled_request_body_releases_its_connection(server: WorkbenchServer,
                                                        monkeypatch) -> None:
    """A client that sends half a body and stops is dropped after the idle timeout."""
    import socket

    from vd_data_server.workbench import server as module

    monkeypatch.setattr(module._Handler, 'timeout', 0.5)
    with socket.create_connection(('127.0.0.1', server.port)) as sock:
        sock.sendall(f'POST /api/edit HTTP/1.1\r\nHost: 127.0.0.1:{server.port}\r\n'
                     f'Origin: {server.origin}\r\nContent-Length: 100\r\n\r\n{{"op"'.encode())
        sock.settimeout(60)  # a guard against a hang only: the server closes within 0.5 s
        assert sock.recv(1024) == b''  # closed by the server, no answer
    assert call(server, 'GET', '/api/state')[0] == 200


def test_validation_copies_left_by_a_killed_editor_are_removed(server: WorkbenchServer,
                                                               sedan_master: Path) -> None:
    stale = sedan_master.with_name(f'.{sedan_master.name}.k1ll3d.check')
    stale.write_text('left by kill -9 during an edit')
    assert call(server, 'POST', '/api/edit', CAMBER)[0] == 200
    assert not stale.exists()
    assert not list(sedan_master.parent.glob('.*.check'))
