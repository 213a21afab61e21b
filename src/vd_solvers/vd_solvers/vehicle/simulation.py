# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Time integration of the full vehicle with its drivers, and the recorded trace.

``simulate`` advances :class:`.model.VehicleModel` with a fixed step, asks the drivers
every step, records every ``record_every`` steps and stops at ``duration`` or when
``stop(trace_row)`` says so. The speed driver's request becomes wheel torques through
:class:`.drivers.WheelTorques` (the configuration's brakes and driveline, or the fixed
shares ``drive_front`` and ``brake_front`` without them). Channels are SI, ISO 8855
signs: roll positive left side up (outward in a left turn), sideslip and yaw rate positive
to the left.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
import math
import time

import numpy as np
import pinocchio as pin

from vd_solvers.errors import SolverError

from .drivers import Observation, Pedals, SpeedDriver, SteeringDriver, WheelTorques
from .model import STEP, VehicleModel

#: recorded per-sample channels besides the per-wheel ones
TRACE = ('time', 'x', 'y', 'yaw', 'roll', 'pitch', 'yaw_rate', 'speed', 'sideslip',
         'steering_wheel_angle', 'steer_angle_front_left', 'steer_angle_front_right',
         'cog_velocity_x', 'cog_velocity_y', 'cog_velocity_z', 'wheel_torque')
PER_WHEEL = ('wheel_load', 'wheel_travel', 'slip_angle', 'slip_ratio', 'inclination',
             'tire_force_x', 'tire_force_y', 'wheel_steer', 'aligning_moment')
#: what the brakes and driveline did per sample: throttle 0..1, gear (0: no driveline),
#: and per wheel the brake line pressure (Pa) and the wheel torque (N*m)
ACTUATION = ('throttle', 'gear')
ACTUATION_WHEEL = ('brake_pressure', 'applied_torque')


@dataclass
class Trace:
    """Recorded samples: ``rows`` of TRACE values and per-wheel (4,) arrays."""

    rows: list[list[float]] = field(default_factory=list)
    wheels: dict[str, list[np.ndarray]] = field(
        default_factory=lambda: {k: [] for k in PER_WHEEL + ACTUATION_WHEEL})
    actuation: dict[str, list[float]] = field(default_factory=lambda: {k: [] for k in ACTUATION})
    timings: dict[str, float] = field(default_factory=lambda: {'forces': 0.0, 'multibody': 0.0})
    steps: int = 0
    stop_reason: str = ''

    def channels(self) -> dict[str, np.ndarray]:
        """Every channel as an array over the samples, plus accelerations (m/s^2)."""
        data = np.array(self.rows)
        out = {name: data[:, i] for i, name in enumerate(TRACE)}
        for key, values in self.wheels.items():
            out[key] = np.array(values)
        for key, scalars in self.actuation.items():
            out[key] = np.array(scalars)
        t = out['time']
        if t.size >= 3:
            ax_w = np.gradient(out['cog_velocity_x'], t)
            ay_w = np.gradient(out['cog_velocity_y'], t)
        else:
            ax_w = ay_w = np.zeros_like(t)
        c, s = np.cos(out['yaw']), np.sin(out['yaw'])
        out['lateral_acceleration'] = -ax_w * s + ay_w * c
        out['longitudinal_acceleration'] = ax_w * c + ay_w * s
        return out


def observe(model: VehicleModel, q: np.ndarray, v: np.ndarray, t: float) -> Observation:
    rot = pin.Quaternion(q[6], q[3], q[4], q[5]).toRotationMatrix()
    vw = rot @ v[0:3]
    return Observation(t=t, x=float(q[0]), y=float(q[1]),
                       yaw=math.atan2(rot[1, 0], rot[0, 0]), speed=math.hypot(vw[0], vw[1]),
                       course=math.atan2(vw[1], vw[0]))


def simulate(model: VehicleModel, steering: SteeringDriver, speed: SpeedDriver | None,
             duration: float, *, event: str, initial_speed: float, initial_yaw_rate: float = 0.0,
             record_every: int = 10, h: float = STEP, drive_front: float = 0.5,
             brake_front: float = 0.65,
             stop: Callable[[dict[str, float]], str] | None = None,
             progress: Callable[[float, str], None] | None = None) -> Trace:
    """Integrate from straight-ahead motion at ``initial_speed`` (module doc)."""
    q, v = model.initial_state(initial_speed, initial_yaw_rate)
    slip = np.zeros((2, 4))
    previous = None
    trace = Trace()
    cog = np.array(model.config.group('mass').point('sprung_cog'))
    n_steps = int(round(duration / h))
    swa = 0.0
    t_forces = t_mb = 0.0
    actuate = WheelTorques(model.chassis, drive_front, brake_front)
    for step in range(n_steps + 1):
        t = step * h
        obs = observe(model, q, v, t)
        swa = steering.steering_wheel_angle(obs, h)
        request = speed.wheel_torque(obs, h) if speed is not None else 0.0
        kappa = previous.kappa if previous is not None else np.zeros(4)
        torques = actuate(request, v[7::2], kappa, obs.speed, h)
        torque = float(np.sum(torques)) if isinstance(request, Pedals) else float(request)
        c0 = time.perf_counter()
        tau, wheel, update = model.forces(q, v, swa, torques, slip, previous, h)
        c1 = time.perf_counter()
        if step % record_every == 0:
            row = _row(model, q, v, t, swa, wheel, cog, torque)
            trace.rows.append(row)
            for key, values in zip(PER_WHEEL, (wheel.fz, wheel.travel, wheel.alpha, wheel.kappa,
                                               wheel.gamma, wheel.fx, wheel.fy, wheel.steer,
                                               wheel.mz)):
                trace.wheels[key].append(values)
            trace.wheels['brake_pressure'].append(actuate.pressures.copy())
            trace.wheels['applied_torque'].append(torques)
            trace.actuation['throttle'].append(actuate.throttle)
            trace.actuation['gear'].append(float(actuate.gear))
            if stop is not None:
                reason = stop(dict(zip(TRACE, row)))
                if reason:
                    trace.stop_reason = reason
                    break
            if progress is not None and step % (record_every * 50) == 0:
                progress(step / max(n_steps, 1), 'simulating')
        if step == n_steps:
            break
        c2 = time.perf_counter()
        a = model.acceleration(q, v, tau)
        q, v = model.integrate(q, v, a, h)
        t_mb += time.perf_counter() - c2
        t_forces += c1 - c0
        slip = np.stack([update.kappa_next(v[7::2]), update.alpha])
        previous = wheel
        if not (np.all(np.isfinite(q)) and np.all(np.isfinite(v))):
            raise SolverError(f'{model.label(event, t + h)}: the state became non-finite')
        trace.steps += 1
    trace.timings['forces'] = t_forces
    trace.timings['multibody'] = t_mb
    return trace


def _row(model: VehicleModel, q, v, t, swa, wheel, cog, torque) -> list[float]:
    rot = pin.Quaternion(q[6], q[3], q[4], q[5]).toRotationMatrix()
    o = v[3:6]  # omega x cog written out: np.cross costs more than the rest of the row
    v_cog = rot @ (v[0:3] + np.array([o[1] * cog[2] - o[2] * cog[1],
                                      o[2] * cog[0] - o[0] * cog[2],
                                      o[0] * cog[1] - o[1] * cog[0]]))
    yaw = math.atan2(rot[1, 0], rot[0, 0])
    roll = math.asin(max(-1.0, min(1.0, rot[2, 1])))
    pitch = -math.asin(max(-1.0, min(1.0, rot[2, 0])))
    omega_w = rot @ v[3:6]
    c, s = math.cos(yaw), math.sin(yaw)
    u = v_cog[0] * c + v_cog[1] * s
    w = -v_cog[0] * s + v_cog[1] * c
    return [t, q[0], q[1], yaw, roll, pitch, omega_w[2], math.hypot(u, w), math.atan2(w, u),
            swa, wheel.steer[0], wheel.steer[1], v_cog[0], v_cog[1], v_cog[2], torque]


__all__ = ['simulate', 'Trace', 'TRACE', 'PER_WHEEL', 'ACTUATION', 'ACTUATION_WHEEL', 'observe']
