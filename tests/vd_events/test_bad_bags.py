# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd compare`` and ``vd replay`` on bags that cannot be read whole.

A truncated ``.mcap`` and a broken ``metadata.yaml`` give one clean message naming the
bag, exit code 2 and no output folder (issue 28, defect 4).
"""
from __future__ import annotations

from pathlib import Path
import shutil

import pytest

from vd_events.cli.main import main
from vdtest import tree_snapshot

pytestmark = pytest.mark.ros


@pytest.fixture(scope='module')
def sim_bag(tmp_path_factory) -> Path:
    from vd_data_server.paths import default_master
    from vd_data_server.study import load_study
    from vd_events.bags.outcomes import write_outcomes
    from vd_solvers.kc.from_config import run_kc_event

    baseline = load_study(default_master()).configurations['baseline']
    outcome = run_kc_event(baseline, 'parallel_wheel_travel', 'front', ['steps=11'])
    bag = tmp_path_factory.mktemp('sim') / 'sim_bounce'
    return write_outcomes(bag, [(outcome, 1_700_000_000_000_000_000)], {'vd.kind': 'test'})


def _copy(sim_bag: Path, tmp_path: Path) -> Path:
    bag = tmp_path / 'broken'
    shutil.copytree(sim_bag, bag)
    return bag


def _truncate(bag: Path) -> None:
    (mcap,) = bag.glob('*.mcap')
    data = mcap.read_bytes()
    mcap.write_bytes(data[:len(data) // 2])


def _refused(capsys, tmp_path: Path, argv: list[str]) -> str:
    before = tree_snapshot(tmp_path)
    rc = main(argv)
    out, err = capsys.readouterr()
    assert (rc, out) == (2, '')
    assert tree_snapshot(tmp_path) == before
    assert not (tmp_path / 'out').exists()
    return err.strip()


@pytest.mark.parametrize('command', ['compare', 'replay'])
def test_truncated_mcap_is_a_bag_error(capsys, sim_bag: Path, tmp_path: Path,
                                       command: str) -> None:
    bag = _copy(sim_bag, tmp_path)
    _truncate(bag)
    argv = (['compare', str(sim_bag), str(bag)] if command == 'compare'
            else ['replay', str(bag), '--models', 'bicycle'])
    err = _refused(capsys, tmp_path, [*argv, '--out', str(tmp_path / 'out')])
    assert err.startswith(f'{bag}: not a readable rosbag2 bag (')


@pytest.mark.parametrize(('metadata', 'reason'), [
    ('rosbag2_bagfile_information: [', 'broken metadata.yaml (malformed YAML: '),
    ('other: 1\n', 'broken metadata.yaml (no rosbag2_bagfile_information with its '
                   'topics_with_message_count)'),
    ('rosbag2_bagfile_information:\n  topics_with_message_count: [1]\n',
     'broken metadata.yaml (no rosbag2_bagfile_information with its '
     'topics_with_message_count)'),
])
@pytest.mark.parametrize('command', ['compare', 'replay'])
def test_broken_metadata_is_a_bag_error(capsys, sim_bag: Path, tmp_path: Path, command: str,
                                        metadata: str, reason: str) -> None:
    bag = _copy(sim_bag, tmp_path)
    (bag / 'metadata.yaml').write_text(metadata)
    argv = (['compare', str(sim_bag), str(bag)] if command == 'compare'
            else ['replay', str(bag), '--models', 'bicycle'])
    err = _refused(capsys, tmp_path, [*argv, '--out', str(tmp_path / 'out')])
    assert err.startswith(f'{bag}: {reason}')
