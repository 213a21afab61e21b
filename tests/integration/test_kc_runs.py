# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
K&C events over the ROS graph.

Every event on every configuration of both sample vehicles (embedded), one
distributed run, JSON contract, bags and report.
"""
from __future__ import annotations

import json

import pytest

pytestmark = [pytest.mark.ros, pytest.mark.slow]

EVENTS = ('parallel_wheel_travel', 'opposite_wheel_travel', 'lateral_force',
          'longitudinal_force')


def _vd(capsys, *argv):
    from vd_events.cli.main import main

    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


@pytest.mark.parametrize('vehicle, configs', [('sedan', ['baseline', 'stiff_rear', 'sport']),
                                              ('hmmwv', ['baseline', 'bushings'])])
def test_all_kc_events_on_every_configuration(capsys, tmp_path, sample_root, vehicle, configs):
    # rigid: the residual bounds below are the rigid model's (a plan run without fidelity
    # follows the configuration's flexible switch; the flexible model's force tolerance
    # scales with its stiffest component)
    runs = ''.join(f"""  - event: {event}
    models: [kc]
    axle: {axle}
    configurations: all
    fidelity: rigid
    parameters: [steps=21]
""" for event in EVENTS for axle in ('front', 'rear'))
    runs += """  - event: steering
    models: [kc]
    axle: front
    configurations: all
    fidelity: rigid
    parameters: [steps=21]
"""
    plan = tmp_path / 'plan.yaml'
    plan.write_text(f"name: kc_{vehicle}\nmaster: {sample_root / 'studies' / (vehicle + '.yaml')}"
                    f"\nruns:\n{runs}")
    out = tmp_path / 'out'
    rc, stdout, err = _vd(capsys, 'study', str(plan), '--report', str(out), '--json')
    assert rc == 0, err
    summary = json.loads(stdout)
    assert len(summary['runs']) == 9 * len(configs)
    assert [r['error'] for r in summary['runs']] == [None] * len(summary['runs'])
    for run in summary['runs']:
        assert run['metrics']['max_constraint_residual']['value'] <= 1e-9
        assert run['metrics']['max_force_residual']['value'] <= 1e-6
    html = (out / 'report.html').read_text()
    assert 'parallel_wheel_travel — front (kc)' in html
    assert (out / 'parallel_wheel_travel_front_kc_0.png').stat().st_size > 10_000


def test_kc_run_json_contract_and_distributed(capsys, tmp_path, sedan_master):
    args = ('run', 'parallel_wheel_travel', '--axle', 'front', '--model', 'kc', '--config',
            'sport', '--master', str(sedan_master), '--param', 'steps=21', '--json')
    rc, out, err = _vd(capsys, *args)
    assert rc == 0, err
    embedded = json.loads(out)
    # sport switches its front components flexible in the master file: the default fidelity
    assert (embedded['event'], embedded['configuration'], embedded['model'],
            embedded['fidelity'], embedded['axle']) == ('parallel_wheel_travel', 'sport', 'kc',
                                                        'flexible', 'front')
    assert embedded['metrics']['camber']['unit'] == 'rad'
    assert len(embedded['channels']['toe_left']['values']) == 21
    bag = tmp_path / 'kc_bag'
    rc, out, err = _vd(capsys, *args, '--distributed', '--bag', str(bag))
    assert rc == 0, out + err
    distributed = json.loads(out)
    assert distributed['metrics'] == embedded['metrics']
    from vd_events.bags.bag import read_bag

    topics = [m.topic for m in read_bag(bag)]
    assert topics.count('/vd/kc/result') == 1
    assert topics.count('/vd/kc/state') == 21


def test_kc_bad_input(capsys, tmp_path, sedan_master):
    rc, _, err = _vd(capsys, 'run', 'steering', '--model', 'kc', '--axle', 'rear', '--master',
                     str(sedan_master))
    assert rc == 2
    assert err.strip() == ("event 'steering' needs a steered axle: the rear axle of 'baseline' "
                           "has no steering")
    rc, _, err = _vd(capsys, 'run', 'lateral_force', '--model', 'kc', '--master',
                     str(sedan_master))
    assert rc == 2
    assert err.strip() == "K&C events need --axle front or rear (found '')"
    rc, _, err = _vd(capsys, 'run', 'lateral_force', '--model', 'kc', '--axle', 'front',
                     '--fidelity', 'wobbly', '--master', str(sedan_master))
    assert rc == 2
    assert err.strip() == "unknown fidelity 'wobbly' (rigid, flexible)"
    rc, _, err = _vd(capsys, 'run', 'steady_state_circular', '--model', 'bicycle',
                     '--fidelity', 'flexible', '--master', str(sedan_master))
    assert rc == 2
    assert err.strip() == ("fidelity 'flexible' is available for models 'kc' and 'vehicle' "
                           "only (model 'bicycle' has no flexible components)")
    from vdtest import replace_once

    replace_once(sedan_master, '  front_flex: X\n', '')
    replace_once(sedan_master, '    flexible_components: [lca, strut, upright]\n', '')
    rc, _, err = _vd(capsys, 'run', 'lateral_force', '--model', 'kc', '--axle', 'front',
                     '--fidelity', 'flexible', '--master', str(sedan_master))
    assert rc == 2
    assert err.strip() == ("configuration 'baseline' has no flexible components on the front "
                           "axle (no front_flex group in the master file)")


@pytest.mark.slow
def test_flexible_kc_runs_embedded_and_distributed(capsys, tmp_path, sedan_master):
    """
    Run the flexible K&C lateral-force event over the ROS graph.

    `vd run lateral_force --model kc --fidelity flexible`: the same
    numbers embedded and distributed, softer than rigid, labelled flexible, in a bag.
    """
    from vd_events.bags.bag import read_bag

    runs = {}
    for mode in ('embedded', 'distributed'):
        args = ['run', 'lateral_force', '--model', 'kc', '--axle', 'front', '--fidelity',
                'flexible', '--param', 'steps=11', '--json', '--master', str(sedan_master),
                '--bag', str(tmp_path / mode)]
        rc, out, err = _vd(capsys, *args, *(['--distributed'] if mode == 'distributed' else []))
        assert rc == 0, err
        runs[mode] = json.loads(out)
    rc, out, err = _vd(capsys, 'run', 'lateral_force', '--model', 'kc', '--axle', 'front',
                       '--param', 'steps=11', '--json', '--master', str(sedan_master))
    rigid = json.loads(out)
    flex = runs['embedded']
    assert flex['fidelity'] == 'flexible' and rigid['fidelity'] == 'rigid'
    for name in ('lateral_stiffness', 'lateral_compliance_camber'):
        assert runs['distributed']['metrics'][name]['value'] == pytest.approx(
            flex['metrics'][name]['value'], rel=1e-12)
    stiffness = 'lateral_stiffness'
    assert flex['metrics'][stiffness]['value'] < rigid['metrics'][stiffness]['value']
    assert flex['metrics']['component_mass.lca']['value'] > 0.0
    results = [m.msg for m in read_bag(tmp_path / 'embedded') if m.topic == '/vd/kc/result']
    assert [r.fidelity for r in results] == ['flexible']
