# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Plain input data of the K&C suspension model.

Thesis 3.2: hard points, parts and masses, spring, damper, bump and rebound
stops, anti-roll bar, bushings and joints, rack and pinion.

Everything is SI: m, N, N/m, N*m/rad, rad, kg. Positions are in the vehicle
frame of ISO 8855 (x forward, y left, z up), origin on the ground under the
front axle centre at design ride height. Hard points are given for the LEFT
side only; the right side is their mirror image (y -> -y).

An adapter fills these classes from the project's data files; they carry no
behaviour beyond the small curve evaluation and checks of their own shape.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Literal, Union

import numpy as np
from numpy.typing import ArrayLike

from vd_solvers.errors import SolverError
from vd_solvers.flex.component import Condensed, ShapePoint
from vd_solvers.flex.section import Material, Section

Axle = Literal['front', 'rear']
Side = Literal['left', 'right']
SIDES: tuple[Side, Side] = ('left', 'right')

# Mirror factors per side: the left side is given, the right is y -> -y.
SIDE_SIGN: dict[Side, float] = {'left': 1.0, 'right': -1.0}


def mirror(vector: ArrayLike, side: Side) -> np.ndarray:
    """Return the left-side point or direction ``vector`` (3,) as seen on ``side``."""
    out = np.array(vector, dtype=float)
    out[1] *= SIDE_SIGN[side]
    return out


@dataclass(frozen=True, eq=False)
class Curve:
    """
    Piecewise-linear characteristic y(x) with linear extrapolation.

    ``x`` (n,) strictly increasing, ``y`` (n,), n >= 2. Used for force vs
    deflection (N vs m or N*m vs rad) and force vs velocity (dampers).
    ``integral(u)`` is the work from 0 to ``u`` (J for force curves), so a
    force curve is also an exact potential for the quasi-static solver.
    """

    x: np.ndarray
    y: np.ndarray
    # derived in __post_init__: segment slopes, work to each knot, work from x[0] to 0
    _slope: np.ndarray = field(init=False, repr=False)
    _cumulative: np.ndarray = field(init=False, repr=False)
    _origin: float = field(init=False, repr=False)

    def __post_init__(self) -> None:
        x = np.asarray(self.x, dtype=float).reshape(-1)
        y = np.asarray(self.y, dtype=float).reshape(-1)
        if x.size < 2 or x.size != y.size:
            raise SolverError('a curve needs at least two (x, y) points of equal count')
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
            raise SolverError('a curve holds non-finite values')
        if np.any(np.diff(x) <= 0.0):
            raise SolverError('curve abscissae must be strictly increasing')
        object.__setattr__(self, 'x', x)
        object.__setattr__(self, 'y', y)
        slope = np.diff(y) / np.diff(x)
        # Work from x[0] to each knot, for the exact integral of the polyline.
        cumulative = np.concatenate(([0.0], np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(x))))
        object.__setattr__(self, '_slope', slope)
        object.__setattr__(self, '_cumulative', cumulative)
        object.__setattr__(self, '_origin', float(self._raw_integral(np.array(0.0))))

    def _segment(self, u: np.ndarray) -> np.ndarray:
        return np.clip(np.searchsorted(self.x, u, side='right') - 1, 0, self.x.size - 2)

    def value(self, u: ArrayLike) -> np.ndarray:
        """Y at ``u``."""
        u = np.asarray(u, dtype=float)
        i = self._segment(u)
        return self.y[i] + self._slope[i] * (u - self.x[i])

    def slope(self, u: ArrayLike) -> np.ndarray:
        """dy/dx at ``u`` (right-continuous at the knots)."""
        return self._slope[self._segment(np.asarray(u, dtype=float))]

    def _raw_integral(self, u: np.ndarray) -> np.ndarray:
        i = self._segment(u)
        du = u - self.x[i]
        return self._cumulative[i] + self.y[i] * du + 0.5 * self._slope[i] * du * du

    def integral(self, u: ArrayLike) -> np.ndarray:
        """Integral of y from 0 to ``u``."""
        return self._raw_integral(np.asarray(u, dtype=float)) - self._origin

    def evaluate(self, u: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(integral from 0, value, slope) at ``u`` with one segment search."""
        u = np.asarray(u, dtype=float)
        i = self._segment(u)
        du = u - self.x[i]
        value = self.y[i] + self._slope[i] * du
        work = self._cumulative[i] + self.y[i] * du + 0.5 * self._slope[i] * du * du
        return work - self._origin, value, self._slope[i]


Stiffness = Union[float, Curve]


@dataclass(frozen=True)
class SpringSpec:
    """
    Coil spring acting between the template's spring seats.

    Give exactly one of ``rate`` (N/m) and ``curve`` (compression force N,
    positive pushing the seats apart, vs compression from the free length m),
    and exactly one of ``free_length`` (m) and ``preload`` (N, compression
    force at the design length). With neither, the preload is trimmed so the
    design wheel-pad load equals ``SuspensionInput.corner_load``.
    """

    rate: float | None = None
    curve: Curve | None = None
    free_length: float | None = None
    preload: float | None = None


@dataclass(frozen=True)
class DamperSpec:
    """
    Damper force (N, positive resisting compression) vs compression velocity (m/s).

    Carried for the dynamic models; zero force quasi-statically.
    """

    curve: Curve


@dataclass(frozen=True)
class StopSpec:
    """
    Bump or rebound stop on the damper line.

    ``clearance`` (m): free travel of the damper length from design before
    contact (compression for the bump stop, extension for the rebound stop).
    ``curve``: stop force (N, >= 0) vs compression of the stop itself (m).
    """

    clearance: float
    curve: Curve


@dataclass(frozen=True)
class Bushing:
    """
    Six-direction elastic connection replacing an ideal joint.

    ``stiffness``: (x, y, z, rx, ry, rz) in the bushing frame, N/m and
    N*m/rad, each a rate or a force-deflection :class:`Curve`.
    ``damping``: same order, N*s/m and N*m*s/rad (carried, unused here).
    ``axial``: optional direction (3,) of the bushing's local z axis in the
    vehicle frame (left side); default: the bushing frame is the vehicle frame.
    """

    stiffness: tuple[Stiffness, ...]  # six (``validate`` checks)
    damping: tuple[float, ...] = (0.0,) * 6
    axial: np.ndarray | None = None


@dataclass(frozen=True)
class StabilizerSpec:
    """
    Torsion anti-roll bar.

    Bar axis through hard point ``arb_pivot`` parallel to y; drop link from
    ``arb_link_lower`` (on the part the template names) to ``arb_link_upper``
    (end of the bar arm).
    """

    torsional_stiffness: float  # N*m/rad, twist between the two bar ends


@dataclass(frozen=True)
class SteeringSpec:
    """
    Rack and pinion; the tie-rod inner points sit on the rack.

    The rack follows the steering-wheel command through the housing mount
    (``rack_stiffness``) in series with the column twist
    (``column_stiffness``, seen at the rack as column_stiffness/rack_ratio^2);
    both None: the rack is held rigidly.
    """

    rack_ratio: float  # m of rack travel per rad of steering-wheel angle
    rack_travel_limit: float  # m, each way from centre
    rack_stiffness: float | None = None  # N/m rack to housing; None = rigid
    column_stiffness: float | None = None  # N*m/rad steering column; None = rigid

    def rack_compliance(self) -> float:
        """m/N of rack travel per rack force with the steering wheel held."""
        compliance = 0.0
        if self.rack_stiffness is not None:
            compliance += 1.0 / self.rack_stiffness
        if self.column_stiffness is not None:
            compliance += self.rack_ratio**2 / self.column_stiffness
        return compliance


@dataclass(frozen=True)
class FlexSpec:
    """
    One flexible component (thesis 3.3).

    A beam frame generated from the hard points of the part it replaces, or an
    imported reduced stiffness.

    Beam frame: ``material``, ``section`` (the anti-roll bar's arms may have
    ``arm_section``), ``shape_points`` (bends, defined relative to the hard
    points), ``elements_per_member``. Imported: ``imported`` holds the reduced
    free-free stiffness of the attachment nodes (left side, vehicle axes), its
    node names (hard points) and positions, mass and centre of mass; the nodes
    must sit on the hard points. ``source`` names where the data came from.
    """

    material: Material | None = None
    section: Section | None = None
    shape_points: tuple[ShapePoint, ...] = ()
    elements_per_member: int = 1
    arm_section: Section | None = None
    imported: Condensed | None = None
    source: str = ''


@dataclass(frozen=True)
class SuspensionInput:
    """
    One axle's suspension as a K&C rig sees it.

    ``hardpoints``: left-side points (3,) in m by template name (see
    ``templates.TEMPLATES[...].required_points``). ``bushings`` are keyed by the
    hard point of the connection they replace. ``masses`` (kg) are keyed by the
    template's part names plus ``"wheel"`` (at the wheel centre); a part's
    centre of mass is the centroid of its hard points (thesis 5.1).
    ``joint_axes``: optional universal-joint cross axes (body-side, part-side),
    keyed by the joint's hard point. ``flexible``: components modelled as
    flexible bodies (part or link names of the template, or
    ``anti_roll_bar``); their mass and centre of mass come from the FE model
    and replace ``masses`` of that part. ``camber``/``toe``: static design
    alignment (rad; ISO: positive toe = toe-in, negative camber = top inward).
    ``tire_radius``: loaded radius (m) at ``corner_load`` (N, the static design
    wheel load).
    """

    template: str
    axle: Axle
    hardpoints: Mapping[str, np.ndarray]
    spring: SpringSpec
    tire_radius: float
    tire_vertical_stiffness: float
    corner_load: float
    damper: DamperSpec | None = None
    bump_stop: StopSpec | None = None
    rebound_stop: StopSpec | None = None
    bushings: Mapping[str, Bushing] = field(default_factory=dict)
    stabilizer: StabilizerSpec | None = None
    steering: SteeringSpec | None = None
    camber: float = 0.0
    toe: float = 0.0
    masses: Mapping[str, float] = field(default_factory=dict)
    joint_axes: Mapping[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    flexible: Mapping[str, FlexSpec] = field(default_factory=dict)


def _positive(value: float | None, what: str) -> None:
    if value is not None and not (np.isfinite(value) and value > 0.0):
        raise SolverError(f'{what} must be a positive finite number, got {value!r}')


def validate(inp: SuspensionInput) -> None:
    """
    Check the scalar data of ``inp``; hard points are checked by the template.

    Raises :class:`SolverError` naming the offending field.
    """
    if inp.axle not in ('front', 'rear'):
        raise SolverError(f"axle must be 'front' or 'rear', got {inp.axle!r}")
    s = inp.spring
    if (s.rate is None) == (s.curve is None):
        raise SolverError('spring: give exactly one of rate and curve')
    if s.free_length is not None and s.preload is not None:
        raise SolverError('spring: give at most one of free_length and preload')
    _positive(s.rate, 'spring rate')
    _positive(s.free_length, 'spring free_length')
    _positive(inp.tire_radius, 'tire_radius')
    _positive(inp.tire_vertical_stiffness, 'tire_vertical_stiffness')
    _positive(inp.corner_load, 'corner_load')
    for name, stop in (('bump_stop', inp.bump_stop), ('rebound_stop', inp.rebound_stop)):
        if stop is not None and not (np.isfinite(stop.clearance) and stop.clearance >= 0.0):
            raise SolverError(f'{name}: clearance must be >= 0 m, got {stop.clearance!r}')
    if inp.stabilizer is not None:
        _positive(inp.stabilizer.torsional_stiffness, 'stabilizer torsional_stiffness')
    if inp.steering is not None:
        if inp.axle != 'front':
            raise SolverError('steering is modelled on the front axle only')
        _positive(inp.steering.rack_ratio, 'steering rack_ratio')
        _positive(inp.steering.rack_travel_limit, 'steering rack_travel_limit')
        _positive(inp.steering.rack_stiffness, 'steering rack_stiffness')
        _positive(inp.steering.column_stiffness, 'steering column_stiffness')
    for name, bushing in inp.bushings.items():
        if len(bushing.stiffness) != 6:
            raise SolverError(f'bushing {name!r}: six stiffnesses (x, y, z, rx, ry, rz) needed')
        for k in bushing.stiffness:
            # Zero is allowed: a bushing may be free about its own axis.
            if not isinstance(k, Curve) and not (np.isfinite(k) and k >= 0.0):
                raise SolverError(f'bushing {name!r}: stiffness must be >= 0, got {k!r}')
    for name, mass in inp.masses.items():
        if not (np.isfinite(mass) and mass >= 0.0):
            raise SolverError(f'mass {name!r} must be >= 0 kg, got {mass!r}')
    for name, spec in inp.flexible.items():
        if spec.imported is None and (spec.material is None or spec.section is None):
            raise SolverError(f'flexible component {name!r}: give a material and a section, '
                              'or an imported stiffness')
    for name, value in (('camber', inp.camber), ('toe', inp.toe)):
        if not (np.isfinite(value) and abs(value) < 0.5):
            raise SolverError(f'{name} must be a finite angle in rad below 0.5, got {value!r}')


def without_bar(inp: SuspensionInput) -> SuspensionInput:
    """``inp`` with the anti-roll bar removed (and its beam model, if flexible)."""
    return replace(inp, stabilizer=None,
                   flexible={k: v for k, v in inp.flexible.items() if k != 'anti_roll_bar'})
