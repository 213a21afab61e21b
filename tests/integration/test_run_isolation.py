# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Runs never share a ROS domain silently, and every result is matched to its request.

Long goals are not mistaken for lost ones either (issue 10, causes 2 and 5).
"""
from __future__ import annotations

import dataclasses
import json
import time

import pytest

from vdtest import HANG_GUARD, tree_snapshot

pytestmark = [pytest.mark.ros, pytest.mark.slow]


def _vd(capsys, *argv: str) -> tuple[int, str, str]:
    from vd_events.cli.main import main

    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def test_a_run_does_not_start_on_a_domain_another_run_holds(capsys, monkeypatch, tmp_path,
                                                            sedan_master):
    """A run through the graph (``--distributed``; an in-process run has no ROS domain)."""
    from vd_events.orchestration.domain import claim_domain

    held = claim_domain()  # what a live run holds for its whole life
    try:
        monkeypatch.setenv('VD_DOMAIN_ID', str(held.domain))
        bag = tmp_path / 'bag'
        before = tree_snapshot(sedan_master.parents[1])
        rc, out, err = _vd(capsys, 'run', 'handling_diagram', '--master', str(sedan_master),
                           '--bag', str(bag), '--distributed')
        assert (rc, out) == (2, '')
        assert err.strip() == (f"VD_DOMAIN_ID: ROS domain {held.domain} is in use by another "
                               f"vd run or vd launch (pid {__import__('os').getpid()}); unset "
                               "VD_DOMAIN_ID or choose another")
        assert not list(tmp_path.glob('bag*'))
        assert tree_snapshot(sedan_master.parents[1]) == before
    finally:
        held.release()


@pytest.mark.parametrize('way', ['graph', 'inprocess'])
def test_a_result_of_other_data_is_refused_and_leaves_no_bag(tmp_path, sedan_master, way):
    """
    Answer as another study on the same domain would.

    The configuration of the same name, computed from other data (its data hash differs).
    """
    from vd_data_server.study import load_study
    from vd_events.orchestration.inprocess import run_inprocess
    from vd_events.orchestration.requests import RunRequest, validate
    from vd_events.orchestration.runner import run_embedded

    bag = tmp_path / 'bag'
    request = validate(load_study(sedan_master), RunRequest(
        event='handling_diagram', configuration='baseline', model='two_track',
        parameters=('steps=5',), bag=bag))
    other = dataclasses.replace(request, data_hash='0123456789abcdef')
    (outcome,) = (run_embedded if way == 'graph' else run_inprocess)(sedan_master, [other])
    assert outcome.outcome is None and outcome.bag is None
    assert outcome.error == (
        "configuration 'baseline', event 'handling_diagram', model 'two_track': the result was "
        f"computed from other data (data hash {request.data_hash}, expected 0123456789abcdef) "
        "- another study answered on this ROS domain; not used")
    assert not list(tmp_path.glob('bag*'))


def test_check_result_refuses_an_answer_to_another_request():
    from vd_events.errors import RunError
    from vd_events.orchestration.runner import RunRequest, check_result
    from vd_interfaces.msg import EventResult

    request = RunRequest(event='handling_diagram', configuration='baseline', model='two_track',
                         data_hash='aaaa')
    check_result(request, EventResult(event='handling_diagram', configuration='baseline',
                                      model='two_track', data_hash='aaaa'))
    with pytest.raises(RunError) as info:
        check_result(request, EventResult(event='handling_diagram', configuration='sport',
                                          model='two_track', data_hash='aaaa'))
    assert str(info.value) == (
        "configuration 'baseline', event 'handling_diagram', model 'two_track': the result is "
        "for configuration 'sport', event 'handling_diagram', model 'two_track' - another run "
        "answered; not used")


def test_embedded_goal_longer_than_the_accept_timeout(monkeypatch, tmp_path, sedan_master):
    """
    The accept wait and the solver's execute callback no longer share one thread.

    A goal that takes several accept timeouts is accepted once and finishes.
    """
    from vd_data_server.study import load_study
    from vd_events.orchestration import runner
    import vd_solvers.analytical.events as analytical_events

    monkeypatch.setattr(runner, 'ACCEPT_TIMEOUT', 0.3)
    calls = []
    real = analytical_events.run_event

    def slow(*args, **kwargs):
        calls.append(time.monotonic())
        time.sleep(4 * runner.ACCEPT_TIMEOUT)
        return real(*args, **kwargs)

    monkeypatch.setattr(analytical_events, 'run_event', slow)
    request = runner.validate(load_study(sedan_master), runner.RunRequest(
        event='handling_diagram', configuration='baseline', model='two_track',
        parameters=('steps=5',), bag=tmp_path / 'bag'))
    t0 = time.monotonic()
    (outcome,) = runner.run_embedded(sedan_master, [request])
    assert outcome.error is None, outcome.error
    assert len(calls) == 1  # accepted at the first attempt, never sent again
    assert time.monotonic() - t0 > 4 * runner.ACCEPT_TIMEOUT
    assert outcome.outcome.data_hash == request.data_hash
    assert (tmp_path / 'bag' / 'metadata.yaml').is_file()


def test_two_embedded_runs_at_once_get_their_own_results(tmp_path, sedan_master, sample_root):
    """
    Two studies whose configurations share a name, run at the same moment.

    Each gets the wheel rate of its own data.
    """
    import subprocess
    import sys

    from vdtest import replace_once

    other_root = tmp_path / 'other'
    import shutil

    shutil.copytree(sample_root, other_root)
    replace_once(other_root / 'sedan/front_spring/X.yaml', 'rate: 30.0', 'rate: 45.0')
    argv = ['run', 'parallel_wheel_travel', '--axle', 'front', '--param', 'steps=5', '--json']
    procs = [subprocess.Popen([sys.executable, '-m', 'vd_events.cli.main', *argv, '--master',
                               str(root / 'studies' / 'sedan.yaml')], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
             for root in (sample_root, other_root)]
    results = []
    for proc in procs:
        out, err = proc.communicate(timeout=HANG_GUARD)
        assert proc.returncode == 0, err
        results.append(json.loads(out))
    rates = [r['metrics']['wheel_rate']['value'] for r in results]
    assert rates[1] > rates[0] * 1.2
    assert results[0]['data_hash'] != results[1]['data_hash']


def test_a_full_disk_while_recording_is_an_error_and_leaves_no_bag(capsys, monkeypatch, tmp_path,
                                                                   sedan_master):
    import errno

    from vd_events.bags import bag as bag_module

    def full(self, topic, msg, timestamp_ns, qos=()):
        raise OSError(errno.ENOSPC, 'No space left on device')

    monkeypatch.setattr(bag_module.BagWriter, 'write', full)
    bag = tmp_path / 'bag'
    before = tree_snapshot(sedan_master.parents[1])
    rc, out, err = _vd(capsys, 'run', 'handling_diagram', '--master', str(sedan_master),
                       '--param', 'steps=5', '--bag', str(bag))
    assert (rc, out) == (2, '')
    assert err.strip() == ("configuration 'baseline', event 'handling_diagram', model "
                           f"'two_track': {bag}: cannot write the bag: No space left on device")
    assert not list(tmp_path.glob('bag*'))
    assert tree_snapshot(sedan_master.parents[1]) == before
