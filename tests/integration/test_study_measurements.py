# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd study`` with measurements: the plan's runs and an imported rig measurement.

Both go into one self-contained study report, compared on the rig's points.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

pytestmark = [pytest.mark.ros, pytest.mark.slow]

SAMPLES = Path(__file__).resolve().parents[2] / 'src' / 'vd_events' / 'samples'


def _vd(capsys, *argv):
    from vd_events.cli.main import main

    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def test_study_report_compares_the_plan_with_a_rig_measurement(capsys, tmp_path):
    rig = tmp_path / 'rig'
    rc, _, err = _vd(capsys, 'import', str(SAMPLES / 'kc_spmm_bounce_front.csv'), '--map',
                     str(SAMPLES / 'kc_spmm_bounce_front.map.yaml'), '--bag', str(rig))
    assert rc == 0, err
    plan = tmp_path / 'plan.yaml'
    plan.write_text('name: with_rig\nmeasurements: [rig]\nruns:\n'
                    '  - event: parallel_wheel_travel\n    models: [kc]\n    axle: front\n'
                    '    configurations: [baseline, sport]\n    parameters: [steps=41]\n')
    out = tmp_path / 'out'
    rc, stdout, err = _vd(capsys, 'study', str(plan), '--report', str(out), '--json')
    assert rc == 0, err
    summary = json.loads(stdout)
    text = Path(summary['study_report']).read_text()
    for config in ('baseline', 'sport'):
        assert (f'Simulation vs test — parallel_wheel_travel front: {config} (kc, ') in text
    # the rig sample is the baseline model with noise: baseline passes; sport (other
    # lower-arm point and camber) is told apart by the camber gain and camber
    assert 'parallel_wheel_travel front: baseline (kc, rigid) vs baseline (rig): PASS' in text
    assert 'vs baseline (rig): FAIL' in text
    assert 'baseline (rig)' in (out / 'report.html').read_text()  # overlaid in the static one


def test_plan_measurement_must_be_a_finished_bag(capsys, tmp_path):
    plan = tmp_path / 'plan.yaml'
    plan.write_text('name: p\nmeasurements: [nothing]\nruns:\n  - event: handling_diagram\n')
    rc, out, err = _vd(capsys, 'study', str(plan))
    assert (rc, out) == (2, '')
    assert err.strip() == (f'{plan}: measurements[0]: {tmp_path / "nothing"}: not a finished '
                           'bag (vd import writes one)')
