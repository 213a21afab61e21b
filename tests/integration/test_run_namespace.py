# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``vd run --namespace``: the run's graph lives in the namespace, its bag says so."""
from __future__ import annotations

import json

import pytest

from vdtest import tree_snapshot

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def _vd(capsys, *argv: str) -> tuple[int, str, str]:
    from vd_events.cli.main import main

    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


@pytest.mark.parametrize('distributed', [False, True])
def test_run_in_a_namespace_records_the_namespaced_topics(capsys, tmp_path, sedan_master,
                                                          distributed):
    from vd_events.bags.bag import read_bag

    bag = tmp_path / 'bag'
    rc, out, err = _vd(capsys, 'run', 'lateral_force', '--model', 'kc', '--axle', 'front',
                       '--master', str(sedan_master), '--param', 'steps=5', '--bag', str(bag),
                       '--namespace', 'car2', '--json',
                       *(['--distributed'] if distributed else []))
    assert rc == 0, err
    result = json.loads(out)
    assert set(result['timings']) >= {'load_and_validate', 'command'}
    topics = [m.topic for m in read_bag(bag)]
    assert topics.count('/car2/kc/result') == 1
    assert topics.count('/car2/kc/state') == 5
    assert topics.count('/car2/configuration') == 1
    assert not [t for t in topics if t.startswith('/vd/')]


def test_invalid_namespace_is_refused_before_anything_runs(capsys, tmp_path, sedan_master):
    before = tree_snapshot(tmp_path)
    rc, out, err = _vd(capsys, 'run', 'lateral_force', '--model', 'kc', '--axle', 'front',
                       '--master', str(sedan_master), '--bag', str(tmp_path / 'bag'),
                       '--namespace', '/car 2', '--json')
    assert rc == 2
    assert json.loads(out) == {'error': "--namespace: '/car 2' is not a valid ROS namespace "
                               "(tokens of letters, digits and '_', not starting with a "
                               "digit, separated by '/', e.g. '/car2')"}
    assert tree_snapshot(tmp_path) == before
