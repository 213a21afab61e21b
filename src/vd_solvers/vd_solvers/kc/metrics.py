# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Derived K&C metrics: pure functions of event channels, registered by name.

Every metric is a :class:`MetricDef` in :data:`METRICS`: its name, SI unit,
the events it needs and a function of those events' results. Slopes "at
design" are exact local derivatives: ratios of the channels' rates at the
design state (:attr:`.result.EventResult.rate_up`, from the implicit
function theorem on the converged tangent), never fits. Values at design are
the channels at the design state. docs/kc.md defines each metric.

The left wheel is reported unless stated (the right is its mirror image).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from vd_solvers.errors import SolverError

from .channels import SIDE_SIGNS
from .result import EventResult

#: Half-widths of the windows of :func:`slope_at` (a fit over channels, for callers that
#: need a slope away from design)
TRAVEL_WINDOW = 0.010  # m of wheel travel
FORCE_WINDOW = 500.0  # N of applied force
ACKERMANN_REFERENCE_ANGLE = np.radians(20.0)  # inner road-wheel angle, rad
#: a compliance below this (m/N) is reported as infinite stiffness (rigid)
RIGID_COMPLIANCE = 1e-12

PAR, OPP, BARE = 'parallel_wheel_travel', 'opposite_wheel_travel', 'opposite_wheel_travel_no_bar'
LAT, LON, ALIGN, STEER = 'lateral_force', 'longitudinal_force', 'aligning_torque', 'steering'


@dataclass(frozen=True)
class Context:
    """What a metric function sees: the results and the vehicle data it may need."""

    results: Mapping[str, EventResult]
    tire_vertical_stiffness: float
    cg_height: float | None = None
    wheelbase: float | None = None
    brake_fraction: float = 1.0
    drive_fraction: float = 1.0

    def __getitem__(self, event: str) -> EventResult:
        """Return the result of ``event``."""
        return self.results[event]


@dataclass(frozen=True)
class MetricDef:
    """A derived metric: SI unit, events needed, vehicle data needed, function."""

    unit: str
    events: tuple[str, ...]
    compute: Callable[[Context], float]
    needs: tuple[str, ...] = ()  # 'cg_height', 'wheelbase'
    axle: str | None = None  # only on this axle ('front'/'rear'), else both
    doc: str = ''


METRICS: dict[str, MetricDef] = {}


def metric(name: str, unit: str, events: tuple[str, ...], needs: tuple[str, ...] = (),
           axle: str | None = None, doc: str = ''):
    """Register the decorated function as metric ``name``."""
    def register(fn: Callable[[Context], float]) -> Callable[[Context], float]:
        if name in METRICS:
            raise ValueError(f'metric {name!r} registered twice')
        METRICS[name] = MetricDef(unit, events, fn, needs, axle, doc)
        return fn
    return register


# --- exact slopes from the channels' rates at design --------------------------


def rate(result: EventResult, channel: str, down: bool = False) -> np.ndarray:
    """Return d channel / d swept quantity at design (up, or ``down`` the sweep)."""
    rates = result.rate_down if down else result.rate_up
    if channel not in rates:
        raise SolverError(f'{result.label}: event {result.event!r} has no rate of {channel!r}')
    return np.asarray(rates[channel])


def slope(result: EventResult, y: str, x: str, side: int = 0, down: bool = False,
          y_index: tuple[int, ...] = (), x_index: tuple[int, ...] = ()) -> float:
    """Return dy/dx at design of two channels of one wheel (``side``), exact."""
    dy = rate(result, y, down)[(side, *y_index)]
    dx = rate(result, x, down)[(side, *x_index)]
    return float(dy / dx)


def design(result: EventResult, channel: str) -> np.ndarray:
    """Return ``channel`` at the design state."""
    return np.asarray(result.design[channel])


def _stiffness(compliance: float) -> float:
    """Return N/m from a compliance in m/N; inf for a rigid connection."""
    if abs(compliance) < RIGID_COMPLIANCE:
        return float('inf')
    return 1.0 / compliance


# --- fits over channels (away from design) ------------------------------------


def _fit_slope(x: np.ndarray, y: np.ndarray) -> float:
    """Return dy/dx at x = 0 from a quadratic least-squares fit (a line below four points)."""
    if x.size < 2:
        raise SolverError("fewer than two steps in a metric's slope window; refine the event")
    coef = np.polyfit(x, y, 2 if x.size >= 4 else 1)
    return float(coef[-2])


def slope_at(x: np.ndarray, y: np.ndarray, x0: float, half_width: float) -> float:
    """
    Return dy/dx at x0 from a quadratic fit to the points within ``half_width``.

    At least the three nearest points are used, so a coarse sweep still gives
    a slope, over a wider window. Metrics at design use the exact rates
    instead; this serves slopes of channels elsewhere (vehicle maps).
    """
    distance = np.abs(x - x0)
    mask = distance <= half_width + 1e-12
    if np.count_nonzero(mask) < 3:
        mask = distance <= np.sort(distance)[min(2, distance.size - 1)] + 1e-12
    return _fit_slope(x[mask] - x0, y[mask])


# --- parallel wheel travel ------------------------------------------------------


def _design_value(channel: str, unit: str, doc: str) -> None:
    metric(channel, unit, (PAR,), doc=doc)(lambda c: float(design(c[PAR], channel)[0]))


for _name, _unit in (('toe', 'rad'), ('camber', 'rad'), ('caster', 'rad'),
                     ('kingpin_inclination', 'rad'), ('scrub_radius', 'm'),
                     ('mechanical_trail', 'm')):
    _design_value(_name, _unit, f'{_name} at design (left wheel)')


@metric('bump_steer', 'rad/m', (PAR,), doc='d toe / d wheel travel')
def _bump_steer(c: Context) -> float:
    return slope(c[PAR], 'toe', 'wheel_travel')


@metric('camber_gain', 'rad/m', (PAR,), doc='d camber / d wheel travel')
def _camber_gain(c: Context) -> float:
    return slope(c[PAR], 'camber', 'wheel_travel')


@metric('track_change', 'm/m', (PAR,), doc='d contact-point y / d wheel travel')
def _track_change(c: Context) -> float:
    return slope(c[PAR], 'contact_point', 'wheel_travel', y_index=(1,))


@metric('wheelbase_change', 'm/m', (PAR,), doc='d contact-point x / d wheel travel')
def _wheelbase_change(c: Context) -> float:
    return slope(c[PAR], 'contact_point', 'wheel_travel', y_index=(0,))


@metric('wheel_rate', 'N/m', (PAR,), doc='d pad force / d wheel travel')
def _wheel_rate(c: Context) -> float:
    return slope(c[PAR], 'pad_force', 'wheel_travel')


@metric('ride_rate', 'N/m', (PAR,), doc='wheel rate in series with the tire')
def _ride_rate(c: Context) -> float:
    kw, kt = _wheel_rate(c), c.tire_vertical_stiffness
    return kw * kt / (kw + kt)


@metric('installation_ratio', '-', (PAR,), doc='-d spring length / d wheel travel')
def _installation_ratio(c: Context) -> float:
    return -slope(c[PAR], 'spring_length', 'wheel_travel')


@metric('roll_centre_height_kinematic', 'm', (PAR,),
        doc='kinematic roll centre (front-view instant centres) at design')
def _roll_centre_kinematic(c: Context) -> float:
    return float(design(c[PAR], 'roll_centre_height'))


for _name, _unit in (('fvsa_length', 'm'), ('svsa_length', 'm'), ('svsa_angle', 'rad')):
    _design_value(_name, _unit, f'{_name} at design (left wheel)')
for _name, _channel, _k in (('front_view_instant_centre_y', 'front_view_instant_centre', 1),
                            ('front_view_instant_centre_z', 'front_view_instant_centre', 2),
                            ('side_view_instant_centre_x', 'side_view_instant_centre', 0),
                            ('side_view_instant_centre_z', 'side_view_instant_centre', 2)):
    metric(_name, 'm', (PAR,), doc=f'{_channel} at design (left wheel)')(
        lambda c, ch=_channel, k=_k: float(design(c[PAR], ch)[0, k]))


# --- opposite wheel travel ------------------------------------------------------


def _roll_rates(result: EventResult) -> tuple[float, float]:
    """
    Return the roll angle's and the pads' roll moment's rates at design.

    Roll angle phi = atan((z_R - z_L) / t) (rad, ISO: right side down
    positive), moment M = (F_R - F_L) t / 2 (N*m), t the design track.
    """
    t = float(design(result, 'track'))
    z = design(result, 'wheel_travel')
    dz, df = rate(result, 'wheel_travel'), rate(result, 'pad_force')
    u = (z[1] - z[0]) / t
    return float((dz[1] - dz[0]) / t / (1.0 + u * u)), float(0.5 * t * (df[1] - df[0]))


def _roll_stiffness_of(result: EventResult) -> float:
    dphi, dm = _roll_rates(result)
    return dm / dphi


@metric('roll_stiffness', 'N*m/rad', (OPP,), doc='d roll moment / d roll angle')
def _roll_stiffness(c: Context) -> float:
    return _roll_stiffness_of(c[OPP])


@metric('roll_stiffness_no_bar', 'N*m/rad', (BARE,), doc='roll stiffness without the bar')
def _roll_stiffness_no_bar(c: Context) -> float:
    return _roll_stiffness_of(c[BARE])


@metric('roll_stiffness_bar', 'N*m/rad', (OPP, BARE), doc='the bar share of roll stiffness')
def _roll_stiffness_bar(c: Context) -> float:
    return _roll_stiffness(c) - _roll_stiffness_no_bar(c)


@metric('roll_steer', 'rad/rad', (OPP,), doc='d mean steer angle / d roll angle')
def _roll_steer(c: Context) -> float:
    dphi, _ = _roll_rates(c[OPP])
    return float(rate(c[OPP], 'steer_angle').mean()) / dphi


@metric('roll_camber', 'rad/rad', (OPP,), doc='d camber to the ground (left) / d roll angle')
def _roll_camber(c: Context) -> float:
    dphi, _ = _roll_rates(c[OPP])
    return float(rate(c[OPP], 'camber')[0]) / dphi - 1.0


# --- lateral force, aligning torque ---------------------------------------------


def _per_newton(result: EventResult, channel: str, force: tuple[str, int],
                down: bool = False) -> np.ndarray:
    """Return both wheels' d channel / d applied force at design."""
    applied = rate(result, force[0], down)[(0, *force[1:])]
    return rate(result, channel, down) / applied


_FY = ('contact_force', 1)


@metric('lateral_compliance_steer', 'rad/N', (LAT,),
        doc='toe per N of lateral force directed inboard, both wheels averaged')
def _lateral_steer(c: Context) -> float:
    return float(np.mean(-SIDE_SIGNS * _per_newton(c[LAT], 'toe', _FY)))


@metric('lateral_compliance_camber', 'rad/N', (LAT,),
        doc='camber per N of lateral force directed inboard, both wheels averaged')
def _lateral_camber(c: Context) -> float:
    return float(np.mean(-SIDE_SIGNS * _per_newton(c[LAT], 'camber', _FY)))


@metric('lateral_stiffness', 'N/m', (LAT,), doc='dFy / d contact-point y, both wheels averaged')
def _lateral_stiffness(c: Context) -> float:
    return _stiffness(float(np.mean(_per_newton(c[LAT], 'contact_point', _FY)[:, 1])))


@metric('roll_centre_height_force', 'm', (LAT,),
        doc='force-based roll centre: -y_cp dF_pad/dFy, both wheels averaged')
def _roll_centre_force(c: Context) -> float:
    y = design(c[LAT], 'contact_point')[:, 1]
    return float(np.mean(-y * _per_newton(c[LAT], 'pad_force', _FY)))


@metric('aligning_torque_compliance_steer', 'rad/(N*m)', (ALIGN,),
        doc='d steer angle / d Mz, both wheels averaged')
def _aligning_steer(c: Context) -> float:
    return float(np.mean(_per_newton(c[ALIGN], 'steer_angle', ('contact_moment', 2))))


# --- longitudinal force -----------------------------------------------------------

# Braking acts at the contact point (the load for F < 0, rates down the sweep), traction at
# the wheel centre (F > 0, rates up): one-sided derivatives at design.
_BRAKE, _DRIVE = (('contact_force', 0), True), (('centre_force', 0), False)


def _lon(c: Context, channel: str, side: tuple[tuple[str, int], bool]) -> np.ndarray:
    force, down = side
    return _per_newton(c[LON], channel, force, down)


# Wheel-centre compliance for both (K&C practice): under braking the locked wheel winds up
# and rolls on the floating pad, so the lowest point of the wheel is not the tire material
# the force acts on.
@metric('longitudinal_stiffness_braking', 'N/m', (LON,), doc='dFx / d wheel-centre x, Fx < 0')
def _lon_brake(c: Context) -> float:
    return _stiffness(float(_lon(c, 'wheel_centre', _BRAKE)[0, 0]))


@metric('longitudinal_stiffness_traction', 'N/m', (LON,), doc='dFx / d wheel-centre x, Fx > 0')
def _lon_drive(c: Context) -> float:
    return _stiffness(float(_lon(c, 'wheel_centre', _DRIVE)[0, 0]))


@metric('longitudinal_compliance_steer_braking', 'rad/N', (LON,), doc='d toe / dFx, Fx < 0')
def _lon_steer(c: Context) -> float:
    return float(_lon(c, 'toe', _BRAKE)[0])


def _tan_brake(c: Context) -> float:
    """Pad-load change per N of braking: the tangent of the side-view force line."""
    return -float(_lon(c, 'pad_force', _BRAKE)[0])


def _tan_drive(c: Context) -> float:
    return float(_lon(c, 'pad_force', _DRIVE)[0])


@metric('svsa_angle_braking', 'rad', (LON,), doc='side-view force-line angle, braking')
def _svsa_brake(c: Context) -> float:
    return float(np.arctan(_tan_brake(c)))


@metric('svsa_angle_traction', 'rad', (LON,), doc='side-view force-line angle, traction')
def _svsa_drive(c: Context) -> float:
    return float(np.arctan(_tan_drive(c)))


def _anti(c: Context, brake: bool) -> float:
    front = c[LON].axle == 'front'
    ratio = c.wheelbase / c.cg_height * 100.0  # type: ignore[operator]
    if brake:
        return (1.0 if front else -1.0) * _tan_brake(c) * c.brake_fraction * ratio
    return (-1.0 if front else 1.0) * _tan_drive(c) * c.drive_fraction * ratio


for _name, _axle, _brake in (('anti_dive', 'front', True),
                             ('anti_lift_braking', 'rear', True),
                             ('anti_lift_traction', 'front', False),
                             ('anti_squat', 'rear', False)):
    metric(_name, '%', (LON,), ('cg_height', 'wheelbase'), _axle,
           doc='anti-pitch from the side-view force line')(lambda c, b=_brake: _anti(c, b))


# --- steering ---------------------------------------------------------------------


@metric('steering_ratio', '-', (STEER,), doc='d steering-wheel angle / d mean road-wheel angle')
def _steering_ratio(c: Context) -> float:
    result = c[STEER]
    return float(rate(result, 'steering_wheel_angle') / rate(result, 'steer_angle').mean())


@metric('ackermann', '%', (STEER,), ('wheelbase',), doc='Ackermann % at 20 deg inner angle')
def _ackermann_metric(c: Context) -> float:
    return _ackermann(c[STEER].channels, c.wheelbase)  # type: ignore[arg-type]


def _ackermann(ch: Mapping[str, np.ndarray], wheelbase: float) -> float:
    """
    Return the Ackermann % in a left turn at the reference inner (left) wheel angle.

    (inner - outer) / (inner - ideal outer) * 100, ideal outer from the
    turn centre on the rear-axle line and the steering-axis ground points.
    """
    inner, outer = ch['steer_angle'][:, 0], ch['steer_angle'][:, 1]
    order = np.argsort(inner)
    reference = min(ACKERMANN_REFERENCE_ANGLE, 0.8 * float(inner.max()))
    delta_o = float(np.interp(reference, inner[order], outer[order]))
    mid = int(np.argmin(np.abs(inner)))
    ground = ch['steering_axis_ground'][mid]
    pivot_track = float(ground[0, 1] - ground[1, 1])
    ideal = np.arctan(wheelbase / (wheelbase / np.tan(reference) + pivot_track))
    return float((reference - delta_o) / (reference - ideal) * 100.0)


def derived_metrics(
    results: Mapping[str, EventResult],
    tire_vertical_stiffness: float,
    *,
    cg_height: float | None = None,
    wheelbase: float | None = None,
    brake_fraction: float = 1.0,
    drive_fraction: float = 1.0,
) -> dict[str, tuple[float, str]]:
    """
    Evaluate every registered metric whose events (and vehicle data) are present.

    Returns name -> (value, SI unit). ``cg_height``/``wheelbase`` enable the
    anti-pitch percentages and the Ackermann figure;
    ``brake_fraction``/``drive_fraction`` are this axle's share of the
    braking and driving force.
    """
    ctx = Context(results, tire_vertical_stiffness, cg_height, wheelbase, brake_fraction,
                  drive_fraction)
    given = {'cg_height': cg_height, 'wheelbase': wheelbase}
    out: dict[str, tuple[float, str]] = {}
    for name, m in METRICS.items():
        if not all(e in results for e in m.events):
            continue
        if any(given[k] is None for k in m.needs):
            continue
        if m.axle is not None and results[m.events[0]].axle != m.axle:
            continue
        out[name] = (float(m.compute(ctx)), m.unit)
    return out


__all__ = ['METRICS', 'MetricDef', 'Context', 'derived_metrics', 'metric', 'rate', 'slope',
           'design', 'slope_at', 'TRAVEL_WINDOW', 'FORCE_WINDOW']
