# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
``vd grade`` on realistic logs (tests/vbox_logs.py) and on simulated runs in bags.

Expected values come from the known signals: A from the linear model's closed-form ramp
response, the entry speed the fixture drove, the gap it cut, the gradients of the linear
model; a glitchy or reversed log must grade as its clean twin once repaired or reversed.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import vbox_logs as vb
from vd_events.bags.outcomes import write_outcomes
from vd_events.cli.main import main
from vd_solvers.results import Channel, EventOutcome

DEG = math.pi / 180.0
POSITION = ','.join(f'{v:g}' for v in vb.IMU_POSITION)


@pytest.fixture(scope='module')
def logs(tmp_path_factory) -> Path:
    """
    Write two SIS runs, a valid sine with dwell, one entered at 83.5 km/h, a map.

    The SIS logs carry no sensor noise, so their A is the closed form's to the rounding;
    with the IMU's noise it scatters by about 0.3 deg (the yaw rate differentiated for the
    transfer to the CoG).
    """
    d = tmp_path_factory.mktemp('logs')
    for k, direction in enumerate((1, -1)):
        vb.write(d / f'sis_{k}.vbo', vb.sis_truth(direction=direction),
                 vb.Log(seed=k, event_comment='slowly increasing steer', noise=False))
    vb.write(d / 'swd.vbo', vb.swd_truth(amplitude=180.0 * DEG), vb.Log(gap=(10.5, 1.0)))
    vb.write(d / 'swd_fast.vbo', vb.swd_truth(amplitude=180.0 * DEG, entry_kmh=83.5),
             vb.Log(seed=5))
    vb.write_map(d / 'map.yaml', 'sine_with_dwell')
    return d


def grade(capsys, *argv: str) -> tuple[int, dict | str]:
    rc = main(['grade', *argv, '--json'])
    out = capsys.readouterr().out
    return rc, json.loads(out)


def expected_a() -> float:
    """Return A in deg: i_s (0.3 g - G'(0) k) / G(0) of the linear model, to 0.1 deg (S7.6.1)."""
    g0, g1 = vb.lateral_acceleration_gain(80.0 / 3.6)
    k = 13.5 * DEG / vb.CAR['ratio']
    return round(vb.CAR['ratio'] * (0.3 * vb.G - g1 * k) / g0 / DEG, 1)


def test_sine_with_dwell_graded_with_a_from_the_sis_logs(capsys, logs: Path,
                                                         tmp_path: Path) -> None:
    rc, out = grade(capsys, str(logs / 'swd.vbo'), str(logs / 'swd_fast.vbo'), '--map',
                    str(logs / 'map.yaml'), '--sis', str(logs / 'sis_0.vbo'),
                    str(logs / 'sis_1.vbo'), '--imu-position', POSITION,
                    '--out', str(tmp_path / 'grade'))
    assert rc == 0 and isinstance(out, dict)
    (proc,) = out['procedures']
    assert proc['a_reference'] == pytest.approx(expected_a() * DEG, abs=1e-9)
    runs = {r['label']: r for r in out['runs']}
    assert runs['swd.vbo (log)']['verdict'] == 'PASS'
    fast = runs['swd_fast.vbo (log)']
    assert fast['verdict'] == 'INVALID'
    assert fast['metrics']['entry_speed']['value'] == pytest.approx(83.5 / 3.6, abs=0.05)
    # an invalid run is not graded as passed, and the deciding criterion is named for it
    assert (proc['verdict'], proc['passed'], proc['valid']) == ('INVALID', False, False)
    assert (proc['deciding_run'], proc['deciding_criterion']) == (2, 'entry_speed')
    assert 'entry speed 83.5 km/h at BOS, outside 80 +/- 2 km/h (S7.9)' in proc['deciding']
    page = Path(out['report'])
    assert page.is_file() and 'entry_speed' in page.read_text()


def test_the_valid_run_alone_passes_and_the_deciding_criterion_is_its_least_margin(
        capsys, logs: Path, tmp_path: Path) -> None:
    rc, out = grade(capsys, str(logs / 'swd.vbo'), '--map', str(logs / 'map.yaml'),
                    '--a-reference', f'{expected_a():.1f}', '--imu-position', POSITION,
                    '--out', str(tmp_path / 'grade'))
    assert rc == 0 and isinstance(out, dict)
    (proc,) = out['procedures']
    (run,) = out['runs']
    assert proc['verdict'] == 'PASS' and proc['deciding_run'] == 1
    m = run['metrics']
    margins = {'yaw_rate_ratio_1_00': 1 - m['yaw_rate_ratio_1_00']['value'] / 0.35,
               'yaw_rate_ratio_1_75': 1 - m['yaw_rate_ratio_1_75']['value'] / 0.20,
               'lateral_displacement': m['lateral_displacement']['value'] / 1.83 - 1}
    assert proc['deciding_criterion'] == min(margins, key=margins.get)


def test_without_a_the_procedure_is_not_passed(capsys, logs: Path, tmp_path: Path) -> None:
    rc, out = grade(capsys, str(logs / 'swd.vbo'), '--map', str(logs / 'map.yaml'),
                    '--out', str(tmp_path / 'grade'))
    assert rc == 0 and isinstance(out, dict)
    (proc,) = out['procedures']
    assert proc['verdict'] == 'INCOMPLETE' and not proc['passed']
    assert any(n.startswith('A not known') for n in proc['notes'])


def _lateral_displacement(truth: vb.Truth) -> float:
    """Y(BOS + 1.07 s) of the known lateral acceleration, BOS where the steer reaches 5 deg."""
    t, ay = truth.fine['time'], truth.fine['lateral_acceleration']
    swa = truth.fine['steering_wheel_angle']
    bos = float(t[np.argmax(swa >= 5.0 * DEG)])
    w = (t >= bos) & (t <= bos + 1.07)
    vy = np.concatenate(([0.0], np.cumsum(0.5 * (ay[w][1:] + ay[w][:-1]) * np.diff(t[w]))))
    return float(np.sum(0.5 * (vy[1:] + vy[:-1]) * np.diff(t[w])))


def test_a_glitchy_log_is_refused_then_graded_as_its_clean_twin(capsys, tmp_path: Path) -> None:
    truth = vb.swd_truth(amplitude=180.0 * DEG)
    cmap = vb.write_map(tmp_path / 'map.yaml', 'sine_with_dwell')
    glitchy, _, _ = vb.write(tmp_path / 'glitchy.vbo', truth, vb.Log(glitches=[
        (1.5, 'Steering_Angle', 27899.0), (8.0, 'Steering_Angle', 8116.0)]))
    before = sorted(p.name for p in tmp_path.iterdir())
    rc = main(['grade', str(glitchy), '--map', str(cmap), '--a-reference', '26.9',
               '--out', str(tmp_path / 'grade')])
    out, err = capsys.readouterr()
    assert (rc, out) == (2, '') and '2 glitches in the imported channels' in err
    assert sorted(p.name for p in tmp_path.iterdir()) == before
    common = ['--map', str(cmap), '--a-reference', '26.9', '--imu-position', POSITION,
              '--out', str(tmp_path / 'grade')]
    rc, repaired = grade(capsys, str(glitchy), '--repair', 'glitches', *common)
    assert rc == 0 and isinstance(repaired, dict)
    m = repaired['runs'][0]['metrics']
    # the manoeuvre, not a 0.09 s glitch: the amplitude and displacement of the known steer
    assert m['amplitude']['value'] == pytest.approx(180.0 * DEG, rel=0.01)
    assert m['half_period']['value'] == pytest.approx(0.5 / 0.7, abs=0.01)
    assert m['lateral_displacement']['value'] == pytest.approx(_lateral_displacement(truth),
                                                               rel=0.02)


def test_a_log_with_the_yaw_rate_positive_clockwise(capsys, tmp_path: Path) -> None:
    """Refused by default; with --yaw-sign auto graded as the same run logged ISO."""
    truth = vb.swd_truth(amplitude=180.0 * DEG)
    cmap = vb.write_map(tmp_path / 'map.yaml', 'sine_with_dwell')
    iso, _, _ = vb.write(tmp_path / 'iso.vbo', truth)
    clockwise, _, _ = vb.write(tmp_path / 'cw.vbo', truth, vb.Log(yaw_iso=False))
    rc = main(['grade', str(clockwise), '--map', str(cmap), '--a-reference', '26.9'])
    assert rc == 2 and 'the yaw rate is positive clockwise' in capsys.readouterr().err
    common = ['--map', str(cmap), '--a-reference', '26.9', '--out', str(tmp_path / 'g')]
    _, a = grade(capsys, str(iso), *common)
    _, b = grade(capsys, str(clockwise), '--yaw-sign', 'auto', *common)
    assert isinstance(a, dict) and isinstance(b, dict)
    ma, mb = a['runs'][0]['metrics'], b['runs'][0]['metrics']
    assert mb['peak_yaw_rate']['value'] == pytest.approx(ma['peak_yaw_rate']['value'],
                                                         abs=0.5 * DEG)
    assert mb['peak_yaw_rate']['value'] < 0  # the second lobe, after a left first steer


def test_a_gap_inside_the_manoeuvre_is_refused_with_where(capsys, tmp_path: Path) -> None:
    truth = vb.swd_truth(amplitude=180.0 * DEG)
    cmap = vb.write_map(tmp_path / 'map.yaml', 'sine_with_dwell')
    path, _, _ = vb.write(tmp_path / 'gap.vbo', truth, vb.Log(gap=(5.5, 2.0)))
    rc = main(['grade', str(path), '--map', str(cmap), '--a-reference', '26.9',
               '--out', str(tmp_path / 'grade')])
    out, err = capsys.readouterr()
    assert (rc, out) == (2, '')
    assert err.startswith(f'{path}: sine_with_dwell: the record ends ')
    assert 'the log has gaps at t = 5.49 s (2.01 s)' in err
    assert not (tmp_path / 'grade').exists()


def test_step_steer_log_graded_by_iso_7401(capsys, tmp_path: Path) -> None:
    truth = vb.step_truth(angle=40.0 * DEG, kmh=100.0, ramp_time=0.1, start=2.0, duration=9.0)
    cmap = vb.write_map(tmp_path / 'map.yaml', 'step_steer')
    path, _, _ = vb.write(tmp_path / 'step.vbo', truth, vb.Log(gap=(8.0, 0.5)))
    rc, out = grade(capsys, str(path), '--map', str(cmap), '--imu-position', POSITION,
                    '--out', str(tmp_path / 'grade'))
    assert rc == 0 and isinstance(out, dict)
    (run,) = out['runs']
    c, u = vb.CAR, 100.0 / 3.6
    gain = u / (c['a'] + c['b'] + vb.understeer_gradient() * u ** 2) / c['ratio']
    assert run['verdict'] == 'VALID'
    assert run['metrics']['yaw_rate_gain']['value'] == pytest.approx(gain, rel=0.02)
    assert run['metrics']['lateral_acceleration_gain']['value'] == pytest.approx(gain * u,
                                                                                 rel=0.02)


def test_circle_log_graded_by_iso_4138(capsys, tmp_path: Path) -> None:
    truth = vb.circle_truth(radius=40.0, duration=40.0)
    cmap = vb.write_map(tmp_path / 'map.yaml', 'constant_radius_turn')
    path, _, _ = vb.write(tmp_path / 'circle.vbo', truth)
    rc, out = grade(capsys, str(path), '--map', str(cmap), '--imu-position', POSITION,
                    '--steering-ratio', '16', '--wheelbase', '2.7',
                    '--out', str(tmp_path / 'grade'))
    assert rc == 0 and isinstance(out, dict)
    (run,) = out['runs']
    m = run['metrics']
    assert run['verdict'] == 'VALID'
    assert m['understeer_gradient']['value'] == pytest.approx(vb.understeer_gradient(),
                                                              rel=0.05)
    assert m['radius']['value'] == pytest.approx(40.0, rel=0.01)


def _simulated_procedure(tmp_path: Path) -> Path:
    """Write a bag with a simulated procedure: two runs at 1.5A, the second entered fast."""
    a_ref = expected_a() * DEG
    sim = vb.swd_procedure([(1, 1.5 * a_ref), (-1, 1.5 * a_ref)], a_ref, [80.0, 83.5])
    return write_outcomes(tmp_path / 'sim', [(sim, 1_700_000_000_000_000_000)],
                          {'vd.kind': 'test'})


def test_a_simulated_procedure_is_regraded_from_its_series(capsys, tmp_path: Path) -> None:
    bag = _simulated_procedure(tmp_path)
    rc, out = grade(capsys, str(bag), '--out', str(tmp_path / 'grade'))
    assert rc == 0 and isinstance(out, dict)
    (proc,) = out['procedures']
    assert proc['a_reference'] == pytest.approx(expected_a() * DEG)
    verdicts = [r['verdict'] for r in out['runs']]
    assert verdicts == ['PASS', 'INVALID']  # the second run entered at 83.5 km/h
    assert proc['verdict'] == 'INVALID' and proc['deciding_criterion'] == 'entry_speed'


@pytest.mark.parametrize('argv, message', [
    (['--a-reference', '-3'], '--a-reference: must be a positive number, found -3.0'),
    (['--gvwr', '0'], '--gvwr: must be a positive number, found 0.0'),
    (['--a-reference', '400'], '--a-reference: 400 deg: A is the angle at 0.3 g, below the '
     '300 deg cap of the series'),
])
def test_bad_grade_options(capsys, logs: Path, tmp_path: Path, argv, message) -> None:
    rc = main(['grade', str(logs / 'swd.vbo'), '--map', str(logs / 'map.yaml'), *argv,
               '--out', str(tmp_path / 'grade')])
    out, err = capsys.readouterr()
    assert (rc, out, err.strip()) == (2, '', message)
    assert not (tmp_path / 'grade').exists()


def test_a_log_without_its_manoeuvre_named(capsys, logs: Path, tmp_path: Path) -> None:
    rc = main(['grade', str(logs / 'swd.vbo'), '--out', str(tmp_path / 'grade')])
    out, err = capsys.readouterr()
    assert (rc, out) == (2, '')
    assert err.strip() == (f"{logs / 'swd.vbo'}: test (test): event 'vehicle_test' has no "
                           'standard to grade by (graded: sine_with_dwell, '
                           'slowly_increasing_steer, step_steer, constant_radius_turn); a log '
                           'needs its manoeuvre: --event or event: in the column map')
    assert not (tmp_path / 'grade').exists()


def test_sis_inputs_that_are_not_files(capsys, logs: Path, tmp_path: Path) -> None:
    missing = tmp_path / 'nothere.vbo'
    rc = main(['grade', str(logs / 'swd.vbo'), '--map', str(logs / 'map.yaml'), '--sis',
               str(missing), '--out', str(tmp_path / 'grade')])
    out, err = capsys.readouterr()
    assert (rc, out, err.strip()) == (2, '', f'{missing}: no such file')
    empty = tmp_path / 'folder'
    empty.mkdir()
    rc = main(['grade', str(empty), '--out', str(tmp_path / 'grade')])
    out, err = capsys.readouterr()
    assert (rc, err.strip()) == (2, f'{empty}: a folder that is not a finished bag (no '
                                    'metadata.yaml)')


def test_a_replay_is_graded_as_a_single_run(capsys, tmp_path: Path) -> None:
    """A simulated run without a series (a replay of a log): graded as a log is."""
    truth = vb.swd_truth(amplitude=180.0 * DEG)
    replay = EventOutcome(
        event='sine_with_dwell', configuration='baseline', model='bicycle', fidelity='rigid',
        axle='', data_hash='3' * 64, metrics={},
        channels={k: Channel(u, getattr(truth, k)) for k, u in (
            ('time', 's'), ('steering_wheel_angle', 'rad'), ('yaw_rate', 'rad/s'),
            ('lateral_acceleration', 'm/s^2'), ('speed', 'm/s'))})
    bag = write_outcomes(tmp_path / 'replay', [(replay, 1_700_000_000_000_000_000)],
                         {'vd.kind': 'test'})
    rc, out = grade(capsys, str(bag), '--a-reference', f'{expected_a():.1f}',
                    '--out', str(tmp_path / 'grade'))
    assert rc == 0 and isinstance(out, dict)
    (proc,) = out['procedures']
    (run,) = out['runs']
    assert proc['label'] == 'baseline (bicycle) runs' and proc['verdict'] == 'PASS'
    assert run['metrics']['lateral_displacement']['value'] == pytest.approx(
        _lateral_displacement(truth), rel=0.02)
