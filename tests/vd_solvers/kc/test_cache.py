# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""K&C results on demand, cached by data hash (vd_solvers.kc.cache)."""
from __future__ import annotations

import numpy as np
import pytest

from vd_data_server.master import parse_set, with_overrides
from vd_data_server.study import load_study
from vd_solvers.errors import SolverError
from vd_solvers.kc import cache, from_config
from vd_solvers.kc.events import KCModel
from vd_solvers.kc.from_config import suspension_input


@pytest.fixture
def baseline(sedan_master, tmp_path, monkeypatch):
    cache.clear()
    monkeypatch.setenv('XDG_CACHE_HOME', str(tmp_path / 'cache'))  # never the user's cache
    return load_study(sedan_master).configurations['baseline']


def _no_solving(*args, **kwargs):
    raise AssertionError('solved again')


def test_a_new_process_reads_the_result_from_the_disk(baseline, monkeypatch):
    first = cache.kc_result(baseline, 'front', 'parallel_wheel_travel', steps=11)
    direct = KCModel(suspension_input(baseline, 'front')).run('parallel_wheel_travel', steps=11)
    cache.clear()  # what a new process holds
    monkeypatch.setattr(cache, 'kc_model', _no_solving)
    again = cache.kc_result(baseline, 'front', 'parallel_wheel_travel', steps=11)
    assert again is not first
    assert again.channels.keys() == direct.channels.keys()
    for name, values in direct.channels.items():
        np.testing.assert_array_equal(again.channels[name], values)  # to the last bit
    assert again.params == direct.params


def test_other_data_or_other_code_is_solved_again(baseline, monkeypatch):
    cache.kc_result(baseline, 'front', 'parallel_wheel_travel', steps=11)
    cache.clear()
    solved = []
    real = cache.kc_model
    monkeypatch.setattr(cache, 'kc_model', lambda *a, **k: solved.append(a) or real(*a, **k))
    cambered = with_overrides(baseline, parse_set(['front_alignment.camber=-2 deg']))
    cache.kc_result(cambered, 'front', 'parallel_wheel_travel', steps=11)
    assert len(solved) == 1
    cache.clear()
    cache.kc_result(baseline, 'front', 'parallel_wheel_travel', steps=12)  # other parameters
    assert len(solved) == 2
    cache.clear()
    monkeypatch.setattr(cache, '_code', lambda: 'the sources after an edit')
    cache.kc_result(baseline, 'front', 'parallel_wheel_travel', steps=11)
    assert len(solved) == 3


def test_result_equals_a_direct_run_and_is_reused(baseline):
    first = cache.kc_result(baseline, 'front', 'parallel_wheel_travel', steps=11)
    direct = KCModel(suspension_input(baseline, 'front')).run('parallel_wheel_travel', steps=11)
    np.testing.assert_array_equal(first.channels['toe'], direct.channels['toe'])
    assert cache.kc_result(baseline, 'front', 'parallel_wheel_travel', steps=11) is first


def test_changed_data_is_a_new_entry(baseline):
    first = cache.kc_result(baseline, 'front', 'parallel_wheel_travel', steps=11)
    cambered = with_overrides(baseline, parse_set(['front_alignment.camber=-2 deg']))
    assert cambered.data_hash != baseline.data_hash
    second = cache.kc_result(cambered, 'front', 'parallel_wheel_travel', steps=11)
    assert second is not first
    at = 5  # design step of an 11-step symmetric sweep
    # bushings deflect under the corner load, so compare the change with the override's
    change = second.channels['camber'][at, 0] - first.channels['camber'][at, 0]
    given = np.radians(-2.0) - baseline.group('front_alignment').scalar('camber')
    assert change == pytest.approx(given, abs=np.radians(0.02))


def test_no_bar_run_is_softer_in_roll(baseline):
    bar = cache.kc_result(baseline, 'front', 'opposite_wheel_travel', steps=11)
    bare = cache.kc_result(baseline, 'front', cache.NO_BAR, steps=11)
    roll_moment = lambda r: np.ptp(r.channels['pad_force'][:, 0])  # noqa: E731
    assert roll_moment(bare) < roll_moment(bar)


def test_unknown_fidelity_is_refused(baseline):
    with pytest.raises(SolverError, match="fidelity 'wobbly' is not available"):
        cache.kc_result(baseline, 'front', 'parallel_wheel_travel', fidelity='wobbly')


def test_runs_on_the_shared_model_equal_runs_on_fresh_ones(baseline, monkeypatch):
    """The rigid-limit model assembled once gives every event what a new assembly gives."""
    built = []
    real = from_config.build_kc_model
    monkeypatch.setattr(from_config, 'build_kc_model',
                        lambda *a, **k: built.append(a) or real(*a, **k))
    events = ('lateral_force', 'opposite_wheel_travel', 'lateral_force')
    shared = [from_config.run_kc_event(baseline, e, 'rear', ['steps=11'], fidelity='flexible',
                                       at_rigid_limit=True, build=cache.kc_model)
              for e in events]
    assert len(built) == 1
    for event, outcome in zip(events, shared):
        fresh = from_config.run_kc_event(baseline, event, 'rear', ['steps=11'],
                                         fidelity='flexible', at_rigid_limit=True)
        assert outcome.channels.keys() == fresh.channels.keys()
        for name, channel in fresh.channels.items():
            np.testing.assert_array_equal(outcome.channels[name].values, channel.values)
        assert outcome.metrics == fresh.metrics
        assert outcome.notes == fresh.notes


def test_a_run_leaves_the_shared_model_as_it_was(baseline):
    model = cache.kc_model(baseline, 'front', 'rigid', 'the run that built it')
    inp = model.inp
    from_config.run_kc_event(baseline, 'lateral_force', 'front', ['steps=5'],
                             build=cache.kc_model)
    assert cache.kc_model(baseline, 'front', 'rigid') is model
    assert model.label == 'the run that built it'
    assert model.inp is inp


def _limit_run(config):
    return cache.kc_outcome(config, 'lateral_force', 'rear', ['steps=5'], 'flexible',
                            at_rigid_limit=True)


def test_an_outcome_is_read_from_the_disk_by_a_new_process(baseline, monkeypatch):
    first = _limit_run(baseline)
    direct = from_config.run_kc_event(baseline, 'lateral_force', 'rear', ['steps=5'],
                                      fidelity='flexible', at_rigid_limit=True)
    cache.clear()  # what a new process holds
    monkeypatch.setattr(from_config, 'run_kc_event', _no_solving)
    again = _limit_run(baseline)
    assert again is not first
    assert again.channels.keys() == direct.channels.keys()
    for name, channel in direct.channels.items():
        np.testing.assert_array_equal(again.channels[name].values, channel.values)
    assert again.metrics == direct.metrics
    assert again.notes == direct.notes
    assert (again.configuration, again.fidelity, again.axle) == ('baseline', 'flexible', 'rear')


def test_an_outcome_of_an_edited_data_file_or_other_code_is_run_again(sedan_master, sample_root,
                                                                      tmp_path, monkeypatch):
    monkeypatch.setenv('XDG_CACHE_HOME', str(tmp_path / 'cache'))
    cache.clear()
    solved = []
    real = from_config.run_kc_event
    monkeypatch.setattr(from_config, 'run_kc_event',
                        lambda *a, **k: solved.append(a) or real(*a, **k))
    before = _limit_run(load_study(sedan_master).configurations['baseline'])
    cache.clear()
    _limit_run(load_study(sedan_master).configurations['baseline'])
    assert len(solved) == 1
    alignment = sample_root / 'sedan' / 'rear_alignment' / 'X.yaml'
    alignment.write_text(alignment.read_text().replace('camber: -1.2', 'camber: -2.2'))
    cache.clear()
    edited = load_study(sedan_master).configurations['baseline']
    after = _limit_run(edited)
    assert len(solved) == 2
    # the new outcome is of the new data: one degree more negative camber at design
    at = 2  # design step of a 5-step symmetric sweep
    change = after.channels['camber_left'].values[at] - before.channels['camber_left'].values[at]
    assert change == pytest.approx(np.radians(-1.0), abs=np.radians(0.02))
    cache.clear()
    monkeypatch.setattr(cache, '_code', lambda: 'the sources after an edit')
    _limit_run(edited)
    assert len(solved) == 3
