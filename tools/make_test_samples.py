# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Make the sample measured files of src/vd_events/samples (made for the tests, not measured).

Run with ``tools/env.sh python tools/make_test_samples.py``. Every file says in itself
that it is synthetic: it is vd's own model output on the sample sedan ``baseline`` written
in the layout of a rig or logger, with sensor noise and the logger's resolution, so the
tests can check that an import and a replay recover what went in.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from vd_data_server.paths import default_master
from vd_data_server.study import load_study

OUT = Path(__file__).resolve().parents[1] / 'src' / 'vd_events' / 'samples'
G = 9.80665
DEG = 180.0 / math.pi
LABEL = ('SYNTHETIC TEST FILE made for the vd tests, not a measurement: vd full-vehicle '
         'model, sample sedan baseline')
#: where the synthetic log "was driven": 52 deg N, 1 deg 10 min W (minutes, long +west)
LAT0_MIN, LONG0_MIN = 52.0 * 60.0, 70.0
WGS84_A, WGS84_E2 = 6378137.0, 6.69437999014e-3


def sine_steer_log(config):
    """Full vehicle at 80 km/h, 1 s straight, two periods of a 0.5 Hz 40 deg sine."""
    from vd_solvers.vehicle.drivers import OpenLoopSteering, SpeedController
    from vd_solvers.vehicle.model import VehicleModel
    from vd_solvers.vehicle.simulation import simulate

    model = VehicleModel(config, 'rigid')
    speed = 80.0 / 3.6
    amplitude = math.radians(40.0)

    def swa(t: float) -> float:
        return amplitude * math.sin(math.pi * (t - 1.0)) if 1.0 <= t <= 5.0 else 0.0

    _, r_e = model.tire_radii(model.static_loads())
    trace = simulate(model, OpenLoopSteering(swa),
                     SpeedController(lambda t: speed, model.total_mass, float(np.mean(r_e))),
                     8.0, event='sine_steer', initial_speed=speed, record_every=10)
    return trace.channels()  # 5 ms steps, every 10th: 20 Hz


def write_vbo(ch) -> None:
    rng = np.random.default_rng(126)
    n = len(ch['time'])
    phi0 = math.radians(LAT0_MIN / 60.0)
    s2 = math.sin(phi0) ** 2
    r_n = WGS84_A / math.sqrt(1.0 - WGS84_E2 * s2)
    r_m = WGS84_A * (1.0 - WGS84_E2) / (1.0 - WGS84_E2 * s2) ** 1.5
    x, y = ch['x'], ch['y']
    lat = LAT0_MIN + np.degrees(y / r_m) * 60.0
    long_w = LONG0_MIN - np.degrees(x / (r_n * math.cos(phi0))) * 60.0
    heading = np.mod(90.0 - np.degrees(ch['yaw']), 360.0)
    t_utc = 10 * 3600 + 14 * 60 + 5.0 + ch['time']
    kmh = ch['speed'] * 3.6 + rng.normal(0.0, 0.05, n)
    ax = ch['longitudinal_acceleration'] / G + rng.normal(0.0, 0.005, n)
    ay = ch['lateral_acceleration'] / G + rng.normal(0.0, 0.005, n)
    yaw_rate = np.degrees(ch['yaw_rate']) + rng.normal(0.0, 0.1, n)
    steer = np.degrees(ch['steering_wheel_angle']) + rng.normal(0.0, 0.1, n)
    slip = -np.degrees(ch['sideslip'])  # this logger's slip angle: positive to the right
    roll = np.degrees(ch['roll'])
    lines = ['File created on 20/11/2026 at 10:14:05', '', '[header]', 'satellites', 'time',
             'latitude', 'longitude', 'velocity kmh', 'heading', 'height',
             'vertical velocity kmh', 'long accel', 'lat accel', 'Yaw Rate', 'Steering Angle',
             'Slip Angle', 'Roll Angle', '', '[channel units]', '\u00b0/s', 'deg', 'deg', 'deg',
             '', '[comments]', LABEL, 'open-loop sine steer, 0.5 Hz, 40 deg, 80 km/h',
             'VBOX 3i layout; Log Rate (Hz) : 20.00', '', '[module information]',
             'IMU04 (synthetic)', '', '[avifile]', 'none', '', '[column names]',
             'sats time lat long velocity heading height vert-vel longacc latacc yaw_rate '
             'steer slip roll', '', '[data]']
    for i in range(n):
        hh, rem = divmod(t_utc[i], 3600.0)
        mm, ss = divmod(rem, 60.0)
        lines.append(
            f'137 {int(hh):02d}{int(mm):02d}{ss:05.2f} {lat[i]:+013.7f} {long_w[i]:+013.7f} '
            f'{kmh[i]:07.3f} {heading[i]:06.2f} +00085.00 +000.000 {ax[i]:+.3f} {ay[i]:+.3f} '
            f'{yaw_rate[i]:+.6E} {steer[i]:+.6E} {slip[i]:+.6E} {roll[i]:+.6E}')
    (OUT / 'vbox_sine_steer.vbo').write_bytes(('\r\n'.join(lines) + '\r\n').encode('cp1252'))


def write_vehicle_csv(ch) -> None:
    rng = np.random.default_rng(4138)
    keep = slice(0, None, 2)  # 10 Hz
    rows = ['# ' + LABEL + ' (the same run as vbox_sine_steer.vbo, 10 Hz)',
            'Time,Speed,SWA,YawRate,AccY,Sideslip']
    for t, v, d, r, a, b in zip(ch['time'][keep], ch['speed'][keep],
                                ch['steering_wheel_angle'][keep], ch['yaw_rate'][keep],
                                ch['lateral_acceleration'][keep], ch['sideslip'][keep]):
        rows.append(f'{t:.3f},{v * 3.6 + rng.normal(0, 0.05):.3f},{d * DEG:.3f},'
                    f'{r * DEG:.3f},{a / G:.4f},{b * DEG:.3f}')
    (OUT / 'vehicle_log.csv').write_text('\n'.join(rows) + '\n')


def write_kc(config) -> None:
    from vd_solvers.kc.from_config import run_kc_event

    rng = np.random.default_rng(8855)
    bounce = run_kc_event(config, 'parallel_wheel_travel', 'front', ['steps=41']).channels
    rows = ['Wheel Travel LH,Wheel Travel RH,Toe LH,Toe RH,Camber LH,Camber RH,'
            'Vertical Force LH,Vertical Force RH,Comment',
            'mm,mm,deg,deg,deg,deg,N,N,']
    for i in range(len(bounce['wheel_travel_left'].values)):
        def v(name, scale, noise):
            return bounce[name].values[i] * scale + rng.normal(0.0, noise)
        # this rig's toe is positive toe-out (the map's sign -1 turns it into ISO toe-in)
        rows.append(f"{v('wheel_travel_left', 1e3, 0.01):.3f},"
                    f"{v('wheel_travel_right', 1e3, 0.01):.3f},"
                    f"{-v('toe_left', DEG, 0.002):.4f},{-v('toe_right', DEG, 0.002):.4f},"
                    f"{v('camber_left', DEG, 0.002):.4f},{v('camber_right', DEG, 0.002):.4f},"
                    f"{v('pad_force_left', 1.0, 2.0):.1f},{v('pad_force_right', 1.0, 2.0):.1f},"
                    + ('synthetic' if i == 0 else ''))
    (OUT / 'kc_spmm_bounce_front.csv').write_text(
        '\n'.join(rows) + '\n')
    lateral = run_kc_event(config, 'lateral_force', 'front', ['steps=21']).channels
    rows = ['# ' + LABEL.replace('full-vehicle', 'K&C') + ', lateral force compliance front',
            'Fy_N          toe_L_deg    toe_R_deg    camber_L_deg  camber_R_deg']
    for i in range(len(lateral['applied_force'].values)):
        rows.append('  '.join(f'{x:+12.5f}' for x in (
            lateral['applied_force'].values[i] + rng.normal(0.0, 1.0),
            lateral['toe_left'].values[i] * DEG + rng.normal(0.0, 0.001),
            lateral['toe_right'].values[i] * DEG + rng.normal(0.0, 0.001),
            lateral['camber_left'].values[i] * DEG + rng.normal(0.0, 0.001),
            lateral['camber_right'].values[i] * DEG + rng.normal(0.0, 0.001))))
    (OUT / 'kc_abd_lateral_front.txt').write_text('\n'.join(rows) + '\n')


def main() -> None:
    config = load_study(default_master()).configurations['baseline']
    OUT.mkdir(parents=True, exist_ok=True)
    write_kc(config)
    ch = sine_steer_log(config)
    write_vbo(ch)
    write_vehicle_csv(ch)


if __name__ == '__main__':
    main()
