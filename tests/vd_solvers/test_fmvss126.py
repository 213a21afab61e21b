# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Sine-with-dwell processing and grading (FMVSS 126) on synthetic signals.

Their answers are known in closed form: a filtered pure sine, the analytic steering
profile, a first-order yaw
decay, a smooth lateral acceleration with an exact double integral, a linear SIS.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import vbox_logs as vb
from vd_solvers.standards import fmvss126 as f

DEG = math.pi / 180.0
FS = 500.0  # Hz
T = np.arange(0.0, 8.0, 1.0 / FS)
START, FREQ, DWELL = 1.0, 0.7, 0.5
PERIOD = 1.0 / FREQ


def test_the_filter_is_phaseless_with_the_butterworth_gain():
    """Sosfiltfilt of a 6-pole Butterworth: |H|^2 = 1 / (1 + (f/fc)^12), zero phase."""
    x = np.sin(2 * math.pi * 5.0 * T)
    y = f.lowpass(T, x, 6.0)
    gain = 1.0 / (1.0 + (5.0 / 6.0) ** 12)
    inner = slice(1000, -1000)
    np.testing.assert_allclose(y[inner], gain * x[inner], atol=2e-4)


def test_bos_and_cos_of_the_analytic_steer():
    """
    Find BOS and COS of the analytic steer.

    BOS from the sine's own closed form; COS where the filtered steer returns to zero:
    the 10 Hz filter rounds the corner at the end of the steer (rate A w -> 0), which
    moves the crossing by 1/(2 pi 10 Hz) at most (16 ms).
    """
    a = 100.0 * DEG
    steer = f.sine_with_dwell(T, a, 1, START, FREQ, DWELL)
    w = 2 * math.pi * FREQ
    yaw = 0.4 * f.sine_with_dwell(T - 0.1, 1.0, 1, START, FREQ, DWELL)
    g = f.grade_run(T, steer, yaw, 8.0 * yaw, a_reference=20.0 * DEG)
    assert g.bos == pytest.approx(START + math.asin(5.0 * DEG / a) / w, abs=2e-3)
    assert 0.0 <= g.cos - (START + PERIOD + DWELL) <= 1.0 / (2 * math.pi * 10.0)
    assert g.amplitude == pytest.approx(a, rel=2e-3) and g.direction == 1


def _bump(t, centre, width):
    return np.exp(-(((t - centre) / width) ** 2))


def test_yaw_rate_ratios_of_a_first_order_decay():
    """
    Grade the yaw-rate ratios of a first-order decay.

    A smooth yaw response (Gaussian bumps: +R1 with the first steer, -P after the
    reversal) that decays as r(COS) exp(-(t - COS)/tau) once the steer is complete: the
    first local peak after the reversal is -P, and the ratios are known in closed form.
    """
    a, big_p, tau = 120.0 * DEG, 0.5, 0.8
    steer = f.sine_with_dwell(T, a, -1, START, FREQ, DWELL)  # first steer to the right
    cos = START + PERIOD + DWELL
    t2 = START + 1.5
    before = -0.3 * _bump(T, START + 0.6, 0.15) + big_p * _bump(T, t2, 0.25)
    r_cos = big_p * float(_bump(cos, t2, 0.25)) - 0.3 * float(_bump(cos, START + 0.6, 0.15))
    yaw = np.where(T < cos, before, r_cos * np.exp(-(T - cos) / tau))
    g = f.grade_run(T, steer, yaw, 10.0 * yaw, a_reference=24.0 * DEG)
    assert g.peak_yaw_rate == pytest.approx(big_p, rel=1e-4)
    for ratio, dt in ((g.yaw_rate_ratio_1_00, 1.0), (g.yaw_rate_ratio_1_75, 1.75)):
        exact = r_cos * math.exp(-(g.cos + dt - cos) / tau) / big_p
        assert ratio == pytest.approx(exact, rel=1e-3)
    assert g.stable_1_00 and g.stable_1_75 and g.direction == -1


def test_lateral_displacement_is_the_double_integral_from_bos():
    """
    Integrate the lateral displacement twice from BOS.

    a_y = a0 (1 - cos(W (t - start))), smooth at the start: its double integral from BOS
    has a closed form.
    """
    a, a0, big_w = 150.0 * DEG, 6.0, 3.0
    steer = f.sine_with_dwell(T, a, 1, START, FREQ, DWELL)
    tau = np.clip(T - START, 0.0, None)
    ay = a0 * (1.0 - np.cos(big_w * tau))
    yaw = 0.3 * f.sine_with_dwell(T - 0.1, 1.0, 1, START, FREQ, DWELL)
    g = f.grade_run(T, steer, yaw, ay, a_reference=30.0 * DEG)
    tb = g.bos - START
    t1 = tb + 1.07
    exact = a0 * ((t1 - tb) ** 2 / 2 - ((math.cos(big_w * tb) - math.cos(big_w * t1)) / big_w
                                        - math.sin(big_w * tb) * (t1 - tb)) / big_w)
    assert g.lateral_displacement == pytest.approx(exact, rel=1e-3)
    assert g.responsiveness_applies and g.responsive == (exact >= 1.83)


def test_responsiveness_applies_from_5a():
    steer = f.sine_with_dwell(T, 100.0 * DEG, 1, START, FREQ, DWELL)
    yaw = 0.3 * f.sine_with_dwell(T - 0.1, 1.0, 1, START, FREQ, DWELL)
    g = f.grade_run(T, steer, yaw, 5 * yaw, a_reference=25.0 * DEG)  # 4A
    assert not g.responsiveness_applies and g.responsive is None


def test_a_from_linear_sis_runs_is_rounded_to_a_tenth_of_a_degree():
    """S7.6.1: each run's A to the nearest 0.1 deg, the absolute values averaged, to 0.1."""
    gain = 0.4  # m/s^2 of lateral acceleration per degree of steering-wheel angle
    steer = np.linspace(0.0, 40.0 * DEG, 400)
    runs = [(steer, steer / DEG * gain), (-steer, -steer / DEG * gain * 1.02)]
    each = [round(0.3 * 9.80665 / gain, 1), round(0.3 * 9.80665 / (gain * 1.02), 1)]
    assert f.amplitude_from_sis(runs) == pytest.approx(round(np.mean(each), 1) * DEG,
                                                        abs=1e-12)


@pytest.mark.parametrize('a_deg, first, last, count', [
    (40.0, 60.0, 270.0, 12),   # 6.5A = 260 < 270: the series ends at 270 deg
    (50.0, 75.0, 300.0, 10),   # 6.5A = 325: capped at 300 deg
    (20.0, 30.0, 270.0, 25),
])
def test_amplitude_series(a_deg, first, last, count):
    series = np.array(f.amplitude_series(a_deg * DEG)) / DEG
    assert series[0] == pytest.approx(first) and series[-1] == pytest.approx(last)
    assert len(series) == count and np.all(np.diff(series) > 0)


@pytest.mark.parametrize('t, x, message', [
    (np.arange(10.0), np.zeros(10), 'need at least 30 samples of equal-length time and signal'),
    (np.r_[np.arange(20.0), np.arange(20.0)], np.zeros(40),
     'time does not increase at t = 0.000 s (sample 21: 19.000 s, then 0.000 s)'),
    (np.r_[np.arange(0.0, 2.0, 0.01), np.arange(4.0, 6.0, 0.01)], np.zeros(400),
     'time step not uniform: 2.01 s from t = 1.990 s to 4.000 s where the step is 0.01 s (a '
     'gap in the record; 1 such step(s))'),
    (np.arange(0, 10, 0.1), np.zeros(100), 'sample rate 10.0 Hz is too low for a 10 Hz filter'),
])
def test_bad_signals_are_refused(t, x, message):
    with pytest.raises(f.ProcessingError) as err:
        f.lowpass(t, x, 10.0)
    assert str(err.value) == message


def test_a_short_record_is_refused():
    short = T[T < START + PERIOD + DWELL + 1.0]
    steer = f.sine_with_dwell(short, 100 * DEG, 1, START, FREQ, DWELL)
    yaw = 0.3 * f.sine_with_dwell(short - 0.1, 1.0, 1, START, FREQ, DWELL)
    with pytest.raises(f.ProcessingError, match='the rule needs 1.75 s'):
        f.grade_run(short, steer, yaw, yaw, a_reference=20 * DEG)


def test_no_steer_is_refused():
    zero = np.zeros_like(T)
    with pytest.raises(f.ProcessingError) as err:
        f.grade_run(T, zero, zero, zero, a_reference=20 * DEG)
    assert str(err.value) == 'the steering-wheel rate never exceeds 75 deg/s for 200 ms'


def _run(a_deg, direction=1, decay=0.8, hold=0.3, speed=None, a_ref: float | None = 20.0):
    """
    Grade a run whose yaw rate decays after the steer.

    The yaw rate peaks at -P 1.5 s into the steer (the first local peak after the
    reversal), falls linearly to -hold P at the end of the steer and then decays as
    exp(-(t - COS)/decay): the ratios are about hold exp(-dt/decay).
    """
    a = a_deg * DEG
    steer = f.sine_with_dwell(T, a, direction, START, FREQ, DWELL)
    cos = START + PERIOD + DWELL
    t2, big_p = START + 1.5, 0.5
    rise = 0.3 * _bump(T, START + 0.6, 0.15) - big_p * _bump(T, t2, 0.25)
    fall = -big_p * (1.0 - (1.0 - hold) * (T - t2) / (cos - t2))
    after = -hold * big_p * np.exp(-(T - cos) / decay)
    yaw = np.where(T < t2, rise, np.where(T < cos, fall, after))
    return f.grade_run(T, steer, direction * yaw, 10.0 * direction * yaw,
                       a_reference=None if a_ref is None else a_ref * DEG, speed=speed,
                       commanded_amplitude=a)


def test_the_procedure_fails_on_the_first_failing_run_and_names_it():
    """
    Fail the procedure on the first failing run, and name it.

    A slow decay (ratio about 0.8 exp(-1/3) = 57 % at COS + 1 s) fails S5.2.1, a
    fast one (0.3 exp(-1/0.3) = 1 %) passes: the first failing run in series order
    decides.
    """
    runs = [_run(30.0, decay=0.3), _run(100.0, decay=3.0, hold=0.8),
            _run(120.0, decay=3.0, hold=0.8), _run(30.0, -1, decay=0.3)]
    assert runs[0].stable_1_00 and not runs[1].stable_1_00
    verdict = f.grade_procedure(runs, 20.0 * DEG)
    assert not verdict.passed and verdict.valid
    assert verdict.deciding_run == 1 and verdict.deciding_criterion == 'yaw_rate_ratio_1_00'
    by = {c.name: c for c in verdict.criteria}
    assert not by['yaw_rate_ratio_1_00'].passed and by['yaw_rate_ratio_1_00'].runs == 4
    assert by['yaw_rate_ratio_1_00'].deciding_value == pytest.approx(
        runs[1].yaw_rate_ratio_1_00)
    # responsiveness from 5A = 100 deg: graded on the two runs at 100 and 120 deg only
    assert by['lateral_displacement'].runs == 2


def test_a_passing_procedure_names_the_run_of_least_margin():
    runs = [_run(30.0, decay=0.3), _run(60.0, decay=0.5, hold=0.5),
            _run(60.0, -1, decay=0.4, hold=0.6)]
    verdict = f.grade_procedure(runs, 20.0 * DEG)
    assert verdict.passed
    ratios = [g.yaw_rate_ratio_1_00 / 0.35 for g in runs] + \
        [g.yaw_rate_ratio_1_75 / 0.20 for g in runs]
    worst = int(np.argmax(ratios))
    assert verdict.deciding_run == worst % 3
    assert verdict.deciding_criterion == ('yaw_rate_ratio_1_00' if worst < 3
                                          else 'yaw_rate_ratio_1_75')


def test_a_ratio_exactly_at_the_limit_passes():
    """'Shall not exceed' is <=: a run whose ratio equals 35 % passes S5.2.1."""
    base = _run(30.0, decay=0.5)
    at_limit = dataclasses.replace(base, yaw_rate_ratio_1_00=0.35, stable_1_00=0.35 <= 0.35)
    assert f.grade_procedure([at_limit], 20.0 * DEG).passed


def test_entry_speed_outside_80_plus_minus_2_kmh_makes_the_procedure_invalid():
    ok = _run(30.0, speed=np.full_like(T, 81.9 / 3.6))
    slow = _run(30.0, speed=np.full_like(T, 77.9 / 3.6))
    assert ok.entry_speed == pytest.approx(81.9 / 3.6) and ok.speed_valid
    assert not slow.speed_valid
    verdict = f.grade_procedure([ok, slow], 20.0 * DEG)
    assert not verdict.valid and not verdict.passed


def test_responsiveness_applies_by_the_commanded_amplitude():
    """S5.2.3 counts commanded angles of 5A and more, whatever the filter did to the peak."""
    g = _run(100.0, a_ref=20.0)
    assert g.responsiveness_applies
    g = _run(99.0, a_ref=20.0)
    assert not g.responsiveness_applies and g.responsive is None


def test_heavy_vehicles_have_the_lower_displacement_limit():
    steer = f.sine_with_dwell(T, 150.0 * DEG, 1, START, FREQ, DWELL)
    yaw = 0.3 * f.sine_with_dwell(T - 0.1, 1.0, 1, START, FREQ, DWELL)
    light = f.grade_run(T, steer, yaw, 6.0 * yaw, a_reference=30 * DEG, gvwr=3500.0)
    heavy = f.grade_run(T, steer, yaw, 6.0 * yaw, a_reference=30 * DEG, gvwr=3500.1)
    assert light.displacement_limit == 1.83 and heavy.displacement_limit == 1.52


@pytest.mark.parametrize('kwargs, message', [
    ({'roll': np.zeros(10)}, f'roll has 10 samples, time has {T.size}'),
    ({'speed': np.full(T.size, np.nan)}, 'speed holds non-finite samples'),
    ({'gvwr': -1.0}, 'GVWR must be a positive mass, got -1.0'),
    ({'a_reference': 0.0}, 'A must be a positive angle, got 0.0'),
])
def test_bad_measured_signals_are_refused_with_the_quantity_named(kwargs, message):
    steer = f.sine_with_dwell(T, 100.0 * DEG, 1, START, FREQ, DWELL)
    yaw = 0.3 * f.sine_with_dwell(T - 0.1, 1.0, 1, START, FREQ, DWELL)
    args = {'a_reference': 20.0 * DEG, **kwargs}
    with pytest.raises(f.ProcessingError) as err:
        f.grade_run(T, steer, yaw, yaw, **args)
    assert str(err.value) == message


def test_no_runs_is_refused():
    with pytest.raises(f.ProcessingError) as err:
        f.grade_procedure([], 20.0 * DEG)
    assert str(err.value) == 'no sine-with-dwell runs to grade'


def test_the_grading_is_the_solver_s_one_implementation():
    from vd_solvers.standards import fmvss126 as core

    assert f.grade_run is core.grade_run and f.grade_procedure is core.grade_procedure


def test_the_steering_rate_is_averaged_over_a_tenth_of_a_second():
    """
    S7.11.4: the derivative, then a 0.1 s running average.

    Of a ramp that starts at t0 the averaged rate rises linearly from 0 at t0 - 0.05 s to
    the ramp's rate at t0 + 0.05 s: half the rate at t0, within one sample of the 50-sample
    window.
    """
    rate = 100.0 * DEG
    steer = rate * np.clip(T - 2.0, 0.0, None)
    averaged = f.steering_rate(T, steer)
    i0 = int(round(2.0 * FS))
    assert averaged[i0] == pytest.approx(0.5 * rate, abs=rate / 50)
    assert averaged[i0 + 50] == pytest.approx(rate, rel=1e-9)  # 0.1 s after: the full rate
    assert averaged[i0 - 50] == pytest.approx(0.0, abs=1e-9)


def test_an_invalid_entry_speed_is_never_graded_as_passed():
    """83.5 km/h at BOS: the run and the procedure are invalid, and the reason is named."""
    fast = _run(30.0, speed=np.full_like(T, 83.5 / 3.6))
    ok = _run(30.0, speed=np.full_like(T, 80.0 / 3.6))
    assert fast.stable_1_00 and fast.stable_1_75 and fast.responsive is None
    assert not fast.passed and fast.invalid_reasons == ('entry_speed',)
    verdict = f.grade_procedure([ok, fast], 20.0 * DEG)
    assert not verdict.passed and not verdict.valid
    assert (verdict.deciding_run, verdict.deciding_criterion) == (1, 'entry_speed')
    # the criteria are graded on the valid run only
    assert {c.name: c.runs for c in verdict.criteria}['yaw_rate_ratio_1_00'] == 1


def test_a_steer_that_is_not_the_rule_s_sine_is_invalid():
    """0.5 Hz instead of 0.7 Hz: half-period 1.0 s against 0.714 s (S7.9.1)."""
    steer = f.sine_with_dwell(T, 100.0 * DEG, 1, START, 0.5, DWELL)
    yaw = 0.3 * f.sine_with_dwell(T - 0.1, 1.0, 1, START, 0.5, DWELL)
    g = f.grade_run(T, steer, yaw, 8.0 * yaw, a_reference=20.0 * DEG)
    assert g.half_period == pytest.approx(1.0, abs=0.01)
    assert g.invalid_reasons == ('steering_profile',) and not g.passed
    good = f.grade_run(T, f.sine_with_dwell(T, 100.0 * DEG, 1, START, FREQ, DWELL),
                       0.3 * f.sine_with_dwell(T - 0.1, 1.0, 1, START, FREQ, DWELL),
                       2.4 * f.sine_with_dwell(T - 0.1, 1.0, 1, START, FREQ, DWELL),
                       a_reference=20.0 * DEG)
    assert good.half_period == pytest.approx(0.5 / FREQ, abs=0.005) and good.profile_valid


def test_a_reversed_yaw_rate_is_refused_not_graded_on_the_wrong_lobe():
    steer = f.sine_with_dwell(T, 100.0 * DEG, 1, START, FREQ, DWELL)
    yaw = 0.3 * f.sine_with_dwell(T - 0.1, 1.0, 1, START, FREQ, DWELL)
    with pytest.raises(f.ProcessingError, match='the yaw rate turns against the first steer'):
        f.grade_run(T, steer, -yaw, 8.0 * yaw, a_reference=20.0 * DEG)


def test_without_a_responsiveness_is_not_graded():
    g = _run(150.0, a_ref=None)
    assert not g.responsiveness_applies and g.responsive is None
    verdict = f.grade_procedure([g], None)
    assert {c.name: c.runs for c in verdict.criteria}['lateral_displacement'] == 0
    assert g.stable_1_00 and g.stable_1_75 and not verdict.passed


def _sis_log(direction: int = 1, kmh: float = 80.0, rate: float = 13.5 * DEG):
    truth = vb.sis_truth(direction=direction, kmh=kmh, rate=rate)
    return truth, (truth.time, truth.steering_wheel_angle, truth.lateral_acceleration,
                   truth.speed)


def test_a_of_a_slowly_increasing_steer_run_from_the_closed_form_ramp_response():
    """
    A of a linear bicycle model's SIS run (S7.6).

    Once the ramp delta = k t has run a while, the linear model answers
    a_y = G(0) k t + G'(0) k (closed form from its state space), so the steering-wheel
    angle at 0.3 g is i_s (0.3 g - G'(0) k) / G(0), to the nearest 0.1 deg.
    """
    g0, g1 = vb.lateral_acceleration_gain(80.0 / 3.6)
    k = 13.5 * DEG / vb.CAR['ratio']
    exact = vb.CAR['ratio'] * (0.3 * vb.G - g1 * k) / g0
    for direction in (1, -1):
        _, signals = _sis_log(direction)
        g = f.grade_sis(*signals)
        assert g.a_value == pytest.approx(round(exact / DEG, 1) * DEG, abs=1e-9)
        assert g.direction == direction and g.valid
        assert g.steering_rate == pytest.approx(13.5 * DEG, rel=1e-3)


@pytest.mark.parametrize('kwargs, reason', [({'kmh': 83.0}, 'sis_speed'),
                                            ({'rate': 16.0 * DEG}, 'sis_steering_rate')])
def test_an_invalid_sis_run_makes_the_procedure_invalid(kwargs, reason):
    _, signals = _sis_log(**kwargs)
    sis = f.grade_sis(*signals)
    assert sis.invalid_reasons == (reason,)
    verdict = f.grade_procedure([_run(30.0)], f.a_from_sis([sis]), [sis])
    assert not verdict.valid and not verdict.passed
    assert (verdict.deciding_criterion, verdict.deciding_sis_run) == (reason, 0)
