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
* driveline and brakes: wheel torques from the speed driver, split by
  :func:`.drivers.wheel_torques` (front/rear share, open differentials).

Integrator: semi-implicit (symplectic) Euler on Pinocchio's ABA accelerations,
``v+ = v + h a(q, v)``, ``q+ = integrate(q, h v+)``, fixed step ``h`` (STEP), with the
transient slips advanced analytically (exact first-order decay over the step) and the
stiff wheel-spin / longitudinal-slip coupling linearly implicit (see
:meth:`VehicleModel.forces`): that is what makes the step independent of speed. A
non-finite state is a SolverError naming configuration, event and time.

Not modelled (documented in docs/models.md): steering-system inertia and compliance
beyond the K&C compliance steer, wheel-centre fore-aft and lateral motion with travel
(their effect enters through the jacking coefficients), gyroscopic steer moments (the
wheel's spin inertia is carried about the body y axis: a torque about the spin axis
reaches the body as one about y, an error of that torque times the steer angle, zero
for a free-rolling wheel in a steady state), road unevenness.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import pinocchio as pin

from vd_data_server.model import Configuration
from vd_data_server.tire_group import tire_properties
from vd_solvers.analytical.params import SPIN_INERTIA_FACTOR
from vd_solvers.constants import STANDARD_GRAVITY
from vd_solvers.errors import SolverError
from vd_solvers.tire.magic_formula import MagicFormula
from vd_solvers.vehicle_data import static_wheel_loads, wheel_centres

from .maps import WHEELS, SuspensionMaps, suspension_maps

#: integration step, s
STEP = 0.005
#: slip-velocity floor of the slip definitions, m/s (the .tir VXLOW when it is larger)
VX_FLOOR = 1.0
#: side sign per wheel: +1 left, -1 right
SIDE = np.array([1.0, -1.0, 1.0, -1.0])
FRONT = np.array([True, True, False, False])


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
        target = (spin * self.radius - self.vx) / self.denominator
        return target + (self.kappa - target) * self.decay


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

    def __init__(self, config: Configuration, fidelity: str = 'rigid',
                 options: Options = Options(), maps: SuspensionMaps | None = None) -> None:
        self.config = config
        self.options = options
        self.maps = maps if maps is not None else suspension_maps(config, fidelity)
        mass = config.group('mass')
        front_props = tire_properties(config.group('front_tire'))
        rear_props = tire_properties(config.group('rear_tire'))
        self.tires = (MagicFormula(front_props), MagicFormula(rear_props))
        # one vectorised evaluation of all four wheels where both axles share the .tir data
        self._one_tire = (front_props.file_format == rear_props.file_format
                          and front_props.sections == rear_props.sections)
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
        self.gravity = STANDARD_GRAVITY if options.gravity else 0.0
        self.model = self._build(mass)
        self.data = self.model.createData()
        self.total_mass = float(sum(i.mass for i in self.model.inertias))
        self._static = self.static_loads()
        # slip stiffness for the implicit spin update, taken proportional to the load
        # (PKX1 Fz): only the stability of the update depends on it
        self._slip_stiffness_static = self._slip_stiffness(self._static)

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
        # body height and pitch at which the tires carry the static loads at zero travel
        sink = (self.r0 - fz_static / self.cz) - self.wheel_centres[:, 2]
        x_f, x_r = self.wheel_centres[0, 0], self.wheel_centres[2, 0]
        pitch = (sink[2] - sink[0]) / (x_f - x_r)  # ISO pitch: z = q_z - x pitch
        q[2] = sink[0] + pitch * x_f
        q[3:7] = pin.Quaternion(pin.rpy.rpyToMatrix(0.0, pitch, 0.0)).coeffs()
        v = np.zeros(self.model.nv)
        v[0] = speed
        # kinematic cornering (no rear slip): the rear axle moves along the heading, the
        # origin ahead of it sideways at yaw_rate times the distance
        v[1] = yaw_rate * (-self.wheel_centres[2:, 0].mean())
        v[5] = yaw_rate
        _, r_e = self.tire_radii(fz_static)
        # wheel-centre speeds of a body yawing about its origin
        vx_wheel = speed - yaw_rate * self.wheel_centres[:, 1]
        v[7::2] = vx_wheel / r_e
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
        if self._one_tire:
            return self.tires[0].radii(fz)
        lf, ef = self.tires[0].radii(fz[:2])
        lr, er = self.tires[1].radii(fz[2:])
        return np.concatenate([lf, lr]), np.concatenate([ef, er])

    # --- one step ----------------------------------------------------------------------

    def forces(self, q: np.ndarray, v: np.ndarray, swa: float, wheel_torque: np.ndarray,
               slip: np.ndarray, previous: WheelState | None, h: float
               ) -> tuple[np.ndarray, WheelState, SlipUpdate]:
        """
        Generalised forces tau (nv,), the wheels' state, and how the transient slips move.

        ``slip`` (2, 4): transient [kappa', alpha'] at the start of the step; ``wheel_torque``
        (4,) N*m drive (+) / brake torques about the spin axes.
        """
        rot = pin.Quaternion(q[6], q[3], q[4], q[5]).toRotationMatrix()  # world R body
        z = q[7::2]
        zdot = v[6::2]
        spin = v[7::2]
        v_lin, omega = v[0:3], v[3:6]
        r = self.wheel_centres.copy()
        r[:, 2] += z  # wheel centres, body frame
        v_body = v_lin + _cross(omega, r)
        v_body[:, 2] += zdot  # wheel-centre velocity, body axes
        p_world = q[0:3] + r @ rot.T
        v_world = v_body @ rot.T
        tau = np.zeros(self.model.nv)
        maps = self.maps
        table = maps.travel(z)
        # --- tire kinematics
        steer = np.zeros(4)
        steer[0], steer[1] = maps.road_wheel_angles(swa)
        if previous is not None:
            # body-axis tire forces and the aligning moments of the previous step for the
            # compliances
            fy_b = previous.fx * np.sin(previous.steer) + previous.fy * np.cos(previous.steer)
            fx_b = previous.fx * np.cos(previous.steer) - previous.fy * np.sin(previous.steer)
            mz_prev = previous.mz
        else:
            fy_b = fx_b = mz_prev = np.zeros(4)
        side = np.where(fx_b < 0.0, 0, 1)
        cols = np.arange(4)
        roll = maps.roll(z)
        toe = (table[1] + roll[0] + maps.compliance_steer_y * fy_b
               + maps.compliance_steer_x[side, cols] * fx_b + maps.compliance_steer_mz * mz_prev)
        camber = table[2] + roll[1] + maps.compliance_camber_y * fy_b
        steer = steer - SIDE * toe
        # the wheel's spin axis: body y turned by the inclination to the body (+ top to the
        # right, the .tir convention) about the wheel's heading, then by the steer about z
        lean = -SIDE * camber
        cos_l = np.cos(lean)
        axis = np.stack([-np.sin(steer) * cos_l, np.cos(steer) * cos_l, np.sin(lean)],
                        axis=1) @ rot.T  # world
        gamma = np.arcsin(np.clip(axis[:, 2], -1.0, 1.0))
        # heading on the road: spin axis x road normal
        level = np.hypot(axis[:, 0], axis[:, 1])
        ch, sh = axis[:, 1] / level, -axis[:, 0] / level
        vx = v_world[:, 0] * ch + v_world[:, 1] * sh
        vy = -v_world[:, 0] * sh + v_world[:, 1] * ch
        height = p_world[:, 2]
        if self.options.road:
            fz = np.maximum(self.cz * (self.r0 - height) - self.cd * v_world[:, 2], 0.0)
            fz = np.where(height < self.r0, fz, 0.0)
        else:
            fz = np.zeros(4)
        _, r_e = self.tire_radii(fz)
        denom = np.maximum(np.abs(vx), self.vx_floor)
        kappa = (spin * r_e - vx) / denom
        alpha = np.arctan(vy / denom)
        sigma_k, sigma_a = self._relaxation(fz, gamma)
        # The transient slips follow the steady ones with the time constant sigma / V, V the
        # same floored speed as in the slip definitions: at standstill the tire then acts as
        # a damper instead of freezing a slip (a limit cycle at rest).
        decay_k = np.where(sigma_k > 0.0, np.exp(-denom * h / np.maximum(sigma_k, 1e-9)), 0.0)
        decay_a = np.where(sigma_a > 0.0, np.exp(-denom * h / np.maximum(sigma_a, 1e-9)), 0.0)
        if previous is None:
            slip = np.stack([kappa, alpha])  # start in the steady state
        k_t, a_t = slip
        update = SlipUpdate(alpha=alpha + (a_t - alpha) * decay_a, kappa=k_t, decay=decay_k,
                            radius=r_e, vx=vx, denominator=denom)
        f = self._tire(fz, k_t, a_t, gamma, vx)
        wheel = WheelState(fz=fz, fx=f.fx, fy=f.fy, mz=f.mz, kappa=k_t, alpha=a_t, gamma=gamma,
                           steer=steer, travel=z)
        # --- tire wrench (world) at the contact point, moment about the wheel centre
        e_h = np.stack([ch, sh, np.zeros(4)], axis=1)
        e_l = np.stack([-sh, ch, np.zeros(4)], axis=1)
        force = f.fx[:, None] * e_h + f.fy[:, None] * e_l
        force[:, 2] = fz
        # (contact point - wheel centre) x force, the lever being (0, 0, -height)
        moment = np.stack([height * force[:, 1], -height * force[:, 0], f.mz], axis=1) \
            + f.mx[:, None] * e_h + f.my[:, None] * e_l
        force_b = force @ rot
        moment_b = moment @ rot
        # carrier Jacobian: body linear, body angular (about the origin), travel
        tau[0:3] = force_b.sum(axis=0)
        tau[3:6] = (_cross(r, force_b) + moment_b).sum(axis=0)
        tau[6::2] = force_b[:, 2]
        # Linearly implicit wheel spin. With Fx linearised in the transient slip (slope K_x)
        # and kappa' advanced with the spin rate at the end of the step,
        #   I dw = h (T - R_e K_x ((1 - d)(kappa - kappa') + (1 - d) R_e dw / V)),
        # so dw = h T_eff / I with T_eff below. The explicit form is unstable for
        # h > V / (sigma omega_n^2) (omega_n of the spin/slip mode): 1.7 ms at 10 m/s.
        k_x = self._slip_stiffness_static * fz / self._static
        # the wheel-spin equation I dw/dt = T - R F_x + M_y: the contact force's moment
        # about the wheel's own spin axis plus the rolling-resistance moment M_y; the
        # aligning and overturning moments are about road axes and reach the body through
        # the bearing (M_z's share along a cambered axis would roll a car at rest)
        lever_moment = np.stack([height * force[:, 1], -height * force[:, 0],
                                 np.zeros(4)], axis=1)
        spin_torque = (lever_moment * axis).sum(axis=1) + f.my + wheel_torque
        lag = (1.0 - decay_k) * r_e * k_x
        tau[7::2] = (spin_torque - lag * (kappa - k_t)) * self.spin_inertia / (
            self.spin_inertia + h * lag * r_e / denom)
        # --- suspension
        suspension = table[0] + maps.arb(z)
        if self.options.dampers:
            ratio = table[3]
            damper = np.concatenate([
                np.interp(ratio[:2] * zdot[:2], maps.damper_x[0], maps.damper_y[0]),
                np.interp(ratio[2:] * zdot[2:], maps.damper_x[1], maps.damper_y[1])])
            suspension = suspension + ratio * damper
        side_now = np.where(force_b[:, 0] < 0.0, 0, 1)
        # The carriers slide along the body's z axis only, so an unsprung mass's lateral
        # inertia reaches the body at its wheel centre. In the car it is the links that
        # carry the tire force less that inertia (the force roll centre's jacking acts on
        # that share) while the unsprung mass's own overturning moment loads its tires
        # (the unsprung term of the load transfer): the lateral acceleration of the
        # previous step's tire forces restores both.
        inertia = self.unsprung * fy_b.sum() / self.total_mass
        jacking = (maps.jacking_y * (force_b[:, 1] - inertia)
                   + maps.jacking_x[side_now, cols] * force_b[:, 0]
                   + self._unsprung_arm * inertia)
        tau[6::2] -= suspension + (jacking if self.options.road else 0.0)
        return tau, wheel, update

    def _tire(self, fz, kappa, alpha, gamma, vx):
        if self._one_tire:
            return self.tires[0].steady_state(fz, kappa, alpha, gamma, vx, mirror=self.mirror)
        front = self.tires[0].steady_state(fz[:2], kappa[:2], alpha[:2], gamma[:2], vx[:2],
                                           mirror=self.mirror[:2])
        rear = self.tires[1].steady_state(fz[2:], kappa[2:], alpha[2:], gamma[2:], vx[2:],
                                          mirror=self.mirror[2:])
        return type(front)(*(np.concatenate([a, b]) for a, b in zip(front, rear)))

    def _slip_stiffness(self, fz):
        if self._one_tire:
            return self.tires[0].slip_stiffness(fz)
        return np.concatenate([self.tires[0].slip_stiffness(fz[:2]),
                               self.tires[1].slip_stiffness(fz[2:])])

    def _relaxation(self, fz, gamma):
        if self._one_tire:
            return self.tires[0].relaxation_lengths(fz, gamma)
        kf, af = self.tires[0].relaxation_lengths(fz[:2], gamma[:2])
        kr, ar = self.tires[1].relaxation_lengths(fz[2:], gamma[2:])
        return np.concatenate([kf, kr]), np.concatenate([af, ar])

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


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """
    Compute a x b row by row for (3,) or (n, 3) operands.

    np.cross costs more on small arrays.
    """
    a = np.broadcast_to(a, b.shape)
    return np.stack([a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1], a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2],
                     a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]], axis=1)


__all__ = ['VehicleModel', 'WheelState', 'SlipUpdate', 'Options', 'STEP', 'WHEELS']
