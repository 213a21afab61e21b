"""
Sine-with-dwell processing (FMVSS 126) on synthetic signals whose answers are known
in closed form: a filtered pure sine, the analytic steering profile, a first-order yaw
decay, a smooth lateral acceleration with an exact double integral, a linear SIS.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from vd_events import fmvss126 as f

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
    gain = 0.4  # m/s^2 of lateral acceleration per degree of steering-wheel angle
    steer = np.linspace(0.0, 40.0 * DEG, 400)
    runs = [(steer, steer / DEG * gain), (-steer, -steer / DEG * gain * 1.02)]
    expected = np.mean([0.3 * 9.80665 / gain, 0.3 * 9.80665 / (gain * 1.02)])
    assert f.amplitude_from_sis(runs) == pytest.approx(round(expected, 1) * DEG, abs=1e-12)


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
     'time must be strictly increasing with a uniform step'),
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
