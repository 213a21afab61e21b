# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Full-vehicle multibody model: Pinocchio chassis, K&C suspension maps, Magic Formula tires.

Topology (Pinocchio, built once per configuration)::

    universe -- free flyer -- body (sprung mass, CoG and inertia of the mass group)
                  +-- prismatic z (body axis) -- carrier FL (unsprung mass)
                      -- revolute y -- wheel FL (spin inertia)
                  +-- ... FR, RL, RR

The body frame is the data frame of the configuration (ISO 8855 / REP 103: x forward,
y left, z up, origin on the ground at the front axle at design); the carrier joints sit
at the design wheel centres, so travel z = 0 is the design position. ``q`` is
Pinocchio's [x y z qx qy qz qw | z_FL theta_FL | z_FR theta_FR | ...] and ``v`` its
local-frame velocity [v_body omega_body | dz_FL omega_FL | ...].

Forces per step (all from the configuration; :mod:`.maps` for the suspension):

* suspension, on each travel joint: -(wheel force map + anti-roll bar + damper
  motion_ratio * F_damper(motion_ratio * dz/dt)) - jacking (K&C d(pad force)/dF times the
  force the links carry, the tire force in body axes less the unsprung mass's lateral
  inertia: force roll centre, anti-dive/-lift/-squat) - the unsprung mass's own
  overturning moment, m_u a_y h_wc / t on each wheel (a_y from the previous step's tire
  forces): the prismatic carriers would otherwise hand that moment to the body;
* tire, at the contact point below the wheel centre on a flat road z = 0: Fz = C_z
  deflection + tire damping (>= 0). The wheel's frame follows its steer and camber: the
  spin axis is the body y axis turned by the camber map (+ its roll correction and the
  compliance camber) about the wheel's heading and by the steering-map angle + toe map
  (+ its roll correction, see :mod:`.maps`) + compliance steer (lateral,
  longitudinal and aligning-moment compliance, from the previous step's forces) about
  the body z axis, then carried by the body's attitude. The wheel's heading on the road
  is the line where its plane meets the road (spin axis x road normal), its inclination
  the spin axis' angle to the road; slip from the wheel-centre velocity in that heading;
  first-order transient slip with the .tir relaxation lengths,
  ``sigma dalpha'/dt + V alpha' = V alpha`` (V = max(|V_x|, VX_FLOOR)), integrated
  exactly over a step;
  combined-slip Magic Formula forces and moments. The contact wrench is mapped to the
  generalised forces with the carrier's Jacobian (body, travel); the contact force's
  moment about the wheel's own spin axis and the rolling-resistance moment drive the
  wheel (I dw/dt = T - R F_x + M_y), so a free-rolling wheel settles where its
  longitudinal force balances the rolling resistance, whatever its steer.
* driveline and brakes: wheel torques from the drivers through the configuration's
  brakes (anti-lock per wheel) and driveline (engine map, gears, differentials), or split
  by fixed shares without those groups (:class:`.drivers.WheelTorques`);
* aerodynamics (the ``aero`` group; none without it): drag against the body's x speed at
  the sprung centre of gravity's height, lift through each axle's line
  (:mod:`vd_solvers.chassis.aero`).

Integrator: semi-implicit (symplectic) Euler on the articulated-body accelerations,
``v+ = v + h a(q, v)``, ``q+ = integrate(q, h v+)``, fixed step ``h`` (STEP), compiled for
this tree in :mod:`.dynamics` (:meth:`VehicleModel.step`; Pinocchio's ``aba`` and
``integrate``, :meth:`VehicleModel.acceleration` and :meth:`VehicleModel.integrate`, are
its reference), with the
transient slips advanced analytically (exact first-order decay over the step) and the
stiff wheel-spin / longitudinal-slip coupling linearly implicit (see
:meth:`VehicleModel.forces`): that is what makes the step independent of speed. A
non-finite state is a SolverError naming configuration, event and time.

Not modelled (documented in docs/models.md): steering-system inertia and compliance
beyond the K&C compliance steer, wheel-centre fore-aft and lateral motion with travel
(their effect enters through the jacking coefficients), gyroscopic steer moments (the
wheel's spin inertia is carried about the body y axis: a torque about the spin axis
reaches the body as one about y, an error of that torque times the steer angle, zero
for a free-rolling wheel in a steady state).

Road: the tires stand on the :class:`vd_solvers.road.arrays.RoadGrid` given (default the
configuration's road, :func:`vd_solvers.road.from_config.road_of`: without a ``road``
group the flat road of friction 1) through the tandem elliptical cams of :mod:`.forces`;
the cams of each tire come from its .tir [CONTACT_PATCH] section: half-length
a_e = ELLIPS_LENGTH r0, height b_e = ELLIPS_HEIGHT r0, order c_e = ELLIPS_ORDER, spacing
l_s = ELLIPS_SHIFT 2a (defaults 1, 1, 1.8, 0.8), a the contact half-length at the static load,
a = r0 (Q_RA2 rho / r0 + Q_RA1 sqrt(rho / r0)) of MF 6.1 (rho the static deflection;
without Q_RA1 / Q_RA2 the chord of the undeformed circle, a = sqrt(2 r0 rho)).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import pinocchio as pin

from vd_data_server.model import Configuration
from vd_data_server.tire_group import tire_properties
from vd_solvers.analytical.params import SPIN_INERTIA_FACTOR
from vd_solvers.chassis.from_config import chassis_systems
from vd_solvers.constants import STANDARD_GRAVITY
from vd_solvers.errors import SolverError
from vd_solvers.results import run_fidelity
from vd_solvers.road.arrays import RoadGrid
from vd_solvers.road.from_config import road_of
from vd_solvers.tire.magic_formula import MagicFormula
from vd_solvers.vehicle_data import static_wheel_loads, wheel_centres

from .dynamics import kappa_next, multibody_arrays, vehicle_step
from .forces import (
    AERO_ROWS,
    CAM_ROWS,
    COMPLIANCE_ROWS,
    CONSTANT_ROWS,
    VehicleArrays,
    vehicle_forces,
    wheel_radii,
)
from .maps import WHEELS, SuspensionMaps, suspension_maps

#: integration step, s
STEP = 0.005
#: slip-velocity floor of the slip definitions, m/s (the .tir VXLOW when it is larger)
VX_FLOOR = 1.0
#: side sign per wheel: +1 left, -1 right
SIDE = np.array([1.0, -1.0, 1.0, -1.0])


class SlipUpdate(NamedTuple):
    """
    How the transient slips move over a step (arrays (4,)).

    alpha' moves explicitly, kappa' with the wheel spin at the end of the step (see
    :meth:`VehicleModel.forces`).
    """

    alpha: np.ndarray  # alpha' at the end of the step
    kappa: np.ndarray  # kappa' at the start of the step
    decay: np.ndarray  # exp(-|V_x| h / sigma_kappa)
    radius: np.ndarray  # effective rolling radius R_e, m
    vx: np.ndarray  # m/s
    denominator: np.ndarray  # max(|V_x|, floor), m/s

    def kappa_next(self, spin: np.ndarray) -> np.ndarray:
        """Kappa' at the end of the step for the spin rates ``spin`` (rad/s) reached."""
        return kappa_next(np.stack(self), np.ascontiguousarray(spin, dtype=float))


class WheelState(NamedTuple):
    """Per-wheel quantities of one step (arrays (4,), SI, order FL FR RL RR)."""

    fz: np.ndarray
    fx: np.ndarray  # wheel heading axis
    fy: np.ndarray  # wheel lateral axis
    mz: np.ndarray
    kappa: np.ndarray  # transient longitudinal slip
    alpha: np.ndarray  # transient slip angle, TYDEX (alpha > 0: patch slides left)
    gamma: np.ndarray  # inclination to the road, rad
    steer: np.ndarray  # heading of the wheel relative to the body, rad (+ left)
    travel: np.ndarray  # m, + bump


@dataclass(frozen=True)
class Options:
    """Switches for tests of conservation properties (defaults: the real vehicle)."""

    road: bool = True  # tires touch the road
    gravity: bool = True
    dampers: bool = True


class VehicleModel:
    """The multibody vehicle of one configuration (module doc). Not thread-safe."""

    def __init__(self, config: Configuration, fidelity: str = '',
                 options: Options = Options(), maps: SuspensionMaps | None = None,
                 road: RoadGrid | None = None) -> None:
        self.config = config
        self.road = road if road is not None else road_of(config)
        self.options = options
        #: the K&C fidelity of the suspension maps: ``fidelity``, "" = the configuration's
        #: flexible switch (``results.run_fidelity``)
        self.fidelity = run_fidelity('vehicle', config, fidelity)
        self.maps = maps if maps is not None else suspension_maps(config, self.fidelity)
        mass = config.group('mass')
        front_props = tire_properties(config.group('front_tire'))
        rear_props = tire_properties(config.group('rear_tire'))
        self.tires = (MagicFormula(front_props), MagicFormula(rear_props))
        for axle, tire in zip(('front', 'rear'), self.tires):
            if tire.vertical_stiffness <= 0.0:
                raise SolverError(f"configuration '{config.name}': {axle} tire has no "
                                  "VERTICAL_STIFFNESS")
        self.mirror = np.array([self._mirror(t, s) for t, s in
                                zip((self.tires[0], self.tires[0], self.tires[1], self.tires[1]),
                                    SIDE)])
        self.r0 = np.array([self.tires[0].unloaded_radius] * 2
                           + [self.tires[1].unloaded_radius] * 2)
        self.cz = np.array([self.tires[0].vertical_stiffness] * 2
                           + [self.tires[1].vertical_stiffness] * 2)
        self.cd = np.array([self.tires[0].vertical_damping] * 2
                           + [self.tires[1].vertical_damping] * 2)
        vxlow = [t.props.number('MODEL', 'VXLOW', 0.0) for t in self.tires]
        self.vx_floor = max(VX_FLOOR, *vxlow)
        self.wheel_centres = wheel_centres(config)  # (4, 3) body frame, design
        m_u = np.array([mass.scalar('unsprung_mass_front')] * 2
                       + [mass.scalar('unsprung_mass_rear')] * 2)
        self.unsprung = m_u
        self.spin_inertia = SPIN_INERTIA_FACTOR * m_u * self.r0**2
        # pad-force change per N of one corner's unsprung lateral inertia: the axle's two
        # corners' overturning moment (wheel-centre height) over its track, on each wheel,
        # outer wheel loaded: 2 h / t = h / |y|
        self._unsprung_arm = -SIDE * self.wheel_centres[:, 2] / np.abs(self.wheel_centres[:, 1])
        self.sprung_mass = mass.scalar('sprung_mass')
        self.chassis = chassis_systems(config)  # brakes, driveline, aerodynamics
        self.gravity = STANDARD_GRAVITY if options.gravity else 0.0
        self.model = self._build(mass)
        self.data = self.model.createData()
        self.total_mass = float(sum(i.mass for i in self.model.inertias))
        self._static = self.static_loads()
        # slip stiffness for the implicit spin update, taken proportional to the load
        # (PKX1 Fz): only the stability of the update depends on it
        self._slip_stiffness_static = np.concatenate(
            [self.tires[0].slip_stiffness(self._static[:2]),
             self.tires[1].slip_stiffness(self._static[2:])])
        self.cam = self._cams()
        self.arrays = self._arrays()
        self.multibody = multibody_arrays(self.model)
        self._no_previous = np.zeros((4, 4))

    @staticmethod
    def _mirror(tire: MagicFormula, side: float) -> float:
        measured = str(tire.props.get('MODEL', 'TYRESIDE', 'LEFT')).upper()
        return 1.0 if (measured == 'LEFT') == (side > 0) else -1.0

    def _build(self, mass) -> pin.Model:
        model = pin.Model()
        model.gravity.linear = np.array([0.0, 0.0, -self.gravity])
        body = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), 'body')
        inertia = np.diag([mass.scalar('sprung_inertia.ixx'), mass.scalar('sprung_inertia.iyy'),
                           mass.scalar('sprung_inertia.izz')])
        model.appendBodyToJoint(body, pin.Inertia(self.sprung_mass,
                                                  np.array(mass.point('sprung_cog')), inertia),
                                pin.SE3.Identity())
        for w, name in enumerate(WHEELS):
            travel = model.addJoint(body, pin.JointModelPZ(),
                                    pin.SE3(np.eye(3), self.wheel_centres[w]), f'{name}_travel')
            # the carrier: unsprung mass at the wheel centre (rotational inertia in the wheel)
            model.appendBodyToJoint(travel, pin.Inertia(float(self.unsprung[w]), np.zeros(3),
                                                        np.zeros((3, 3))), pin.SE3.Identity())
            spin = model.addJoint(travel, pin.JointModelRY(), pin.SE3.Identity(), f'{name}_spin')
            i_s = float(self.spin_inertia[w])
            model.appendBodyToJoint(spin, pin.Inertia(0.0, np.zeros(3),
                                                      np.diag([0.5 * i_s, i_s, 0.5 * i_s])),
                                    pin.SE3.Identity())
        return model

    # --- state -------------------------------------------------------------------------

    def initial_state(self, speed: float, yaw_rate: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """
        Return the initial state (q, v) with the static loads on the tires.

        The vehicle moves at ``speed`` (m/s, body x) and ``yaw_rate`` (rad/s; zero:
        straight ahead).
        """
        q = pin.neutral(self.model)
        fz_static = self.static_loads()
        _, r_e = self.tire_radii(fz_static)
        v = np.zeros(self.model.nv)
        v[0] = speed
        # kinematic cornering (no rear slip): the rear axle moves along the heading, the
        # origin ahead of it sideways at yaw_rate times the distance
        v[1] = yaw_rate * (-self.wheel_centres[2:, 0].mean())
        v[5] = yaw_rate
        # wheel-centre speeds of a body yawing about its origin
        vx_wheel = speed - yaw_rate * self.wheel_centres[:, 1]
        v[7::2] = vx_wheel / r_e
        # body height and pitch at which the tires carry the static loads at zero travel;
        # an MF 6.2 tire's deflection depends on its camber: a second pass at the camber of
        # the first
        gamma = np.zeros(4)
        for i in range(2 if any(t.props.file_format == 'MF62' for t in self.tires) else 1):
            if i > 0:
                gamma = self.forces(q, v, 0.0, np.zeros(4), np.zeros((2, 4)), None, STEP)[1].gamma
            deflection = np.concatenate([
                self.tires[k // 2].deflection(fz_static[k:k + 2], v[7 + 2 * k:11 + 2 * k:2],
                                              self.mirror[k:k + 2] * gamma[k:k + 2])
                for k in (0, 2)])
            sink = (self.r0 - deflection) - self.wheel_centres[:, 2]
            x_f, x_r = self.wheel_centres[0, 0], self.wheel_centres[2, 0]
            pitch = (sink[2] - sink[0]) / (x_f - x_r)  # ISO pitch: z = q_z - x pitch
            q[2] = sink[0] + pitch * x_f
            q[3:7] = pin.Quaternion(pin.rpy.rpyToMatrix(0.0, pitch, 0.0)).coeffs()
        return q, v

    def static_loads(self) -> np.ndarray:
        """
        Return the static wheel loads FL FR RL RR, N.

        They are the ``static_wheel_loads`` of the configuration.
        """
        front, rear = static_wheel_loads(self.config)
        return np.array([front, front, rear, rear])

    def tire_radii(self, fz: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Return the (loaded, effective rolling) radii of the four tires at loads ``fz``, m."""
        return wheel_radii(self.arrays.tire_front, self.arrays.tire_rear,
                           np.ascontiguousarray(fz, dtype=float))

    # --- one step ----------------------------------------------------------------------

    def forces(self, q: np.ndarray, v: np.ndarray, swa: float, wheel_torque: np.ndarray,
               slip: np.ndarray, previous: WheelState | None, h: float
               ) -> tuple[np.ndarray, WheelState, SlipUpdate]:
        """
        Generalised forces tau (nv,), the wheels' state, and how the transient slips move.

        ``slip`` (2, 4): transient [kappa', alpha'] at the start of the step; ``wheel_torque``
        (4,) N*m drive (+) / brake torques about the spin axes.
        """
        prev = (np.stack([previous.fx, previous.fy, previous.mz, previous.steer])
                if previous is not None else self._no_previous)
        tau, wheel, update = vehicle_forces(
            np.ascontiguousarray(q, dtype=float), np.ascontiguousarray(v, dtype=float),
            float(swa), np.ascontiguousarray(wheel_torque, dtype=float),
            np.ascontiguousarray(slip, dtype=float), prev, previous is not None, float(h),
            self.arrays, self.vx_floor, self.total_mass, self.options.road,
            self.options.dampers)
        return tau, WheelState(*wheel), SlipUpdate(*update)

    def step(self, q: np.ndarray, v: np.ndarray, swa: float, wheel_torque: np.ndarray,
             slip: np.ndarray, previous: np.ndarray | None, h: float
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """
        One compiled step (:func:`.dynamics.vehicle_step`): q, v and slip at its end, the wheels.

        ``previous`` (4, 4): the previous step's wheel rows dynamics.PREVIOUS_ROWS (Fx, Fy,
        Mz, steer), None on the first step; the wheels' state is (WHEEL_ROWS, 4) at the
        step's start.
        """
        has_previous = previous is not None
        return vehicle_step(
            np.ascontiguousarray(q, dtype=float), np.ascontiguousarray(v, dtype=float),
            float(swa), np.ascontiguousarray(wheel_torque, dtype=float),
            np.ascontiguousarray(slip, dtype=float),
            self._no_previous if previous is None else np.ascontiguousarray(previous),
            has_previous, float(h), self.arrays, self.vx_floor, self.total_mass,
            self.options.road, self.options.dampers, self.multibody)

    def _cams(self) -> np.ndarray:
        """Return the enveloping cams of the four tires, (len(CAM_ROWS), 4) (module doc)."""
        out = np.empty((len(CAM_ROWS), 4))
        for w in range(4):
            tire = self.tires[0 if w < 2 else 1]
            props = tire.props
            r0 = float(self.r0[w])
            rho = float(self._static[w] / self.cz[w])
            q1 = props.number('CONTACT_PATCH', 'Q_RA1', 0.0)
            q2 = props.number('CONTACT_PATCH', 'Q_RA2', 0.0)
            half = (r0 * (q2 * rho / r0 + q1 * np.sqrt(rho / r0)) if q1 > 0.0 or q2 > 0.0
                    else np.sqrt(2.0 * r0 * rho))
            out[:, w] = (props.number('CONTACT_PATCH', 'ELLIPS_LENGTH', 1.0) * r0,
                         props.number('CONTACT_PATCH', 'ELLIPS_HEIGHT', 1.0) * r0,
                         props.number('CONTACT_PATCH', 'ELLIPS_ORDER', 1.8),
                         props.number('CONTACT_PATCH', 'ELLIPS_SHIFT', 0.8) * 2.0 * half)
        if not np.all(out[[0, 1, 3]] > 0.0) or not np.all(out[2] >= 1.0):
            raise SolverError(f"configuration '{self.config.name}': the tires' enveloping "
                              'ellipses need positive ELLIPS_LENGTH, ELLIPS_HEIGHT, '
                              'ELLIPS_SHIFT and an ELLIPS_ORDER of at least 1')
        return out

    def _arrays(self) -> VehicleArrays:
        """Return the constant inputs of the compiled force evaluation (:mod:`.forces`)."""
        maps = self.maps
        per_wheel = {'side': SIDE, 'r0': self.r0, 'cz': self.cz, 'cd': self.cd,
                     'mirror': self.mirror, 'unsprung': self.unsprung,
                     'spin_inertia': self.spin_inertia, 'unsprung_arm': self._unsprung_arm,
                     'slip_stiffness_static': self._slip_stiffness_static,
                     'static_load': self._static}
        compliance = {'steer_y': maps.compliance_steer_y, 'camber_y': maps.compliance_camber_y,
                      'steer_mz': maps.compliance_steer_mz,
                      'steer_x_braking': maps.compliance_steer_x[0],
                      'steer_x_traction': maps.compliance_steer_x[1],
                      'jacking_y': maps.jacking_y, 'jacking_x_braking': maps.jacking_x[0],
                      'jacking_x_traction': maps.jacking_x[1]}

        def c(a) -> np.ndarray:
            return np.ascontiguousarray(a, dtype=float)

        return VehicleArrays(
            centres=c(self.wheel_centres),
            wheel=c(np.stack([per_wheel[k] for k in CONSTANT_ROWS])),
            tire_front=c(self.tires[0].coefficients), tire_rear=c(self.tires[1].coefficients),
            travel0=c(maps.travel0), travel_step=c(maps.travel_step),
            travel_table=c(maps.travel_table), arb0=c(maps.arb0), arb_step=c(maps.arb_step),
            arb_table=c(maps.arb_table[None]), roll0=c(maps.roll0), roll_step=c(maps.roll_step),
            roll_table=c(maps.roll_table),
            compliance=c(np.stack([compliance[k] for k in COMPLIANCE_ROWS])),
            damper_front_x=c(maps.damper_x[0]), damper_front_y=c(maps.damper_y[0]),
            damper_rear_x=c(maps.damper_x[1]), damper_rear_y=c(maps.damper_y[1]),
            steer_swa=c(maps.steer_swa), steer_left=c(maps.steer_angle[:, 0]),
            steer_right=c(maps.steer_angle[:, 1]), aero=c(self._aero()),
            road_axes=c(self.road.axes), road_height=c(self.road.height),
            road_friction=c(self.road.friction), cam=c(self.cam))

    def _aero(self) -> np.ndarray:
        """Return the aerodynamic constants of :data:`.forces.AERO_ROWS` (zeros: none)."""
        aero = self.chassis.aero
        if aero is None:
            return np.zeros(len(AERO_ROWS))
        q = 0.5 * aero.density
        rows = {'drag': q * aero.drag_area, 'lift_front': q * aero.frontal_area * aero.lift_front,
                'lift_rear': q * aero.frontal_area * aero.lift_rear,
                'x_front': self.wheel_centres[0, 0], 'x_rear': self.wheel_centres[2, 0],
                'z_drag': self.config.group('mass').point('sprung_cog')[2]}
        return np.array([rows[k] for k in AERO_ROWS])

    def acceleration(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> np.ndarray:
        """Pinocchio ABA: generalised accelerations (nv,)."""
        return pin.aba(self.model, self.data, q, v, tau)

    def integrate(self, q: np.ndarray, v: np.ndarray, a: np.ndarray, h: float
                  ) -> tuple[np.ndarray, np.ndarray]:
        """Semi-implicit Euler step."""
        v_next = v + h * a
        return pin.integrate(self.model, q, v_next * h), v_next

    def energy(self, q: np.ndarray, v: np.ndarray) -> float:
        """Kinetic + gravitational energy of the multibody, J (suspension potential excluded)."""
        kinetic = pin.computeKineticEnergy(self.model, self.data, q, v)
        potential = pin.computePotentialEnergy(self.model, self.data, q)
        return float(kinetic + potential)

    def momentum(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Centroidal momentum (linear, angular about the CoG), world axes (6,)."""
        h = pin.computeCentroidalMomentum(self.model, self.data, q, v)
        return np.concatenate([h.linear, h.angular])

    def label(self, event: str, t: float) -> str:
        return f"configuration '{self.config.name}', event '{event}', t = {t:.3f} s"


__all__ = ['VehicleModel', 'WheelState', 'SlipUpdate', 'Options', 'STEP', 'WHEELS']
