# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Suspension maps of the full vehicle, taken from the K&C results of the same configuration.

Every characteristic comes from a K&C event of the same configuration, data hash and
fidelity (``kc.cache.kc_result``: computed on demand, cached by hash), and says which
(:attr:`SuspensionMaps.provenance`):

* ``parallel_wheel_travel``: per wheel vs its own travel z (m, + bump): the vertical
  wheel force of spring, bump/rebound stops and bushings, toe, camber and the damper's
  motion ratio -d(damper length)/dz;
* ``opposite_wheel_travel`` with and without the anti-roll bar: the bar's wheel force vs
  half the travel difference (z_left - z_right)/2; and the roll correction of toe and
  camber: the opposite-travel event's toe and camber less the parallel-travel map's at
  the same travel, vs the half travel difference. A wheel's toe is then the parallel map
  at its own travel plus that correction, which is zero in heave and makes pure roll
  reproduce the K&C roll steer and roll camber: what the bar's load and the bushings do
  to the wheels in roll (the sample sedan's front: bump steer -0.122 rad/m per wheel in
  parallel travel, +0.004 in opposite travel with the bar);
* ``lateral_force``: compliance steer and camber per newton of lateral force, and the
  force-based jacking coefficient d(pad force)/dFy (the force roll centre);
* ``aligning_torque``: compliance steer per N*m of moment about +z at the contact point
  (the exact rate at design, the number the K&C metric
  ``aligning_torque_compliance_steer`` and the understeer budget use);
* ``longitudinal_force``: compliance steer per newton (braking and traction sides) and
  the jacking coefficients d(pad force)/dFx of both sides (anti-dive/-lift/-squat);
* ``steering`` (front): road-wheel steer angle of each wheel vs steering-wheel angle
  (steering ratio and Ackermann).

The K&C rig carries the whole corner load on its pads without gravity (the spring
preload is trimmed to the static wheel load). On the road the unsprung weight rests
on the tire directly, so the wheel-force map used here is the pad force minus the
corner's unsprung weight: the body then sits at design height under static loads.

Wheel order everywhere: FL, FR, RL, RR. Tables are resampled on a uniform grid so the
per-step look-up is one vectorised linear interpolation (linear extrapolation outside).
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from vd_data_server.model import Configuration
from vd_solvers.compiled import jit
from vd_solvers.constants import STANDARD_GRAVITY
from vd_solvers.errors import SolverError
from vd_solvers.kc.cache import NO_BAR, kc_model, kc_result
from vd_solvers.kc.metrics import FORCE_WINDOW, rate, slope_at
from vd_solvers.kc.steering_map import steering_map

#: wheels in the order of every per-wheel array
WHEELS = ('front_left', 'front_right', 'rear_left', 'rear_right')
#: K&C steps per sweep used for the maps (the map resolution)
KC_STEPS = 41
#: points of the uniform travel grid the maps are resampled on
GRID_POINTS = 81
#: rows of :attr:`SuspensionMaps.travel_table`
TRAVEL_ROWS = ('wheel_force', 'toe', 'camber', 'motion_ratio')


@dataclass(frozen=True)
class SuspensionMaps:
    """Per-wheel characteristics (wheel order FL, FR, RL, RR; SI)."""

    travel0: np.ndarray  # (4,) m, first grid point
    travel_step: np.ndarray  # (4,) m, grid spacing
    travel_table: np.ndarray  # (len(TRAVEL_ROWS), 4, GRID_POINTS)
    arb0: np.ndarray  # (4,) m, first grid point of the half travel difference
    arb_step: np.ndarray  # (4,) m
    arb_table: np.ndarray  # (4, GRID_POINTS) N, bar force on the wheel (upward positive is -)
    roll0: np.ndarray  # (4,) m, first grid point of the half travel difference
    roll_step: np.ndarray  # (4,) m
    roll_table: np.ndarray  # (2, 4, GRID_POINTS) rad, toe and camber correction in roll
    compliance_steer_y: np.ndarray  # (4,) rad/N, toe change per N of lateral force (+y)
    compliance_camber_y: np.ndarray  # (4,) rad/N
    compliance_steer_mz: np.ndarray  # (4,) rad/(N*m), toe change per N*m about +z
    compliance_steer_x: np.ndarray  # (2, 4) rad/N, [braking, traction] toe per N of Fx
    jacking_y: np.ndarray  # (4,) -, d(pad force)/dFy
    jacking_x: np.ndarray  # (2, 4) -, [braking, traction] d(pad force)/dFx
    damper_x: tuple[np.ndarray, np.ndarray]  # front, rear curve velocities, m/s
    damper_y: tuple[np.ndarray, np.ndarray]  # N, positive resisting compression
    steer_swa: np.ndarray  # (n,) rad steering-wheel angle, increasing
    steer_angle: np.ndarray  # (n, 2) rad road-wheel angle FL, FR relative to straight ahead
    steering_ratio: float  # -, at the centre
    provenance: Mapping[str, str]

    def travel(self, z: np.ndarray) -> np.ndarray:
        """(len(TRAVEL_ROWS), 4) values at wheel travels ``z`` (4,)."""
        return grid_lookup(self.travel_table, self.travel0, self.travel_step, _vector(z))

    def arb(self, z: np.ndarray) -> np.ndarray:
        """(4,) anti-roll-bar force on each wheel, N (upward on the wheel positive)."""
        return grid_lookup(self.arb_table.reshape(1, 4, GRID_POINTS), self.arb0, self.arb_step,
                           half_difference(_vector(z)))[0]

    def roll(self, z: np.ndarray) -> np.ndarray:
        """(2, 4) toe and camber correction in roll at wheel travels ``z`` (module doc)."""
        return grid_lookup(self.roll_table, self.roll0, self.roll_step,
                           half_difference(_vector(z)))

    def road_wheel_angles(self, swa: float) -> tuple[float, float]:
        """Steer angles (rad, + left) of FL and FR at steering-wheel angle ``swa`` (rad)."""
        return (float(np.interp(swa, self.steer_swa, self.steer_angle[:, 0])),
                float(np.interp(swa, self.steer_swa, self.steer_angle[:, 1])))


def _vector(z: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(z, dtype=float)


@jit
def grid_lookup(table: np.ndarray, x0: np.ndarray, step: np.ndarray,
                x: np.ndarray) -> np.ndarray:
    """
    Linear interpolation of per-wheel tables on uniform grids (linear extrapolation outside).

    ``table`` (rows, 4, GRID_POINTS), grid of wheel w: ``x0[w] + step[w] * k``; ``x`` (4,).
    Returns (rows, 4).
    """
    rows, wheels, points = table.shape
    out = np.empty((rows, wheels))
    for w in range(wheels):
        u = (x[w] - x0[w]) / step[w]
        i = min(max(int(np.floor(u)), 0), points - 2)
        frac = u - i
        for r in range(rows):
            lo = table[r, w, i]
            out[r, w] = lo + frac * (table[r, w, i + 1] - lo)
    return out


@jit
def half_difference(z: np.ndarray) -> np.ndarray:
    """(4,) half the travel difference of each wheel to the other of its axle, (z_w - z_o)/2."""
    return 0.5 * np.array([z[0] - z[1], z[1] - z[0], z[2] - z[3], z[3] - z[2]])


def _uniform(x: np.ndarray, y: np.ndarray, what: str) -> tuple[float, float, np.ndarray]:
    order = np.argsort(x)
    x, y = x[order], y[order]
    if np.any(np.diff(x) <= 0.0):
        raise SolverError(f'{what}: the K&C sweep is not monotonic')
    grid = np.linspace(x[0], x[-1], GRID_POINTS)
    return float(grid[0]), float(grid[1] - grid[0]), np.interp(grid, x, y)


def _one_sided(x: np.ndarray, y: np.ndarray, sign: float) -> float:
    """Slope of y(x) on one side of x = 0 (sign -1: x <= 0, +1: x >= 0)."""
    mask = sign * x >= -1e-9
    return slope_at(x[mask], y[mask], 0.0, FORCE_WINDOW)


def suspension_maps(config: Configuration, fidelity: str = 'rigid') -> SuspensionMaps:
    """Return the maps of both axles of ``config`` (K&C results on demand, module doc)."""
    g = STANDARD_GRAVITY
    mass = config.group('mass')
    tag = f'{fidelity}, data hash {config.data_hash}'
    prov: dict[str, str] = {}
    t0, ts, table = np.zeros(4), np.zeros(4), np.zeros((len(TRAVEL_ROWS), 4, GRID_POINTS))
    a0, as_, arb = np.zeros(4), np.ones(4), np.zeros((4, GRID_POINTS))
    r0, rs, roll = np.zeros(4), np.ones(4), np.zeros((2, 4, GRID_POINTS))
    c_sy, c_cy, j_y, c_mz = np.zeros(4), np.zeros(4), np.zeros(4), np.zeros(4)
    c_sx, j_x = np.zeros((2, 4)), np.zeros((2, 4))
    dampers_x, dampers_y = [], []
    for k, axle in enumerate(('front', 'rear')):
        label = f"configuration '{config.name}', {axle} axle"
        m_u = mass.scalar(f'unsprung_mass_{axle}')
        par = kc_result(config, axle, 'parallel_wheel_travel', fidelity, steps=KC_STEPS)
        ch = par.channels
        for s in range(2):
            w = 2 * k + s
            z = ch['wheel_travel'][:, s]
            rows = (ch['pad_force'][:, s] - m_u * g, ch['toe'][:, s], ch['camber'][:, s],
                    -np.gradient(ch['damper_length'][:, s], z))
            for r, y in enumerate(rows):
                t0[w], ts[w], table[r, w] = _uniform(z, y, f'{label} parallel_wheel_travel')
        prov['wheel_force'] = prov.get('wheel_force', '') + (
            f'{axle}: K&C parallel_wheel_travel pad force - unsprung weight ({tag}); ')
        for key in ('toe', 'camber', 'damper_motion_ratio'):
            prov[key] = prov.get(key, '') + f'{axle}: K&C parallel_wheel_travel ({tag}); '
        inp = kc_model(config, axle, fidelity).inp
        if inp.damper is None:
            raise SolverError(f'{label}: the full vehicle needs a damper')
        dampers_x.append(np.asarray(inp.damper.curve.x, dtype=float))
        dampers_y.append(np.asarray(inp.damper.curve.y, dtype=float))
        damper_file = config.group(f'{axle}_damper').file
        prov['damper'] = prov.get('damper', '') + f'{axle}: {damper_file}; '
        opp = kc_result(config, axle, 'opposite_wheel_travel', fidelity, steps=KC_STEPS)
        for s in range(2):
            zo = opp.channels['wheel_travel']
            half_o = 0.5 * (zo[:, s] - zo[:, 1 - s])
            w = 2 * k + s
            for row, key in enumerate(('toe', 'camber')):
                parallel = np.interp(zo[:, s], t0[w] + ts[w] * np.arange(GRID_POINTS),
                                     table[TRAVEL_ROWS.index(key), w])
                r0[w], rs[w], roll[row, w] = _uniform(half_o, opp.channels[key][:, s] - parallel,
                                                      f'{label} opposite_wheel_travel')
        for key in ('roll_toe', 'roll_camber'):
            prov[key] = prov.get(key, '') + (
                f'{axle}: K&C opposite_wheel_travel - parallel_wheel_travel ({tag}); ')
        if inp.stabilizer is not None:
            bare = kc_result(config, axle, NO_BAR, fidelity, steps=KC_STEPS)
            for s in range(2):
                zo, zb = opp.channels['wheel_travel'], bare.channels['wheel_travel']
                half_o = 0.5 * (zo[:, s] - zo[:, 1 - s])
                half_b = 0.5 * (zb[:, s] - zb[:, 1 - s])
                # pad force of the bare axle at the bar run's travels
                order = np.argsort(half_b)
                bare_force = np.interp(half_o, half_b[order], bare.channels['pad_force'][order, s])
                a0[2 * k + s], as_[2 * k + s], arb[2 * k + s] = _uniform(
                    half_o, opp.channels['pad_force'][:, s] - bare_force,
                    f'{label} opposite_wheel_travel')
            prov['anti_roll_bar'] = prov.get('anti_roll_bar', '') + (
                f'{axle}: K&C opposite_wheel_travel with - without bar ({tag}); ')
        else:
            prov['anti_roll_bar'] = prov.get('anti_roll_bar', '') + f'{axle}: no anti-roll bar; '
            a0[2 * k:2 * k + 2], as_[2 * k:2 * k + 2] = -0.1, 0.2 / (GRID_POINTS - 1)
        lat = kc_result(config, axle, 'lateral_force', fidelity, steps=KC_STEPS)
        f = lat.channels['contact_force'][:, 0, 1]
        lon = kc_result(config, axle, 'longitudinal_force', fidelity, steps=KC_STEPS)
        fx = lon.channels['contact_force'][:, 0, 0] + lon.channels['centre_force'][:, 0, 0]
        for s in range(2):
            w = 2 * k + s
            c_sy[w] = slope_at(f, lat.channels['toe'][:, s], 0.0, FORCE_WINDOW)
            c_cy[w] = slope_at(f, lat.channels['camber'][:, s], 0.0, FORCE_WINDOW)
            j_y[w] = slope_at(f, lat.channels['pad_force'][:, s], 0.0, FORCE_WINDOW)
            for side, sign in enumerate((-1.0, 1.0)):
                c_sx[side, w] = _one_sided(fx, lon.channels['toe'][:, s], sign)
                j_x[side, w] = _one_sided(fx, lon.channels['pad_force'][:, s], sign)
        align = kc_result(config, axle, 'aligning_torque', fidelity, steps=KC_STEPS)
        c_mz[2 * k:2 * k + 2] = rate(align, 'toe') / rate(align, 'contact_moment')[0, 2]
        prov['compliance_steer_aligning'] = prov.get('compliance_steer_aligning', '') + (
            f'{axle}: K&C aligning_torque ({tag}); ')
        for key in ('compliance_steer_lateral', 'compliance_camber_lateral',
                    'jacking_lateral'):
            prov[key] = prov.get(key, '') + f'{axle}: K&C lateral_force ({tag}); '
        for key in ('compliance_steer_longitudinal', 'jacking_longitudinal'):
            prov[key] = prov.get(key, '') + f'{axle}: K&C longitudinal_force ({tag}); '
    steer = steering_map(config, fidelity, KC_STEPS)
    prov['steering'] = steer.source
    return SuspensionMaps(
        travel0=t0, travel_step=ts, travel_table=table, arb0=a0, arb_step=as_, arb_table=arb,
        roll0=r0, roll_step=rs, roll_table=roll,
        compliance_steer_y=c_sy, compliance_camber_y=c_cy, compliance_steer_mz=c_mz,
        compliance_steer_x=c_sx,
        jacking_y=j_y, jacking_x=j_x, damper_x=(dampers_x[0], dampers_x[1]),
        damper_y=(dampers_y[0], dampers_y[1]), steer_swa=steer.swa,
        steer_angle=steer.angles, steering_ratio=steer.ratio,
        provenance={k: v.strip().rstrip(';') for k, v in prov.items()})


__all__ = ['SuspensionMaps', 'suspension_maps', 'WHEELS', 'TRAVEL_ROWS', 'KC_STEPS',
           'grid_lookup', 'half_difference']
