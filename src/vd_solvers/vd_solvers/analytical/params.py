# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Vehicle parameter set of the bicycle and two-track models (thesis 3.1).

One frozen :class:`VehicleParams` carries everything both analytical models
need: mass and its position, tracks, roll centres and roll stiffnesses
(thesis Table 3.1.2), unsprung masses for the unsprung part of the lateral
load transfer (Milliken & Milliken, "Race Car Vehicle Dynamics", ch. 18),
the yaw inertia of the transient single-track model, one
:class:`~vd_solvers.tire.simple.SimpleTire` per axle (thesis eqs. 6-9) and
one :class:`AxleCompliance` per axle: the linear compliance steer, roll steer
and camber that the K&C model of the same configuration measured, and the
tire's pneumatic trail and camber stiffness (zero: the bare-tire models).

Units are SI throughout (m, kg, N, rad); axes follow ISO 8855 (x forward,
y left, z up).  Distances along x are measured rearward from the front axle.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields
import math
from types import MappingProxyType
from typing import TYPE_CHECKING

from vd_solvers.constants import STANDARD_GRAVITY
from vd_solvers.tire.simple import SimpleTire

if TYPE_CHECKING:
    from _typeshed import DataclassInstance

#: the data have no wheel spin inertia: every rung takes I_spin = SPIN_INERTIA_FACTOR
#: m_corner R0^2 (wheel and tire, about 60 % of the corner mass, as a ring-and-disc mix)
SPIN_INERTIA_FACTOR = 0.3

# The axle force peak search (two_track.py) needs a Magic Formula with a
# genuine maximum: 1 < C < 2 makes sin(C * arctan(.)) rise to 1 and fall
# back without changing sign, and E < 1 keeps the arctan argument monotonic.
_SHAPE_MIN = 1.0  # exclusive
_SHAPE_MAX = 2.0  # exclusive
_CURVATURE_MAX = 1.0  # exclusive


@dataclass(frozen=True)
class AxleCompliance:
    """
    Linear steer and camber changes of one axle's wheels (K&C).

    With the tire properties that turn them into slip (all zero: a rigid,
    bare-tire axle).

    Signs (ISO 8855, per wheel; the left and right wheel are mirror images):

    Attributes:
        lateral_compliance_steer: steer angle change (positive to the left)
            per N of lateral force along +y at the contact point, rad/N.  The
            K&C metric ``lateral_compliance_steer`` (toe-in per inward force)
            is the same number.
        lateral_compliance_camber: camber change (top outward) per N of
            inward force at the contact point, rad/N (K&C metric of that name).
        roll_steer: steer angle change (positive to the left) per rad of body
            roll (ISO: right side down positive), rad/rad.
        roll_camber: camber to the road of the left wheel (top outward) per
            rad of body roll, rad/rad.
        aligning_torque_compliance_steer: steer angle change (positive to the
            left) per N*m of moment about +z at the contact point, rad/(N*m).
        pneumatic_trail: of the tire at the static wheel load and zero slip, m.
        camber_stiffness: lateral force towards the side the wheel top leans,
            per rad of lean, at the static wheel load, N/rad.
        rolling_resistance: longitudinal force of the free-rolling tire per
            unit load, -F_x/F_z (the .tir's rolling-resistance moment over the
            loaded radius at the static wheel load), -.
        loaded_radius: of the tire at the static wheel load, m: the lever of the
            rolling-resistance moment M_y = -rolling_resistance F_z R_l, which
            moves load from the front axle to the rear (0: no such moment).
        sources: provenance per attribute name (not part of equality).

    """

    lateral_compliance_steer: float = 0.0
    lateral_compliance_camber: float = 0.0
    roll_steer: float = 0.0
    roll_camber: float = 0.0
    aligning_torque_compliance_steer: float = 0.0
    pneumatic_trail: float = 0.0
    camber_stiffness: float = 0.0
    rolling_resistance: float = 0.0
    loaded_radius: float = 0.0
    sources: Mapping[str, str] = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        _check_finite(self)
        _freeze_sources(self)

    @property
    def is_rigid(self) -> bool:
        """True when no term moves the tire slip away from the axle's kinematic slip."""
        aligning = self.aligning_torque_compliance_steer != 0.0 and self.pneumatic_trail != 0.0
        camber = self.camber_stiffness != 0.0 and (self.roll_camber != 0.0
                                                   or self.lateral_compliance_camber != 0.0)
        return not (self.lateral_compliance_steer != 0.0 or self.roll_steer != 0.0
                    or aligning or camber)


@dataclass(frozen=True)
class VehicleParams:
    """
    Parameters of the analytical vehicle models.

    Attributes:
        mass: total vehicle mass m, kg (sprung + unsprung).
        wheelbase: wheelbase L, m.
        cog_to_front_axle: distance a from the front axle back to the COG, m.
        track_front: front track width t_f, m.
        track_rear: rear track width t_r, m.
        cog_height: COG height h above ground of the whole vehicle, m.
        roll_centre_height_front: front roll-centre height h_f, m.
        roll_centre_height_rear: rear roll-centre height h_r, m.
        roll_stiffness_front: front suspension roll stiffness K_phi_f incl.
            anti-roll bar, N*m/rad (tires taken as rigid, thesis 3.1.2).
        roll_stiffness_rear: rear suspension roll stiffness K_phi_r, N*m/rad.
        yaw_inertia: yaw moment of inertia I_zz about the COG, kg*m^2.
        tire_front: simple tire of one front wheel (eqs. 6-9).
        tire_rear: simple tire of one rear wheel (eqs. 6-9).
        unsprung_mass_front: unsprung mass of the front axle (both
            wheels), kg.  Zero reproduces the thesis' eqs. 3-4 exactly.
        unsprung_mass_rear: unsprung mass of the rear axle (both wheels), kg.
        unsprung_cog_height_front: COG height of the front unsprung mass,
            m (typically the wheel-centre height).
        unsprung_cog_height_rear: COG height of the rear unsprung mass, m.
        g: acceleration of gravity, m/s^2.
        compliance_front: compliance steer/camber of the front axle.
        compliance_rear: compliance steer/camber of the rear axle.
        tire_vertical_stiffness_front: vertical stiffness of one front tire,
            N/m; 0 (the default, the thesis' model) takes the tires as rigid.
            The axle then rolls on its tires by 2 dF_z / (C_z t) besides the
            suspension's roll (see ``two_track.roll_geometry``).
        tire_vertical_stiffness_rear: of one rear tire, N/m.
        wheel_gyroscopic_front: spin inertia over rolling radius of one front
            wheel, I_spin / R, kg*m; 0 (the default, the thesis') leaves out the
            spinning wheels' gyroscopic roll moment, sum I_spin omega r =
            sum (I_spin / R) a_y in a steady turn (see two_track.roll_geometry).
        wheel_gyroscopic_rear: of one rear wheel, kg*m.
        sources: provenance per field name, e.g. ``{"mass": "vehicle.xlsx
            Overview!C4"}``; filled by the vehicle-data adapter.

    """

    mass: float
    wheelbase: float
    cog_to_front_axle: float
    track_front: float
    track_rear: float
    cog_height: float
    roll_centre_height_front: float
    roll_centre_height_rear: float
    roll_stiffness_front: float
    roll_stiffness_rear: float
    yaw_inertia: float
    tire_front: SimpleTire
    tire_rear: SimpleTire
    unsprung_mass_front: float = 0.0
    unsprung_mass_rear: float = 0.0
    unsprung_cog_height_front: float = 0.0
    unsprung_cog_height_rear: float = 0.0
    g: float = STANDARD_GRAVITY
    compliance_front: AxleCompliance = field(default_factory=AxleCompliance)
    compliance_rear: AxleCompliance = field(default_factory=AxleCompliance)
    tire_vertical_stiffness_front: float = 0.0
    tire_vertical_stiffness_rear: float = 0.0
    wheel_gyroscopic_front: float = 0.0
    wheel_gyroscopic_rear: float = 0.0
    # Provenance is not physics: two parameter sets with the same numbers
    # compare equal whatever their sources say.
    sources: Mapping[str, str] = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        _check_finite(self)
        _require(self.mass > 0.0, 'mass', 'must be positive', self.mass)
        _require(self.wheelbase > 0.0, 'wheelbase', 'must be positive', self.wheelbase)
        _require(
            0.0 < self.cog_to_front_axle < self.wheelbase,
            'cog_to_front_axle',
            f'must lie strictly between 0 and the wheelbase {self.wheelbase}',
            self.cog_to_front_axle,
        )
        for name in ('track_front', 'track_rear', 'cog_height', 'yaw_inertia', 'g'):
            _require(getattr(self, name) > 0.0, name, 'must be positive', getattr(self, name))
        for name in (
            'roll_stiffness_front',
            'roll_stiffness_rear',
            'unsprung_mass_front',
            'unsprung_mass_rear',
            'unsprung_cog_height_front',
            'unsprung_cog_height_rear',
            'tire_vertical_stiffness_front',
            'tire_vertical_stiffness_rear',
            'wheel_gyroscopic_front',
            'wheel_gyroscopic_rear',
        ):
            _require(getattr(self, name) >= 0.0, name, 'must not be negative', getattr(self, name))
        # The sprung body must keep mass and lie between the axles, otherwise
        # the sprung axle split of eq. 4 is meaningless.
        sprung = self.mass - self.unsprung_mass_front - self.unsprung_mass_rear
        _require(sprung > 0.0, 'unsprung_mass_front + unsprung_mass_rear',
                 'leaves no sprung mass', sprung)
        sprung_x = (self.mass * self.cog_to_front_axle
                    - self.unsprung_mass_rear * self.wheelbase) / sprung
        _require(
            0.0 < sprung_x < self.wheelbase,
            'unsprung_mass_front/unsprung_mass_rear',
            'put the sprung COG outside the wheelbase',
            sprung_x,
        )
        for name in ('compliance_front', 'compliance_rear'):
            if not isinstance(getattr(self, name), AxleCompliance):
                raise ValueError(f'{name} must be an AxleCompliance, '
                                 f'got {type(getattr(self, name)).__name__}')
        _check_tire('tire_front', self.tire_front, self.axle_load_front / 2.0)
        _check_tire('tire_rear', self.tire_rear, self.axle_load_rear / 2.0)
        # Freeze the provenance too, so the whole parameter set is immutable.
        _freeze_sources(self)

    @property
    def cog_to_rear_axle(self) -> float:
        """Distance b from the COG back to the rear axle, m."""
        return self.wheelbase - self.cog_to_front_axle

    @property
    def weight(self) -> float:
        """Vehicle weight m*g, N."""
        return self.mass * self.g

    @property
    def axle_load_front(self) -> float:
        """Static front axle load N_f = m*g*b/L, N (both wheels)."""
        return self.weight * self.cog_to_rear_axle / self.wheelbase

    @property
    def axle_load_rear(self) -> float:
        """Static rear axle load N_r = m*g*a/L, N (both wheels)."""
        return self.weight * self.cog_to_front_axle / self.wheelbase

    @property
    def roll_stiffness(self) -> float:
        """Total suspension roll stiffness K_phi = K_phi_f + K_phi_r, N*m/rad."""
        return self.roll_stiffness_front + self.roll_stiffness_rear


def _check_finite(params: DataclassInstance) -> None:
    """Every numeric field of the dataclass ``params`` must be finite."""
    for f in fields(params):
        value = getattr(params, f.name)
        if isinstance(value, (int, float)) and not math.isfinite(value):
            raise ValueError(f'{f.name} must be finite, got {value!r}')


def _freeze_sources(params: DataclassInstance) -> None:
    """``params.sources`` may name only its fields; frozen to a read-only mapping."""
    known = {f.name for f in fields(params)} - {'sources'}
    sources = getattr(params, 'sources')
    for key in sources:
        _require(key in known, 'sources', f'names unknown field {key!r}', key)
    object.__setattr__(params, 'sources', MappingProxyType(dict(sources)))


def _require(ok: bool, name: str, message: str, value: object) -> None:
    if not ok:
        raise ValueError(f'{name} {message}, got {value!r}')


def _check_tire(name: str, tire: object, static_load: float) -> None:
    """Reject tires the analytical models cannot use, naming the field."""
    if not isinstance(tire, SimpleTire):
        raise ValueError(f'{name} must be a SimpleTire, got {type(tire).__name__}')
    _require(tire.fz0 > 0.0, f'{name}.fz0', 'must be positive', tire.fz0)
    _require(
        _SHAPE_MIN < tire.shape < _SHAPE_MAX,
        f'{name}.shape',
        f'must lie strictly between {_SHAPE_MIN} and {_SHAPE_MAX} for a force peak',
        tire.shape,
    )
    _require(tire.curvature < _CURVATURE_MAX, f'{name}.curvature',
             f'must be below {_CURVATURE_MAX}', tire.curvature)
    mu = float(tire.friction(static_load))
    _require(mu > 0.0, name,
             f'gives no friction (mu0, mu1) at the static load {static_load:.1f} N', mu)
    stiffness = float(tire.cornering_stiffness(static_load))
    _require(
        stiffness > 0.0,
        name,
        f'gives no cornering stiffness (c0, c1) at the static load {static_load:.1f} N',
        stiffness,
    )
