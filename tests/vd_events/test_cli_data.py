# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""`vd data status|show|check`: exit codes, 'file: key: message' errors, --json contracts."""
from __future__ import annotations

import json
import math
from pathlib import Path

from numpy.testing import assert_allclose
import pytest

from vd_data_server.study import load_study
from vd_events.cli.main import main
from vdtest import line_no, replace_once, tree_snapshot

RTOL = 1e-12


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


@pytest.fixture
def broken_sedan(sample_root: Path, sedan_master: Path) -> list[str]:
    """Break two data files of the sedan; return the error lines `vd data check` must print."""
    front = sample_root / 'sedan/front_spring/X.yaml'
    rear = sample_root / 'sedan/rear_alignment/X.yaml'
    replace_once(front, 'rate: 30.0', 'rate: -30.0')
    replace_once(rear, '  toe: 0.15\n', '')
    return [f"sedan/front_spring/X.yaml: rate: must be positive, found -30.0 "
            f"(line {line_no(front, '  rate:')})",
            f"sedan/rear_alignment/X.yaml: toe: missing required key "
            f"(line {line_no(rear, 'data:')})"]


@pytest.mark.parametrize(('study', 'configurations', 'files'), [
    # sedan: 22 default variants + front_spring Y, front_bushings Y, rear_stabilizer Y,
    # targets stiff_rear; hmmwv: 18 defaults + the front_bushings of one configuration
    ('sedan', 3, 28),  # incl. front_flex and rear_flex
    ('hmmwv', 2, 21),
])
def test_check_accepts_the_sample_studies(capsys: pytest.CaptureFixture[str], sample_root: Path,
                                          study: str, configurations: int, files: int) -> None:
    master = sample_root / 'studies' / f'{study}.yaml'
    before = tree_snapshot(sample_root)
    rc, out, err = run(capsys, 'data', 'check', '--master', str(master))
    assert (rc, err) == (0, '')
    assert out == f'{master}: OK ({configurations} configurations, {files} data files)\n'
    assert tree_snapshot(sample_root) == before


def test_check_reports_every_problem_and_exits_2(capsys: pytest.CaptureFixture[str],
                                                 sample_root: Path, sedan_master: Path,
                                                 broken_sedan: list[str]) -> None:
    before = tree_snapshot(sample_root)
    rc, out, err = run(capsys, 'data', 'check', '--master', str(sedan_master))
    assert (rc, out) == (2, '')
    assert err.splitlines() == broken_sedan
    assert 'Traceback' not in err
    assert tree_snapshot(sample_root) == before


def test_check_json_error_shape(capsys: pytest.CaptureFixture[str], sample_root: Path,
                                sedan_master: Path, broken_sedan: list[str]) -> None:
    before = tree_snapshot(sample_root)
    rc, out, err = run(capsys, 'data', 'check', '--master', str(sedan_master), '--json')
    assert (rc, err) == (2, '')
    assert json.loads(out) == {'error': '\n'.join(broken_sedan)}
    assert tree_snapshot(sample_root) == before


def test_check_json_success_shape(capsys: pytest.CaptureFixture[str], sedan_master: Path) -> None:
    rc, out, _ = run(capsys, 'data', 'check', '--master', str(sedan_master), '--json')
    assert rc == 0
    assert json.loads(out) == {'ok': True, 'message': f'{sedan_master}: OK (3 configurations, '
                                                      '28 data files)'}


def test_missing_master_file_exits_2(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    missing = tmp_path / 'none.yaml'
    rc, out, err = run(capsys, 'data', 'status', '--master', str(missing))
    assert (rc, out, err) == (2, '', f'{missing}: file not found\n')
    assert list(tmp_path.iterdir()) == []


def test_status_json_matches_the_study(capsys: pytest.CaptureFixture[str],
                                       sedan_master: Path) -> None:
    rc, out, err = run(capsys, 'data', 'status', '--master', str(sedan_master), '--json')
    assert (rc, err) == (0, '')
    data = json.loads(out)
    assert data == load_study(sedan_master).to_json()
    sport = {e['group']: e for e in data['status'] if e['configuration'] == 'sport'}
    assert sport['front_alignment']['modified_keys'] == [
        {'key': 'camber', 'data_value': '-0.5', 'master_value': '-1.5', 'unit': 'deg'}]


def test_status_table_shows_modified_values(capsys: pytest.CaptureFixture[str],
                                            sedan_master: Path) -> None:
    rc, out, err = run(capsys, 'data', 'status', '--master', str(sedan_master))
    assert (rc, err) == (0, '')
    assert 'MODIFIED' in out and 'UNCHANGED' in out and 'DIFFERS' in out
    assert 'camber' in out


def test_show_json_gives_the_override_in_si(capsys: pytest.CaptureFixture[str],
                                            sedan_master: Path) -> None:
    rc, out, err = run(capsys, 'data', 'show', 'sport', '--master', str(sedan_master), '--json')
    assert (rc, err) == (0, '')
    camber = json.loads(out)['groups']['front_alignment']['values']['camber']
    assert_allclose(camber['value'], math.radians(-1.5), rtol=RTOL)
    assert camber['unit'] == 'rad'
    assert camber['source'] == ('master override '
                                'configurations.sport.overrides.front_alignment.camber')


def test_show_json_gives_every_value_a_unit_and_a_source(capsys: pytest.CaptureFixture[str],
                                                         sedan_master: Path) -> None:
    rc, out, _ = run(capsys, 'data', 'show', 'baseline', '--master', str(sedan_master), '--json')
    assert rc == 0
    data = json.loads(out)
    assert data['configuration'] == 'baseline'
    assert data['data_hash'] == load_study(sedan_master).configurations['baseline'].data_hash
    entries = [(g, k, e) for g, group in data['groups'].items()
               for k, e in group['values'].items()]
    assert entries
    for group, key, entry in entries:
        assert 'unit' in entry and entry['source'], (group, key)
        if entry['type'] == 'curve':
            assert len(entry['x']) == len(entry['y']) and 'x_unit' in entry, (group, key)
        else:
            assert 'value' in entry, (group, key)
    rate = data['groups']['front_spring']['values']['rate']
    assert (rate['unit'], rate['source']) == ('N/m', 'sedan/front_spring/X.yaml (variant X)')
    assert_allclose(rate['value'], 30.0e3, rtol=RTOL)  # front_spring/X.yaml: 30.0 N/mm


def test_show_unknown_configuration_exits_2(capsys: pytest.CaptureFixture[str],
                                            sedan_master: Path) -> None:
    rc, out, err = run(capsys, 'data', 'show', 'rally', '--master', str(sedan_master))
    assert (rc, out) == (2, '')
    assert err == (f"{sedan_master}: configuration 'rally' does not exist (available: baseline, "
                   "stiff_rear, sport)\n")


def test_show_unknown_configuration_json_error(capsys: pytest.CaptureFixture[str],
                                               sedan_master: Path) -> None:
    rc, out, err = run(capsys, 'data', 'show', 'rally', '--master', str(sedan_master), '--json')
    assert (rc, err) == (2, '')
    assert json.loads(out) == {'error': f"{sedan_master}: configuration 'rally' does not exist "
                                        "(available: baseline, stiff_rear, sport)"}
