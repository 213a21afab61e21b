# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Import of realistic VBOX 3i logs: what the import checks, chooses, repairs and refuses.

The logs are written by ``tests/vbox_logs.py`` from a known bicycle-model response (41
channels, IMU and slip module, ``*_raw`` GPS channels, ``[channel units]`` with the
degree sign in Windows-1252, 100 Hz, glitches, a 2 s gap, either yaw-rate convention);
every expected value comes from the known signal or from what the fixture injected.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest

import vbox_logs as vb
from vd_events.cli.main import main
from vd_events.errors import InputError
from vd_events.measured.columns import load_map
from vd_events.measured.compare import load_outcomes
from vd_events.measured.importer import ImportOptions, read_measurement
from vd_events.measured.vbo import read_vbo

DEG = math.pi / 180.0
G = vb.G


@pytest.fixture(scope='module')
def swd() -> vb.Truth:
    return vb.swd_truth(amplitude=180.0 * DEG, direction=1)


def _log(tmp_path: Path, truth: vb.Truth, name: str = 'swd.vbo', **kwargs):
    return vb.write(tmp_path / name, truth, vb.Log(**kwargs))


def test_units_come_from_the_file_with_raw_gps_channels(tmp_path: Path, swd) -> None:
    """
    Take every unit [channel units] states, though the header has *_raw GPS channels.

    The 26 unit lines belong to the 26 module channels; the five *_raw channels are GPS
    channels with the units of their standard twins and no line of their own.
    """
    path, _, _ = _log(tmp_path, swd)
    m = read_vbo(path, None)
    assert not any('not taken from the file' in n for n in m.notes)
    assert not any('assumed' in n for n in m.notes)
    assert m.source_units['yaw_rate'] == '\u00b0/s'  # the legacy one-byte degree sign
    cmap = load_map(vb.write_map(tmp_path / 'map.yaml', 'sine_with_dwell'))
    m = read_vbo(path, cmap)
    assert m.source_units['steering_wheel_angle'] == '\u00b0'
    assert_allclose(m.channels['steering_wheel_angle'], swd.steering_wheel_angle, atol=0.3 * DEG)


def test_the_imu_yaw_rate_is_preferred_and_the_choice_said(tmp_path: Path, swd) -> None:
    path, _, _ = _log(tmp_path, swd)
    m = read_vbo(path, None)
    assert m.columns['yaw_rate'] == 'YawRate'
    note = next(n for n in m.notes if n.startswith('yaw_rate <- '))
    assert "IMU 'YawRate'" in note and "slip module 'Yaw_Rate'" in note
    # the noise each channel carries, as the fixture wrote it (0.3 and 3.7 deg/s)
    noise = [float(s.split(' deg/s')[0]) for s in note.split('noise ')[1:]]
    assert noise[0] == pytest.approx(0.3, rel=0.2) and noise[1] == pytest.approx(3.7, rel=0.2)
    assert_allclose(m.channels['yaw_rate'], swd.yaw_rate, atol=1.5 * DEG)


def test_sample_rate_is_the_logger_interval_and_the_gap_is_reported(tmp_path: Path, swd) -> None:
    path, times, first = _log(tmp_path, swd, gap=(9.0, 2.0))
    measured, _ = read_measurement(path, None)
    f = measured.findings
    assert f is not None
    assert f.interval == pytest.approx(0.01)
    (gap,) = f.gaps
    assert gap.start == pytest.approx(8.99) and gap.end == pytest.approx(11.0)
    assert gap.length == pytest.approx(2.01)
    assert gap.line == first + times.index(gap.end)  # the row after the gap
    assert any(n.startswith('gap: 2.01 s without samples from t = 8.99 s to 11.00 s')
               for n in measured.notes)


def test_glitches_are_found_with_time_value_and_line_and_refused(tmp_path: Path, swd) -> None:
    glitches = [(5.0, 'Steering_Angle', 27899.0), (6.5, 'Steering_Angle', -8116.0),
                (7.2, 'YawRate', 327.67)]
    path, times, first = _log(tmp_path, swd, glitches=glitches)
    cmap = load_map(vb.write_map(tmp_path / 'map.yaml', 'sine_with_dwell'))
    with pytest.raises(InputError) as err:
        read_measurement(path, cmap)
    text = str(err.value)
    column = vb.MODULE.index(('Steering_Angle', '\u00b0')) + 16
    assert text.startswith(f"{path}: line {first + 500}, column {column} 'Steering_Angle': "
                           '3 glitches in the imported channels: steering_wheel_angle 27899 deg '
                           'at t = 5.00 s (outside +/-1080 deg)')
    assert f'steering_wheel_angle -8116 deg at t = 6.50 s (line {first + 650}' in text
    assert f'yaw_rate 327.67 deg/s at t = 7.20 s (line {first + 720}' in text
    assert 'repair them with --repair glitches' in text


def test_glitches_repaired_when_asked(tmp_path: Path, swd) -> None:
    glitches = [(5.0, 'Steering_Angle', 27899.0), (6.5, 'Steering_Angle', -8116.0)]
    path, _, _ = _log(tmp_path, swd, glitches=glitches)
    cmap = load_map(vb.write_map(tmp_path / 'map.yaml', 'sine_with_dwell'))
    measured, _ = read_measurement(path, cmap, ImportOptions(repair=('glitches',)))
    swa = measured.channels['steering_wheel_angle']
    # linear between the neighbours: within the steer's change over one sample of the truth
    assert_allclose(swa, swd.steering_wheel_angle, atol=0.3 * DEG + 2.0 * DEG)
    assert swa[500] == pytest.approx(swd.steering_wheel_angle[500], abs=0.5 * DEG)
    repaired = [n for n in measured.notes if n.startswith('glitch repaired:')]
    assert len(repaired) == 2 and 'at t = 5.00 s' in repaired[0]


@pytest.mark.parametrize('iso', [True, False])
def test_yaw_sign_checked_against_heading_and_lateral_acceleration(tmp_path: Path, swd,
                                                                   iso: bool) -> None:
    path, _, _ = _log(tmp_path, swd, yaw_iso=iso)
    if iso:
        measured, _ = read_measurement(path, None)
        assert_allclose(measured.channels['yaw_rate'], swd.yaw_rate, atol=1.5 * DEG)
        assert any(n.startswith('sign check: yaw_rate agrees') for n in measured.notes)
        return
    with pytest.raises(InputError) as err:
        read_measurement(path, None)
    assert str(err.value).startswith(
        f"{path}: column 21 'YawRate': the yaw rate is positive clockwise: it opposes the "
        'heading rate (correlation -')
    assert '--yaw-sign reversed' in str(err.value)
    for sign in ('auto', 'reversed'):
        measured, _ = read_measurement(path, None, ImportOptions(yaw_sign=sign))
        assert_allclose(measured.channels['yaw_rate'], swd.yaw_rate, atol=1.5 * DEG)
        assert any(n.startswith('yaw_rate reversed') for n in measured.notes)


def test_reversing_an_iso_yaw_rate_is_refused(tmp_path: Path, swd) -> None:
    path, _, _ = _log(tmp_path, swd, yaw_iso=True)
    with pytest.raises(InputError, match='--yaw-sign reversed makes the yaw rate oppose'):
        read_measurement(path, None, ImportOptions(yaw_sign='reversed'))


def test_time_window_from_to(tmp_path: Path, swd) -> None:
    path, _, _ = _log(tmp_path, swd)
    measured, _ = read_measurement(path, None, ImportOptions(start=2.0, end=8.0))
    t = measured.channels['time']
    assert t[0] == pytest.approx(0.0) and t[-1] == pytest.approx(6.0)
    assert_allclose(measured.channels['speed'], swd.speed[200:801], atol=0.3)
    assert any(n.startswith('window: 2.00 s to 8.00 s of the log (--from/--to)')
               for n in measured.notes)


def test_time_window_by_event_detection_leaves_a_late_gap_out(tmp_path: Path, swd) -> None:
    """The sine with dwell found by its steering (S7.11.5): the window ends before the gap."""
    path, _, _ = _log(tmp_path, swd, gap=(10.5, 1.0))
    cmap = load_map(vb.write_map(tmp_path / 'map.yaml', 'sine_with_dwell'))
    measured, _ = read_measurement(path, cmap, ImportOptions(window='auto'))
    f = measured.findings
    assert f is not None and not f.gaps
    start, end = f.window
    # the steer starts at 3.0 s: the rate passes 75 deg/s within 0.1 s of it
    assert start == pytest.approx(3.0 - 2.0, abs=0.1) and end <= 10.5


def test_imu_lateral_acceleration_roll_corrected_and_moved_to_the_cog(tmp_path: Path,
                                                                      swd) -> None:
    path, _, _ = _log(tmp_path, swd, noise=False)
    cmap = load_map(vb.write_map(tmp_path / 'map.yaml', 'sine_with_dwell'))
    raw, _ = read_measurement(path, cmap)
    assert raw.columns['lateral_acceleration'] == 'Y_Accel'
    assert any(n.endswith('not moved to the CoG (no --imu-position)') for n in raw.notes)
    measured, _ = read_measurement(path, cmap, ImportOptions(imu_position=vb.IMU_POSITION))
    ay = measured.channels['lateral_acceleration']
    # the uncorrected IMU signal is off by g sin(roll) and the lever arms ...
    assert np.max(np.abs(raw.channels['lateral_acceleration'] - swd.lateral_acceleration)) > 0.5
    # ... the corrected one is the CoG's, within the derivatives estimated from the 100 Hz
    # samples (r' and p' low-passed at 6 Hz): everywhere but at the steer's start (3.0 s)
    # and end (COS, 3.0 + 1/0.7 + 0.5 s), where the steering rate jumps and r' has a corner
    # the filter rounds off
    t = swd.time
    corners = (np.abs(t - 3.0) < 0.1) | (np.abs(t - (3.0 + 1 / 0.7 + 0.5)) < 0.1)
    assert_allclose(ay[~corners], swd.lateral_acceleration[~corners], atol=0.03)
    assert np.max(np.abs(ay - swd.lateral_acceleration)) < 0.15
    assert np.sqrt(np.mean((ay - swd.lateral_acceleration) ** 2)) < 0.01
    assert any(n.startswith("lateral_acceleration: 'Y_Accel' moved from the IMU at "
                            '(0.6, -0.3, 0.25) m to the CoG and roll-corrected')
               for n in measured.notes)


def test_steering_of_the_wrong_sign_is_refused(tmp_path: Path, swd) -> None:
    path, _, _ = _log(tmp_path, swd)
    cmap = tmp_path / 'map.yaml'
    cmap.write_text(vb.MAP.format(event='sine_with_dwell').replace(
        '{channel: steering_wheel_angle}', '{channel: steering_wheel_angle, sign: -1}'))
    with pytest.raises(InputError, match="'Steering_Angle': the steering-wheel angle turns "
                       'against the heading rate'):
        read_measurement(path, load_map(cmap))


def _refused(capsys, tmp_path: Path, *argv: str) -> str:
    """Run ``vd ARGV``; assert exit 2, nothing on stdout, nothing written; the message."""
    before = sorted(p.name for p in tmp_path.iterdir())
    rc = main(list(argv))
    out, err = capsys.readouterr()
    assert (rc, out) == (2, '')
    assert sorted(p.name for p in tmp_path.iterdir()) == before
    return err.strip()


@pytest.mark.parametrize('options, message', [
    (['--yaw-sign', 'left'], "--yaw-sign: must be one of check, auto, reversed, found 'left'"),
    (['--repair', 'gaps'], "--repair: unknown repair 'gaps' (known: glitches)"),
    (['--imu-position', '0.6,0.3'], "--imu-position: X,Y,Z in m (three numbers), found "
     "'0.6,0.3'"),
    (['--imu-position', '0.6,a,0'], "--imu-position: X,Y,Z in m (three numbers), found "
     "'0.6,a,0'"),
    (['--from', '5', '--to', '4'], '--to: 4 s is not after --from 5 s'),
    (['--from', '-1'], '--from: must be a time >= 0 s from the first sample, found -1.0'),
    (['--window', 'auto', '--from', '1'], '--window: give either --window auto or '
     '--from/--to, not both'),
    (['--window', 'manoeuvre'], "--window: must be auto, found 'manoeuvre'"),
    (['--event', 'slalom'], '--event: must be one of step_steer, constant_radius_turn, '
     "sine_with_dwell, slowly_increasing_steer, vehicle_test, found 'slalom'"),
])
def test_bad_import_options(capsys, tmp_path: Path, swd, options, message) -> None:
    path, _, _ = _log(tmp_path, swd)
    assert _refused(capsys, tmp_path, 'import', str(path), '--bag', str(tmp_path / 'bag'),
                    *options) == message


def test_a_window_beyond_the_log_and_no_manoeuvre_are_refused(capsys, tmp_path: Path,
                                                              swd) -> None:
    path, _, _ = _log(tmp_path, swd)
    bag = str(tmp_path / 'bag')
    assert _refused(capsys, tmp_path, 'import', str(path), '--bag', bag, '--from', '30') == (
        f'{path}: --from 30 s is beyond the end of the log (12.00 s)')
    assert _refused(capsys, tmp_path, 'import', str(path), '--bag', bag, '--window', 'auto',
                    '--event', 'sine_with_dwell') == (
        f'{path}: --window auto: a sine_with_dwell log needs steering_wheel_angle to find '
        'its manoeuvre')
    straight = vb.simulate(6.0, vb.constant(0.0), vb.constant(80.0 / 3.6))
    flat, _, _ = vb.write(tmp_path / 'straight.vbo', straight)
    cmap = vb.write_map(tmp_path / 'map.yaml', 'sine_with_dwell')
    assert _refused(capsys, tmp_path, 'import', str(flat), '--bag', bag, '--map', str(cmap),
                    '--window', 'auto') == (
        f'{flat}: --window auto: no sine with dwell found in the steering-wheel angle of any '
        'gap-free stretch of the log')


def test_import_reports_what_it_checked(capsys, tmp_path: Path, swd) -> None:
    """At the terminal: the channel choice, the sample rate, the gap, the repairs."""
    path, _, _ = _log(tmp_path, swd, gap=(9.0, 2.0), glitches=[(5.0, 'Steering_Angle', 8116.0)])
    cmap = vb.write_map(tmp_path / 'map.yaml', 'sine_with_dwell')
    rc = main(['import', str(path), '--map', str(cmap), '--bag', str(tmp_path / 'bag'),
               '--repair', 'glitches', '--imu-position', '0.6,-0.3,0.25'])
    out = capsys.readouterr().out
    assert rc == 0
    assert "yaw_rate <- IMU 'YawRate'" in out
    assert "sample rate 100 Hz: the logger's interval 0.01 s" in out
    assert 'gap: 2.01 s without samples from t = 8.99 s to 11.00 s' in out
    assert 'glitch repaired: steering_wheel_angle 8116 deg at t = 5.00 s' in out
    (log,) = load_outcomes(tmp_path / 'bag')
    assert log.event == 'sine_with_dwell'
    assert log.metrics['sample_rate'].value == pytest.approx(100.0)
    assert log.metrics['gaps'].value == 1.0
    assert log.metrics['gap_time'].value == pytest.approx(2.01)
    assert log.metrics['glitches_repaired'].value == 1.0


def test_log_options_on_a_rig_measurement_are_refused(capsys, tmp_path: Path) -> None:
    samples = Path(__file__).resolve().parents[2] / 'src' / 'vd_events' / 'samples'
    data = samples / 'kc_spmm_bounce_front.csv'
    assert _refused(capsys, tmp_path, 'import', str(data), '--map',
                    str(samples / 'kc_spmm_bounce_front.map.yaml'), '--bag',
                    str(tmp_path / 'bag'), '--event', 'step_steer') == (
        f'{data}: a K&C rig measurement has no time axis: --repair, --yaw-sign, --from/--to, '
        '--window, --imu-position and --event are for vehicle logs')
