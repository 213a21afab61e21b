# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
ISO 3888-2:2011 obstacle-avoidance (severe lane change) track and its cone check.

**Track** (Table 1 of the standard; b the vehicle width without mirrors, m): five
sections of fixed length, 61 m in all --

====== ======== ==================== ==================================================
section length   width                lateral position
====== ======== ==================== ==================================================
1      12       1.1 b + 0.25         the entry lane, centred on the approach (y = 0)
2      13.5     --                   the lane change
3      11       b + 1                the obstacle-avoidance lane: its near boundary
                                     1 m beyond the far boundary of section 1
4      12.5     --                   the return
5      12       1.3 b + 0.25, >= 3   the exit lane, its outer boundary in line with
                                     the outer boundary of section 1
====== ======== ==================== ==================================================

``direction`` 'left' (the usual layout: the avoidance lane to the left, +y in ISO 8855)
or 'right' mirrors it. The track limits are the lines tangential to the cones' bases;
sections 2 and 4 have none.

**Cone check**: the vehicle is its plan-view rectangle (length, width, the reference
point's distance behind the front), placed at each sample of the run's pose
(x, y, yaw in the course's frame, whose origin is the start of section 1 on the
approach centre line). In sections 1, 3 and 5 the vehicle must stay between the track
limits: a limit is violated (its cones hit or the lane left on that side) when the
rectangle meets the region beyond it along its section -- an exact test of two convex
quadrilaterals (separating axes), so a vehicle that drives past a lane also fails. The
margin of each limit is the smallest distance between the rectangle and that region over
the run (0 where violated).

Signals in SI (m, rad). ISO 3888-2 grades a run subjectively; the cones are its
objective part, which is what this module computes.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np


@dataclass(frozen=True)
class Boundary:
    """One track limit: the segment x0..x1 at lateral position y of section ``section``."""

    section: int
    side: str  # 'left' or 'right' (ISO 8855: left is +y)
    x0: float
    x1: float
    y: float


@dataclass(frozen=True)
class Course:
    """The sections' lengths and widths and the six boundaries of the gated sections."""

    vehicle_width: float
    direction: str
    lengths: tuple[float, ...]
    widths: dict[int, float]
    boundaries: tuple[Boundary, ...]

    @property
    def length(self) -> float:
        """Total length of the track, m (61 m)."""
        return float(sum(self.lengths))

    def centre(self, section: int) -> float:
        """Lateral position of a gated section's centre line, m."""
        left = next(b.y for b in self.boundaries if b.section == section and b.side == 'left')
        right = next(b.y for b in self.boundaries if b.section == section and b.side == 'right')
        return 0.5 * (left + right)


LENGTHS = (12.0, 13.5, 11.0, 12.5, 12.0)  # m, sections 1..5
OFFSET = 1.0  # m, from the far boundary of section 1 to the near boundary of section 3
MIN_EXIT_WIDTH = 3.0  # m, section 5


def course(vehicle_width: float, direction: str = 'left') -> Course:
    """Lay out the ISO 3888-2 track for a vehicle ``vehicle_width`` m wide."""
    if not vehicle_width > 0.0:
        raise ValueError(f'the vehicle width must be positive (got {vehicle_width} m)')
    if direction not in ('left', 'right'):
        raise ValueError(f"the lane change goes 'left' or 'right' (got '{direction}')")
    b = vehicle_width
    w1, w3, w5 = 1.1 * b + 0.25, b + 1.0, max(1.3 * b + 0.25, MIN_EXIT_WIDTH)
    starts = np.concatenate([[0.0], np.cumsum(LENGTHS)])
    # in the left-hand layout: near = right side (low y), far = left side (high y)
    near1, far1 = -0.5 * w1, 0.5 * w1
    near3 = far1 + OFFSET
    far3 = near3 + w3
    near5 = near1
    far5 = near5 + w5
    sign = 1.0 if direction == 'left' else -1.0
    limits = {1: (near1, far1), 3: (near3, far3), 5: (near5, far5)}
    out = []
    for section, (near, far) in limits.items():
        x0, x1 = float(starts[section - 1]), float(starts[section])
        lo, hi = sorted((sign * near, sign * far))
        out.append(Boundary(section, 'right', x0, x1, lo))
        out.append(Boundary(section, 'left', x0, x1, hi))
    return Course(b, direction, LENGTHS, {1: w1, 3: w3, 5: w5}, tuple(out))


@dataclass(frozen=True)
class ConeCheck:
    """
    The run through the track: passed, the hits and the margin of every boundary.

    ``passed``: no cone hit and the whole vehicle beyond the end of section 5. A margin
    stays infinite for a boundary the run never came within a vehicle width of.
    """

    passed: bool
    hits: tuple[tuple[int, str, float], ...]  # (section, side, first time violated)
    margins: dict[tuple[int, str], float]  # (section, side) -> m (0 where hit)
    covered: bool  # the run's rectangle reached beyond the end of section 5


def footprint(x: float, y: float, yaw: float, length: float, width: float,
              front: float) -> np.ndarray:
    """Return the rectangle's corners (4 x 2); the reference point is ``front`` m behind."""
    c, s = math.cos(yaw), math.sin(yaw)
    local = np.array([[front, 0.5 * width], [front, -0.5 * width],
                      [front - length, -0.5 * width], [front - length, 0.5 * width]])
    return np.column_stack([x + c * local[:, 0] - s * local[:, 1],
                            y + s * local[:, 0] + c * local[:, 1]])


OUTSIDE = 100.0  # m: the depth of the region beyond a track limit the check looks at


def _outside(b: Boundary) -> np.ndarray:
    """Return the region beyond a track limit along its section (4 x 2 corners)."""
    far = b.y + (OUTSIDE if b.side == 'left' else -OUTSIDE)
    return np.array([[b.x0, b.y], [b.x1, b.y], [b.x1, far], [b.x0, far]])


def _axes(poly: np.ndarray) -> list[np.ndarray]:
    return [np.array([-(poly[(i + 1) % 4] - poly[i])[1], (poly[(i + 1) % 4] - poly[i])[0]])
            for i in range(2)]


def _overlap(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two convex quadrilaterals meet (separating axes)."""
    for axis in _axes(a) + _axes(b):
        pa, pb = a @ axis, b @ axis
        if pa.max() < pb.min() or pb.max() < pa.min():
            return False
    return True


def _point_segment(point: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    ab = b - a
    t = float(np.clip((point - a) @ ab / (ab @ ab), 0.0, 1.0))
    return float(np.linalg.norm(point - (a + t * ab)))


def _distance(a: np.ndarray, b: np.ndarray) -> float:
    """Distance between two convex quadrilaterals that do not meet (vertex to edge)."""
    best = math.inf
    for p, q in ((a, b), (b, a)):
        for corner in p:
            for i in range(4):
                best = min(best, _point_segment(corner, q[i], q[(i + 1) % 4]))
    return best


def check_run(track: Course, t, x, y, yaw, *, length: float, width: float,
              front: float) -> ConeCheck:
    """Check a run's plan-view poses (course frame, SI) against the track's boundaries."""
    t, x, y, yaw = (np.asarray(a, dtype=float) for a in (t, x, y, yaw))
    if not (t.shape == x.shape == y.shape == yaw.shape) or t.ndim != 1 or t.size < 2:
        raise ValueError('t, x, y and yaw must be series of one length (at least two samples)')
    if not (length > 0.0 and width > 0.0 and 0.0 <= front <= length):
        raise ValueError('the vehicle rectangle needs a positive length and width and its '
                         'reference point on it')
    hits: dict[tuple[int, str], float] = {}
    margins = {(b.section, b.side): math.inf for b in track.boundaries}
    reach = -math.inf
    for k in range(t.size):
        corners = footprint(x[k], y[k], yaw[k], length, width, front)
        lo, hi = corners[:, 0].min(), corners[:, 0].max()
        reach = max(reach, lo)
        for b in track.boundaries:
            key = (b.section, b.side)
            if hi < b.x0 - width or lo > b.x1 + width:
                continue  # far from this boundary along the track
            region = _outside(b)
            if _overlap(corners, region):
                hits.setdefault(key, float(t[k]))
                margins[key] = 0.0
            elif margins[key] > 0.0:
                margins[key] = min(margins[key], _distance(corners, region))
    ordered = tuple(sorted(((s, side, when) for (s, side), when in hits.items()),
                           key=lambda h: h[2]))
    covered = bool(reach > track.length)
    return ConeCheck(covered and not hits, ordered, margins, covered)


__all__ = ['LENGTHS', 'OFFSET', 'MIN_EXIT_WIDTH', 'Boundary', 'Course', 'course', 'ConeCheck',
           'footprint', 'check_run']
