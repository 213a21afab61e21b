# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Realistic Racelogic VBOX 3i logs made from known signals, for the measured-data tests.

A linear single-track (bicycle) model with a second-order roll mode is driven by a known
steering-wheel angle (sine with dwell, step, slow ramp, circle) at a known speed and
integrated with RK4 at 1 kHz (the inputs are linear between the 1 kHz points, so the
integration is exact to round-off for this linear system). The truth is sampled at the
logger's 100 Hz and written as a VBOX 3i ``.vbo`` carries it:

* 41 channels: 10 standard GPS channels (no ``[channel units]`` line), five ``*_raw``
  GPS channels (none either), 26 module channels with their units in
  ``[channel units]`` -- the IMU (``X_Accel``, ``Y_Accel``, ``Z_Accel`` in g at the IMU's
  position, not roll-corrected; ``Pitch_Rate``, ``Roll_Rate``, ``YawRate`` in deg/s;
  ``IMU_Temp``), the slip module (``Yaw_Rate``, ``Slip_Angle`` positive right,
  ``Roll_Angle``, ``Pitch_Angle``, ``Lat_Vel``, ``Long_Vel``) and the steering robot and
  CAN (``Steering_Angle`` ...);
* the degree sign in Windows-1252 (one byte, 0xB0), CRLF, extra sections;
* sensor noise (IMU yaw rate 0.3 deg/s, slip-module yaw rate 3.7 deg/s), the file's
  resolution, one-sample logger glitches, a recording gap, either yaw-rate convention.

Expected answers come from the known signals (``Truth``), never from vd's own output.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
import math
from pathlib import Path

import numpy as np

from vd_solvers.results import Channel, EventOutcome, Metric

G = 9.80665
DEG = math.pi / 180.0
RATE = 100.0  # Hz, the logger
FINE = 1000.0  # Hz, the integration
#: the test car: mass, yaw inertia, CoG to front/rear axle, cornering stiffnesses, steering
#: ratio; roll gradient, roll natural frequency and damping
CAR = {'m': 1500.0, 'iz': 2500.0, 'a': 1.2, 'b': 1.5, 'cf': 80000.0, 'cr': 100000.0,
       'ratio': 16.0, 'roll_gradient': 0.5 * DEG, 'roll_hz': 1.5, 'roll_zeta': 0.6}
#: where the log "was driven": 52 deg N, 1 deg 10 min W (minutes; VBOX longitude is +west)
LAT0_MIN, LONG0_MIN = 52.0 * 60.0, 70.0
WGS84_A, WGS84_E2 = 6378137.0, 6.69437999014e-3
#: the IMU's position from the CoG in the body axes (x forward, y left, z up), m
IMU_POSITION = (0.6, -0.3, 0.25)

STANDARD = ['satellites', 'time', 'latitude', 'longitude', 'velocity kmh', 'heading',
            'height', 'vertical velocity kmh', 'long accel', 'lat accel']
RAW = ['latitude_raw', 'longitude_raw', 'velocity_raw', 'heading_raw', 'height_raw']
MODULE = [  # (name, unit as the file writes it), in header order
    ('X_Accel', 'g'), ('Y_Accel', 'g'), ('Z_Accel', 'g'), ('Pitch_Rate', '\u00b0/s'),
    ('Roll_Rate', '\u00b0/s'), ('YawRate', '\u00b0/s'), ('IMU_Temp', '\u00b0C'),
    ('Yaw_Rate', '\u00b0/s'), ('Slip_Angle', '\u00b0'), ('Roll_Angle', '\u00b0'),
    ('Pitch_Angle', '\u00b0'), ('Lat_Vel', 'km/h'), ('Long_Vel', 'km/h'),
    ('Steering_Angle', '\u00b0'), ('Steering_Rate', '\u00b0/s'), ('Steering_Torque', 'Nm'),
    ('Brake_Pressure', 'bar'), ('Throttle_Pos', '%'), ('Wheel_Speed_FL', 'km/h'),
    ('Wheel_Speed_FR', 'km/h'), ('Wheel_Speed_RL', 'km/h'), ('Wheel_Speed_RR', 'km/h'),
    ('Engine_Speed', 'rpm'), ('Gear', ''), ('Brake_Switch', ''), ('Trigger', ''),
]
SHORT = {'satellites': 'sats', 'time': 'time', 'latitude': 'lat', 'longitude': 'long',
         'velocity kmh': 'velocity', 'heading': 'heading', 'height': 'height',
         'vertical velocity kmh': 'vert-vel', 'long accel': 'longacc', 'lat accel': 'latacc'}
#: the column map a test engineer writes for these logs (the module channels vd cannot guess)
MAP = """kind: vehicle
event: {event}
logger: VBOX 3i, IMU04, slip-angle module, steering robot (synthetic test file)
vehicle: test car
columns:
  Steering_Angle: {{channel: steering_wheel_angle}}
  # the slip module's slip angle is positive to the right
  Slip_Angle: {{channel: sideslip, sign: -1}}
  Roll_Angle: {{channel: roll}}
"""


@dataclass
class Truth:
    """The known signals at the logger's rate (SI, ISO 8855), and the 1 kHz ones."""

    time: np.ndarray
    steering_wheel_angle: np.ndarray
    speed: np.ndarray
    yaw_rate: np.ndarray
    yaw_acceleration: np.ndarray
    lateral_acceleration: np.ndarray  # at the CoG, in the horizontal plane
    longitudinal_acceleration: np.ndarray
    sideslip: np.ndarray
    roll: np.ndarray
    roll_rate: np.ndarray
    roll_acceleration: np.ndarray
    yaw: np.ndarray
    x: np.ndarray
    y: np.ndarray
    fine: dict[str, np.ndarray] = field(default_factory=dict)

    def at(self, name: str, t: float) -> float:
        """Return a known signal at ``t`` from the 1 kHz truth (linear between its points)."""
        return float(np.interp(t, self.fine['time'], self.fine[name]))


def state_space(speed: float) -> tuple[np.ndarray, np.ndarray]:
    """Return A, B of the bicycle model (states v_y, r; input delta) at ``speed``."""
    c = CAR
    a11 = -(c['cf'] + c['cr']) / (c['m'] * speed)
    a12 = -speed - (c['a'] * c['cf'] - c['b'] * c['cr']) / (c['m'] * speed)
    a21 = -(c['a'] * c['cf'] - c['b'] * c['cr']) / (c['iz'] * speed)
    a22 = -(c['a'] ** 2 * c['cf'] + c['b'] ** 2 * c['cr']) / (c['iz'] * speed)
    return (np.array([[a11, a12], [a21, a22]]),
            np.array([c['cf'] / c['m'], c['a'] * c['cf'] / c['iz']]))


def lateral_acceleration_gain(speed: float) -> tuple[float, float]:
    """
    G(0) and G'(0) of road-wheel angle -> lateral acceleration at constant ``speed``.

    a_y = v_y' + u r = C x + D delta with C = A[0] + (0, u), D = B[0]; G(s) = C (sI-A)^-1 B
    + D, so G(0) = D - C A^-1 B and G'(0) = -C A^-2 B. A ramp delta = k t is answered, once
    its transient has died away, by a_y = G(0) k t + G'(0) k (closed form).
    """
    a, b = state_space(speed)
    c = a[0] + np.array([0.0, speed])
    ainv = np.linalg.inv(a)
    return float(b[0] - c @ ainv @ b), float(-c @ ainv @ ainv @ b)


def simulate(duration: float, steering: Callable[[np.ndarray], np.ndarray],
             speed: Callable[[np.ndarray], np.ndarray], steady_start: bool = False) -> Truth:
    """
    Integrate the bicycle model with its roll mode; sample the truth at 100 Hz.

    ``steady_start``: start in the steady state of the first steering angle and speed
    (v_y, r = -A^-1 B delta; roll = its gradient times v r), else straight and level.
    """
    c = CAR
    tf = np.arange(0.0, duration + 0.5 / FINE, 1.0 / FINE)
    swa = steering(tf)
    u = speed(tf)
    delta = swa / c['ratio']
    wn = 2.0 * math.pi * c['roll_hz']

    def rhs(k: float, x: np.ndarray) -> tuple[np.ndarray, float, float]:
        """State derivative at fractional index ``k`` (inputs linear between points)."""
        i = min(int(k), tf.size - 2)
        f = k - i
        uu = u[i] + f * (u[i + 1] - u[i])
        dd = delta[i] + f * (delta[i + 1] - delta[i])
        a, b = state_space(uu)
        vy_dot, r_dot = a @ x[:2] + b * dd
        ay = vy_dot + uu * x[1]
        phi_dd = wn ** 2 * (c['roll_gradient'] * ay - x[2]) - 2 * c['roll_zeta'] * wn * x[3]
        return np.array([vy_dot, r_dot, x[3], phi_dd]), ay, r_dot

    h = 1.0 / FINE
    states = np.zeros((tf.size, 4))
    ay = np.zeros(tf.size)
    r_dot = np.zeros(tf.size)
    phi_dd = np.zeros(tf.size)
    x = np.zeros(4)
    if steady_start:
        a0, b0 = state_space(float(u[0]))
        x[:2] = -np.linalg.solve(a0, b0 * delta[0])
        x[2] = c['roll_gradient'] * float(u[0]) * x[1]
    for i in range(tf.size):
        states[i] = x
        d, ay[i], r_dot[i] = rhs(i, x)
        phi_dd[i] = d[3]
        if i == tf.size - 1:
            break
        k1 = d
        k2 = rhs(i + 0.5, x + 0.5 * h * k1)[0]
        k3 = rhs(i + 0.5, x + 0.5 * h * k2)[0]
        k4 = rhs(i + 1.0, x + h * k3)[0]
        x = x + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    vy, r, phi, p = states.T
    yaw = np.concatenate(([0.0], np.cumsum(0.5 * (r[1:] + r[:-1]) * h)))
    vx_e = u * np.cos(yaw) - vy * np.sin(yaw)
    vy_n = u * np.sin(yaw) + vy * np.cos(yaw)
    xe = np.concatenate(([0.0], np.cumsum(0.5 * (vx_e[1:] + vx_e[:-1]) * h)))
    yn = np.concatenate(([0.0], np.cumsum(0.5 * (vy_n[1:] + vy_n[:-1]) * h)))
    ax = np.gradient(u, tf)
    fine = {'time': tf, 'steering_wheel_angle': swa, 'speed': u, 'yaw_rate': r,
            'yaw_acceleration': r_dot, 'lateral_acceleration': ay,
            'longitudinal_acceleration': ax, 'sideslip': vy / u, 'roll': phi,
            'roll_rate': p, 'roll_acceleration': phi_dd, 'yaw': yaw, 'x': xe, 'y': yn}
    pick = slice(None, None, int(round(FINE / RATE)))
    return Truth(**{k: v[pick] for k, v in fine.items()}, fine=fine)


def sine_with_dwell(amplitude: float, direction: int, start: float) -> Callable:
    """Return the rule's steer (0.7 Hz, 500 ms dwell at the second peak), rad."""
    w, period, dwell = 2.0 * math.pi * 0.7, 1.0 / 0.7, 0.5

    def steer(t: np.ndarray) -> np.ndarray:
        tau = t - start
        out = np.zeros_like(t)
        a = (tau >= 0) & (tau < 0.75 * period)
        out[a] = np.sin(w * tau[a])
        out[(tau >= 0.75 * period) & (tau < 0.75 * period + dwell)] = -1.0
        e = (tau >= 0.75 * period + dwell) & (tau < period + dwell)
        out[e] = np.sin(w * (tau[e] - dwell))
        return direction * amplitude * out
    return steer


def ramp(rate: float, start: float, stop_angle: float, ramp_time: float = 0.0) -> Callable:
    """Return a steer from 0 at ``start`` at ``rate`` (rad/s) to ``stop_angle``, held."""
    def steer(t: np.ndarray) -> np.ndarray:
        if ramp_time > 0.0:
            return stop_angle * np.clip((t - start) / ramp_time, 0.0, 1.0)
        return np.sign(stop_angle) * np.clip((t - start) * rate, 0.0, abs(stop_angle))
    return steer


def constant(value: float) -> Callable:
    return lambda t: np.full_like(t, value)


def coasting(entry: float, start: float, deceleration: float = 0.25) -> Callable:
    """Speed held at ``entry`` until ``start``, then coasting down."""
    return lambda t: entry - deceleration * np.clip(t - start, 0.0, None)


@dataclass
class Log:
    """How the truth is written: conventions, noise, glitches, a gap."""

    yaw_iso: bool = True  # False: both yaw-rate channels positive clockwise
    glitches: Sequence[tuple[float, str, float]] = ()  # (time, channel name, value as written)
    gap: tuple[float, float] | None = None  # (start time, length) without samples, s
    noise: bool = True
    seed: int = 22
    event_comment: str = 'sine with dwell'
    start_utc: float = 10 * 3600 + 14 * 60 + 5.0  # s of the day


def imu_lateral_acceleration(truth: Truth, position: Sequence[float] = IMU_POSITION
                             ) -> np.ndarray:
    """
    Return what a body-fixed accelerometer at ``position`` reads along its y axis, m/s^2.

    The specific force at the CoG in the body axes rolled by phi: a_y cos(phi) + g sin(phi)
    (horizontal a_y, no vertical acceleration); moved to the IMU by the rigid-body relation
    a_P = a_G + w' x rho + w x (w x rho) with w = (p, 0, r): + r' x_P - p' z_P - (p^2 + r^2)
    y_P.
    """
    xp, yp, zp = position
    phi = truth.roll
    at_cog = truth.lateral_acceleration * np.cos(phi) + G * np.sin(phi)
    return (at_cog + truth.yaw_acceleration * xp - truth.roll_acceleration * zp
            - (truth.roll_rate ** 2 + truth.yaw_rate ** 2) * yp)


def rows(truth: Truth, log: Log) -> tuple[list[str], list[float]]:
    """Return the [data] rows and each row's time (s from the first sample)."""
    rng = np.random.default_rng(log.seed)
    n = truth.time.size

    def noise(std: float) -> np.ndarray:
        return rng.normal(0.0, std, n) if log.noise else np.zeros(n)

    phi0 = math.radians(LAT0_MIN / 60.0)
    s2 = math.sin(phi0) ** 2
    r_n = WGS84_A / math.sqrt(1.0 - WGS84_E2 * s2)
    r_m = WGS84_A * (1.0 - WGS84_E2) / (1.0 - WGS84_E2 * s2) ** 1.5
    lat = LAT0_MIN + np.degrees(truth.y / r_m) * 60.0
    long_w = LONG0_MIN - np.degrees(truth.x / (r_n * math.cos(phi0))) * 60.0
    heading = np.mod(90.0 - np.degrees(truth.yaw), 360.0)
    kmh = truth.speed * 3.6
    yaw_sign = 1.0 if log.yaw_iso else -1.0
    gps_ay = truth.speed * truth.yaw_rate / G  # the logger's GPS-derived lateral acceleration
    values = {
        'satellites': np.full(n, 14.0), 'time': truth.time,
        'latitude': lat, 'longitude': long_w, 'velocity kmh': kmh + noise(0.05),
        'heading': heading, 'height': np.full(n, 85.0), 'vertical velocity kmh': noise(0.05),
        'long accel': truth.longitudinal_acceleration / G + noise(0.01),
        'lat accel': gps_ay + noise(0.01),
        'latitude_raw': lat, 'longitude_raw': long_w, 'velocity_raw': kmh + noise(0.1),
        'heading_raw': heading, 'height_raw': np.full(n, 85.0) + noise(0.2),
        'X_Accel': truth.longitudinal_acceleration / G + noise(0.005),
        'Y_Accel': imu_lateral_acceleration(truth) / G + noise(0.005),
        'Z_Accel': (G * np.cos(truth.roll) - truth.lateral_acceleration * np.sin(truth.roll))
        / G + noise(0.005),
        'Pitch_Rate': noise(0.3), 'Roll_Rate': np.degrees(truth.roll_rate) + noise(0.3),
        'YawRate': yaw_sign * np.degrees(truth.yaw_rate) + noise(0.3),
        'IMU_Temp': np.full(n, 31.5),
        'Yaw_Rate': yaw_sign * np.degrees(truth.yaw_rate) + noise(3.7),
        'Slip_Angle': -np.degrees(truth.sideslip) + noise(0.05),
        'Roll_Angle': np.degrees(truth.roll) + noise(0.02), 'Pitch_Angle': noise(0.02),
        'Lat_Vel': truth.speed * truth.sideslip * 3.6 + noise(0.05),
        'Long_Vel': kmh + noise(0.05),
        'Steering_Angle': np.degrees(truth.steering_wheel_angle) + noise(0.05),
        'Steering_Rate': np.degrees(np.gradient(truth.steering_wheel_angle, truth.time)),
        'Steering_Torque': 0.05 * np.degrees(truth.steering_wheel_angle),
        'Brake_Pressure': np.zeros(n), 'Throttle_Pos': np.full(n, 12.0),
        'Wheel_Speed_FL': kmh, 'Wheel_Speed_FR': kmh, 'Wheel_Speed_RL': kmh,
        'Wheel_Speed_RR': kmh, 'Engine_Speed': kmh * 30.0, 'Gear': np.full(n, 5.0),
        'Brake_Switch': np.zeros(n), 'Trigger': np.zeros(n),
    }
    for when, name, value in log.glitches:
        values[name][int(round(when * RATE))] = value
    keep = np.ones(n, dtype=bool)
    if log.gap is not None:
        start, length = log.gap
        keep = (truth.time < start - 1e-9) | (truth.time >= start + length - 1e-9)
    out, times = [], []
    for i in np.flatnonzero(keep):
        utc = log.start_utc + truth.time[i]
        hh, rem = divmod(utc, 3600.0)
        mm, ss = divmod(rem, 60.0)
        v = {k: float(x[i]) for k, x in values.items()}
        fields = [f"{int(v['satellites']):03d}", f'{int(hh):02d}{int(mm):02d}{ss:05.2f}',
                  f"{v['latitude']:+013.7f}", f"{v['longitude']:+013.7f}",
                  f"{v['velocity kmh']:07.3f}", f"{v['heading']:06.2f}",
                  f"{v['height']:+09.2f}", f"{v['vertical velocity kmh']:+08.3f}",
                  f"{v['long accel']:+06.3f}", f"{v['lat accel']:+06.3f}",
                  f"{v['latitude_raw']:+013.7f}", f"{v['longitude_raw']:+013.7f}",
                  f"{v['velocity_raw']:07.3f}", f"{v['heading_raw']:06.2f}",
                  f"{v['height_raw']:+09.2f}"]
        fields += [f'{v[name]:+.6E}' for name, _ in MODULE]
        out.append(' '.join(fields))
        times.append(float(truth.time[i]))
    return out, times


def vbo_text(truth: Truth, log: Log) -> tuple[str, list[float], int]:
    """Return the file's text, the times of its rows and the file line of the first row."""
    names = STANDARD[:] + RAW + [n for n, _ in MODULE]
    columns = [SHORT.get(n, n) for n in names]
    head = ['File created on 12/05/2026 at 10:14:05', '', '[header]', *names, '',
            '[channel units]', *(unit for _, unit in MODULE), '', '[comments]',
            'SYNTHETIC TEST FILE made for the vd tests, not a measurement: linear single-track '
            'model with a roll mode',
            f'(c) Racelogic VBOX 3i; {log.event_comment}', 'Log Rate (Hz) : 100.00',
            'Software Version : 2.6.1', '', '[module information]',
            'IMU04 s/n 012345; RLVBSS slip module s/n 004411; steering robot via CAN', '',
            '[avifile]', 'none', '', '[laptiming]', '', '[column names]', ' '.join(columns),
            '', '[data]']
    data, times = rows(truth, log)
    return '\r\n'.join(head + data) + '\r\n', times, len(head) + 1


def write(path: Path, truth: Truth, log: Log | None = None) -> tuple[Path, list[float], int]:
    """Write the log (Windows-1252: the degree sign is one byte); return path, times, line."""
    text, times, first = vbo_text(truth, log or Log())
    path.write_bytes(text.encode('cp1252'))
    return path, times, first


def write_map(path: Path, event: str) -> Path:
    path.write_text(MAP.format(event=event), encoding='utf-8')
    return path


def swd_truth(amplitude: float = 180.0 * DEG, direction: int = 1, entry_kmh: float = 80.0,
              start: float = 3.0, duration: float = 12.0) -> Truth:
    """Simulate a sine-with-dwell run: from ``entry_kmh``, coasting from the steer on."""
    return simulate(duration, sine_with_dwell(amplitude, direction, start),
                    coasting(entry_kmh / 3.6, start))


def sis_truth(direction: int = 1, kmh: float = 80.0, rate: float = 13.5 * DEG,
              start: float = 2.0) -> Truth:
    """Simulate a slowly-increasing-steer run at constant speed, up to about 0.55 g."""
    g0, _ = lateral_acceleration_gain(kmh / 3.6)
    stop = 0.55 * G / g0 * CAR['ratio']
    return simulate(start + stop / rate + 1.0, ramp(rate, start, direction * stop),
                    constant(kmh / 3.6))


def step_truth(angle: float = 40.0 * DEG, kmh: float = 100.0, ramp_time: float = 0.1,
               start: float = 2.0, duration: float = 8.0) -> Truth:
    """Simulate an ISO 7401 step: at ``kmh``, a ramp of ``ramp_time`` to ``angle``, held."""
    return simulate(duration, ramp(0.0, start, angle, ramp_time), constant(kmh / 3.6))


def circle_truth(radius: float = 40.0, a_start: float = 0.5, a_end: float = 4.5,
                 duration: float = 60.0) -> Truth:
    """
    Simulate a constant-radius run with slowly increasing speed (quasi-steady).

    The speed rises so that v^2 / R goes from ``a_start`` to ``a_end`` linearly in time; the
    steering wheel follows the steady-state angle of the bicycle model for the radius,
    delta = L / R + K a_y (K from the model's cornering stiffnesses), times the ratio.
    """
    c = CAR
    wheelbase = c['a'] + c['b']
    k = c['m'] / wheelbase * (c['b'] / c['cf'] - c['a'] / c['cr'])

    def accel(t):
        return a_start + (a_end - a_start) * np.clip(t / duration, 0.0, 1.0)

    return simulate(duration, lambda t: c['ratio'] * (wheelbase / radius + k * accel(t)),
                    lambda t: np.sqrt(accel(t) * radius), steady_start=True)


def swd_procedure(runs: Sequence[tuple[int, float]], a_reference: float,
                  entry_kmh: Sequence[float] | None = None, start: float = 1.5):
    """
    Return a simulated sine-with-dwell procedure in the vehicle solver's layout.

    ``runs``: (direction, amplitude) of each run, simulated by this module's model;
    channels ``series_<signal>_<run>`` at 50 Hz over ``series_time``, ``run_amplitude``,
    ``run_direction``, ``run_entry_speed``, the first run's signals as the main channels,
    metric ``a_reference`` (an EventOutcome of model ``vehicle``).
    """
    truths = [swd_truth(amplitude=amp, direction=d, start=start, duration=start + 5.0)
              for d, amp in runs]
    pick = slice(None, None, 2)
    units = {'steering_wheel_angle': 'rad', 'yaw_rate': 'rad/s',
             'lateral_acceleration': 'm/s^2', 'roll': 'rad'}
    channels = {'time': Channel('s', truths[0].time),
                'series_time': Channel('s', truths[0].time[pick]),
                'run_amplitude': Channel('rad', np.array([a for _, a in runs])),
                'run_direction': Channel('-', np.array([float(d) for d, _ in runs])),
                'run_entry_speed': Channel('m/s', np.array(entry_kmh or [80.0] * len(runs))
                                           / 3.6)}
    for k, truth in enumerate(truths):
        for name, unit in units.items():
            channels[f'series_{name}_{k + 1:02d}'] = Channel(unit, getattr(truth, name)[pick])
    for name, unit in units.items():
        channels[name] = Channel(unit, getattr(truths[0], name))
    return EventOutcome(event='sine_with_dwell', configuration='baseline', model='vehicle',
                        fidelity='rigid', axle='', data_hash='0' * 64,
                        metrics={'a_reference': Metric(a_reference, 'rad'),
                                 'gvwr': Metric(1800.0, 'kg')}, channels=channels)


def understeer_gradient() -> float:
    """K of the test car, rad/(m/s^2) (Gillespie eq. 6.15: W_f/C_f - W_r/C_r over g)."""
    c = CAR
    return c['m'] / (c['a'] + c['b']) * (c['b'] / c['cf'] - c['a'] / c['cr'])


__all__ = ['Truth', 'Log', 'simulate', 'write', 'write_map', 'swd_truth', 'sis_truth',
           'swd_procedure',
           'step_truth', 'circle_truth', 'imu_lateral_acceleration', 'CAR', 'IMU_POSITION',
           'lateral_acceleration_gain', 'understeer_gradient', 'G', 'DEG', 'MODULE', 'MAP']
