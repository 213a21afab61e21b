# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Suspension templates: topology of one (left) corner by hard-point names.

A template names its parts, the ideal joints between them, the massless
two-force links, where the spring and damper act, which part carries the
anti-roll-bar drop link and how the steering axis is found. It knows no
numbers: :mod:`.assembly` resolves the hard points, mirrors the corner to the
right side, replaces joints by bushings where the input has one, and adds the
rig, the rack and the bar. Adding a template is adding a class here and an
entry in ``TEMPLATES``.

Arm pivots on the body are a spherical joint at the front pivot plus an
in-line joint (2 rows) at the rear one -- together exactly a revolute joint --
so a bushing can replace either pivot on its own.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from vd_data_server.schema import TEMPLATE_POINTS

from .joints import GROUND, JointKind

STEERING = 'steering'  # the rack on a steered axle, else the body



@dataclass(frozen=True)
class PartDef:
    """A rigid part; its centre of mass is the centroid of ``points``."""

    name: str
    points: tuple[str, ...]


@dataclass(frozen=True)
class JointDef:
    """
    An ideal joint at hard point ``point`` (its connection key).

    Between ``inboard`` and ``outboard``; ``axis`` = (from, to) hard points giving the
    joint axis (in-line, cylindrical) or, for a universal joint, the link
    direction its default cross is perpendicular to.
    """

    kind: JointKind
    point: str
    inboard: str
    outboard: str
    axis: tuple[str, str] | None = None


@dataclass(frozen=True)
class LinkDef:
    """Massless two-force link (ball joints at both ends), e.g. a tie rod."""

    name: str
    inboard_point: str
    inboard: str
    outboard_point: str
    outboard: str


@dataclass(frozen=True)
class LineDef:
    """A force line from hard point ``upper`` on the body to ``lower`` on ``part``."""

    upper: str
    lower: str
    part: str


@dataclass(frozen=True)
class Topology:
    """
    One corner's topology.

    ``tracked`` maps reported hard points to the part whose motion they follow
    (default: the part listing them first).
    """

    parts: tuple[PartDef, ...]
    joints: tuple[JointDef, ...]
    links: tuple[LinkDef, ...]
    spring: LineDef
    damper: LineDef
    arb_part: str
    wheel_part: str = 'upright'
    tracked: Mapping[str, str] = field(default_factory=dict)
    #: beam members of each part when it is made flexible (pairs of its hard points);
    #: links are one member from inboard to outboard point
    frames: Mapping[str, tuple[tuple[str, str], ...]] = field(default_factory=dict)
    #: body-side hard points a subframe carries (front to rear), when one is modelled
    subframe_points: tuple[str, ...] = ()

    def flexible_components(self, with_bar: bool) -> tuple[str, ...]:
        """Names that may be made flexible: parts, links, the anti-roll bar, the subframe."""
        names = tuple(p.name for p in self.parts) + tuple(link.name for link in self.links)
        return names + (('anti_roll_bar',) if with_bar else ()) + ('subframe',)


class SuspensionTemplate(Protocol):
    """What the assembly needs from a suspension type."""

    name: str
    required_points: tuple[str, ...]

    def topology(self) -> Topology:
        """Return the corner's parts, joints, links and force lines."""
        ...

    def steering_axis(self, points: Mapping[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        """
        Return the upper and lower points (n, 3) of the steering axis.

        From the current hard-point positions ``points`` (name -> (n, 3)).
        """
        ...


def _arm(prefix: str, part: str, outer_part: str) -> tuple[JointDef, ...]:
    """Return an A-arm's joints: revolute on the body (sphere + in-line), ball joint outboard."""
    front, rear, outer = f'{prefix}_front', f'{prefix}_rear', f'{prefix}_outer'
    return (
        JointDef('spherical', front, GROUND, part),
        JointDef('inline', rear, GROUND, part, axis=(front, rear)),
        JointDef('spherical', outer, part, outer_part),
    )


def _arm_frame(prefix: str) -> tuple[tuple[str, str], ...]:
    return ((f'{prefix}_front', f'{prefix}_outer'), (f'{prefix}_rear', f'{prefix}_outer'))


def _star(centre: str, *points: str) -> tuple[tuple[str, str], ...]:
    """Knuckle arms: a beam from the spindle (wheel centre) to each joint."""
    return tuple((centre, p) for p in points)


def _closest_point(a0: np.ndarray, a1: np.ndarray, b0: np.ndarray, b1: np.ndarray) -> np.ndarray:
    """Midpoint of the common perpendicular of lines a0-a1 and b0-b1 (n, 3)."""
    u, v, w = a1 - a0, b1 - b0, a0 - b0
    a, b, c = (u * u).sum(-1), (u * v).sum(-1), (v * v).sum(-1)
    d, e = (u * w).sum(-1), (v * w).sum(-1)
    den = a * c - b * b  # > 0 unless the links are parallel (no virtual pivot)
    s, t = (b * e - c * d) / den, (a * e - b * d) / den
    return 0.5 * (a0 + s[..., None] * u + b0 + t[..., None] * v)


class DoubleWishbone:
    """
    Upper and lower A-arms, tie rod; spring and damper on the lower arm.

    Steering (kingpin) axis: through the two outer ball joints.
    """

    name = 'double_wishbone'
    required_points = TEMPLATE_POINTS[name]

    def topology(self) -> Topology:
        return Topology(
            parts=(
                PartDef('upright', ('uca_outer', 'lca_outer', 'tierod_outer', 'wheel_centre')),
                PartDef('lca', ('lca_front', 'lca_rear', 'lca_outer')),
                PartDef('uca', ('uca_front', 'uca_rear', 'uca_outer')),
            ),
            joints=_arm('lca', 'lca', 'upright') + _arm('uca', 'uca', 'upright'),
            links=(LinkDef('tierod', 'tierod_inner', STEERING, 'tierod_outer', 'upright'),),
            spring=LineDef('spring_upper', 'spring_lower', 'lca'),
            damper=LineDef('damper_upper', 'damper_lower', 'lca'),
            arb_part='lca',
            frames={'upright': _star('wheel_centre', 'uca_outer', 'lca_outer', 'tierod_outer'),
                    'lca': _arm_frame('lca'), 'uca': _arm_frame('uca')},
            subframe_points=('lca_front', 'lca_rear'),
        )

    def steering_axis(self, points: Mapping[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        return points['uca_outer'], points['lca_outer']


class MacPherson:
    """
    Lower A-arm, tie rod and strut.

    The strut rod hangs from the body on a
    universal joint at ``strut_top`` (the top mount; the joint only stops the
    rod's spin) and slides in the upright's tube (cylindrical joint along
    strut_top -> strut_lower). Spring and damper act along the strut.

    Steering axis: top mount to lower ball joint.
    """

    name = 'macpherson'
    required_points = TEMPLATE_POINTS[name]

    def topology(self) -> Topology:
        return Topology(
            parts=(
                PartDef('upright', ('lca_outer', 'tierod_outer', 'strut_lower', 'wheel_centre')),
                PartDef('lca', ('lca_front', 'lca_rear', 'lca_outer')),
                PartDef('strut', ('strut_top', 'strut_lower')),
            ),
            joints=_arm('lca', 'lca', 'upright')
            + (
                JointDef('universal', 'strut_top', GROUND, 'strut',
                         axis=('strut_top', 'strut_lower')),
                JointDef('cylindrical', 'strut_lower', 'strut', 'upright',
                         axis=('strut_lower', 'strut_top')),
            ),
            links=(LinkDef('tierod', 'tierod_inner', STEERING, 'tierod_outer', 'upright'),),
            spring=LineDef('strut_top', 'strut_lower', 'upright'),
            damper=LineDef('strut_top', 'strut_lower', 'upright'),
            arb_part='upright',
            tracked={'strut_top': 'strut'},
            frames={'upright': _star('wheel_centre', 'lca_outer', 'tierod_outer', 'strut_lower'),
                    'lca': _arm_frame('lca'), 'strut': (('strut_top', 'strut_lower'),)},
            subframe_points=('lca_front', 'lca_rear'),
        )

    def steering_axis(self, points: Mapping[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        return points['strut_top'], points['lca_outer']


class MultiLink:
    """
    Five-link, as Chrono's MultiLink.

    Upper A-arm (two links on one ball joint), lateral link, trailing link
    (universal joint on the body; carries spring, damper and bar link) and
    tie rod.

    Steering axis: upper ball joint to the virtual lower pivot, the midpoint
    of the common perpendicular of the lateral and trailing link lines.
    """

    name = 'multilink'
    required_points = TEMPLATE_POINTS[name]

    def topology(self) -> Topology:
        return Topology(
            parts=(
                PartDef(
                    'upright',
                    ('upper_outer', 'lateral_outer', 'trailing_outer', 'tierod_outer',
                     'wheel_centre'),
                ),
                PartDef('upper_arm', ('upper_front', 'upper_rear', 'upper_outer')),
                PartDef('trailing_link', ('trailing_inner', 'trailing_outer')),
            ),
            joints=_arm('upper', 'upper_arm', 'upright')
            + (
                JointDef(
                    'universal', 'trailing_inner', GROUND, 'trailing_link',
                    axis=('trailing_inner', 'trailing_outer'),
                ),
                JointDef('spherical', 'trailing_outer', 'trailing_link', 'upright'),
            ),
            links=(
                LinkDef('lateral_link', 'lateral_inner', GROUND, 'lateral_outer', 'upright'),
                LinkDef('tierod', 'tierod_inner', STEERING, 'tierod_outer', 'upright'),
            ),
            spring=LineDef('spring_upper', 'spring_lower', 'trailing_link'),
            damper=LineDef('damper_upper', 'damper_lower', 'trailing_link'),
            arb_part='trailing_link',
            frames={'upright': _star('wheel_centre', 'upper_outer', 'lateral_outer',
                                     'trailing_outer', 'tierod_outer'),
                    'upper_arm': _arm_frame('upper'),
                    'trailing_link': (('trailing_inner', 'trailing_outer'),)},
            subframe_points=('upper_front', 'lateral_inner', 'upper_rear', 'tierod_inner'),
        )

    def steering_axis(self, points: Mapping[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        lower = _closest_point(
            points['lateral_inner'], points['lateral_outer'],
            points['trailing_inner'], points['trailing_outer'],
        )
        return points['upper_outer'], lower


TEMPLATES: dict[str, SuspensionTemplate] = {
    'macpherson': MacPherson(),
    'double_wishbone': DoubleWishbone(),
    'multilink': MultiLink(),
}
