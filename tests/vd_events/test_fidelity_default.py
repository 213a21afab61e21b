# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Which K&C fidelity a run gets: the configuration's ``flexible`` switch by default.

Every model that reads the configuration and has flexible components (the K&C model
and the full vehicle, whose suspension maps are K&C runs) follows the switch; the
analytical models stay rigid; an explicit fidelity (``--fidelity``, a plan's or a
sweep's ``fidelity``, a goal's) overrides it. The sample sedan's ``sport`` switches its
components flexible in the master file, ``baseline`` does not.
"""
from __future__ import annotations

from pathlib import Path

import pytest

from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_events.orchestration.runner import RunRequest, validate
from vd_events.studies.plan import expand, load_plan
from vd_events.sweeps.plan import RunSpec
from vd_solvers.families import MODELS
from vd_solvers.results import run_fidelity

#: (event, model, axle) of one run of each model family
RUNS = (('handling_diagram', 'two_track', ''), ('steady_state_circular', 'bicycle', ''),
        ('parallel_wheel_travel', 'kc', 'front'), ('step_steer', 'vehicle', ''))


@pytest.fixture(scope='module')
def study():
    return load_study(default_master())


def test_the_sample_study_has_a_flexible_and_a_rigid_configuration(study) -> None:
    assert study.configurations['sport'].flexible
    assert not study.configurations['baseline'].flexible


@pytest.mark.parametrize(('event', 'model', 'axle'), RUNS)
def test_the_default_fidelity_follows_the_switch_for_models_with_flexible_parts(
        study, event, model, axle) -> None:
    flexible_parts = model in ('kc', 'vehicle')
    for name, switch in (('sport', True), ('baseline', False)):
        request = validate(study, RunRequest(event=event, configuration=name, model=model,
                                             axle=axle))
        expected = 'flexible' if switch and flexible_parts else 'rigid'
        assert request.fidelity == expected, (name, model)
        assert run_fidelity(model, study.configurations[name]) == expected


@pytest.mark.parametrize('model', ['kc', 'vehicle'])
def test_an_explicit_fidelity_overrides_the_switch(study, model) -> None:
    event, axle = {'kc': ('lateral_force', 'front'), 'vehicle': ('step_steer', '')}[model]
    rigid = validate(study, RunRequest(event=event, configuration='sport', model=model,
                                       axle=axle, fidelity='rigid'))
    assert rigid.fidelity == 'rigid'
    assert run_fidelity(model, study.configurations['sport'], 'rigid') == 'rigid'
    assert run_fidelity(model, study.configurations['baseline'], 'flexible') == 'flexible'


def test_an_unknown_configuration_is_rigid_until_validate_refuses_it() -> None:
    assert [run_fidelity(m, None) for m in MODELS] == ['rigid'] * len(MODELS)


def test_a_plan_run_without_fidelity_follows_each_configuration(study, tmp_path: Path) -> None:
    plan = tmp_path / 'plan.yaml'
    plan.write_text('name: ladder\nruns:\n  - event: step_steer\n    models: [vehicle]\n'
                    '  - event: step_steer\n    models: [vehicle]\n'
                    '    configurations: [sport]\n    fidelity: rigid\n')
    runs = expand(load_plan(plan), study, tmp_path / 'bags')
    got = {(r.configuration, r.fidelity, r.bag.name) for r in runs}
    assert got == {('baseline', 'rigid', 'step_steer_vehicle_baseline'),
                   ('stiff_rear', 'rigid', 'step_steer_vehicle_stiff_rear'),
                   ('sport', 'flexible', 'step_steer_vehicle_sport_flexible'),
                   ('sport', 'rigid', 'step_steer_vehicle_sport')}


def test_a_sweep_run_without_fidelity_is_resolved_by_validate(study) -> None:
    spec = RunSpec(event='step_steer', model='vehicle')
    assert spec.fidelity == ''
    request = validate(study, RunRequest(event=spec.event, configuration='sport',
                                         model=spec.model, fidelity=spec.fidelity))
    assert request.fidelity == 'flexible'
