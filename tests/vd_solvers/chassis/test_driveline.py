# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Driveline: torque map, ratios, axle split and differentials against hand calculations.

Conservation: a differential's wheel torques add up to its input whatever the speeds;
an open one splits equally; a limited-slip one carries at most its locking torque from
the faster wheel to the slower one; a locked (viscous) one by c times the speed difference.
"""
from __future__ import annotations

import numpy as np
import pytest

from vd_solvers.chassis.driveline import Differential, Driveline, Engine

ENGINE = Engine(np.array([80.0, 300.0, 600.0, 700.0]), np.array([150.0, 250.0, 220.0, 180.0]))


def test_engine_map():
    assert ENGINE.torque(190.0, 1.0) == pytest.approx(150.0 + 100.0 * 110.0 / 220.0)
    assert ENGINE.torque(190.0, 0.4) == pytest.approx(0.4 * 200.0)
    assert ENGINE.torque(750.0, 1.0) == 0.0  # beyond the redline
    assert ENGINE.torque(50.0, 1.0) == 0.0  # below idle


@pytest.mark.parametrize('diff', [Differential('open'), Differential('limited_slip', 400.0),
                                  Differential('locked', lock_damping=800.0)])
@pytest.mark.parametrize('speeds', [(50.0, 50.0), (52.0, 48.0), (30.0, 70.0)])
def test_differentials_conserve_torque(diff, speeds):
    left, right = diff.split(1000.0, *speeds)
    assert left + right == pytest.approx(1000.0, abs=1e-9)
    if diff.kind == 'open' or speeds[0] == speeds[1]:
        assert left == pytest.approx(right)
    else:
        slower_left = speeds[0] < speeds[1]
        assert (left > right) == slower_left  # the slower wheel gets more
    if diff.kind == 'limited_slip':
        assert abs(left - right) <= 400.0 + 1e-9
    if diff.kind == 'locked':
        assert right - left == pytest.approx(800.0 * (speeds[0] - speeds[1]))


def test_limited_slip_locks_fully_on_a_spinning_wheel():
    left, right = Differential('limited_slip', 400.0).split(1000.0, 10.0, 60.0)
    assert left - right == pytest.approx(400.0, rel=1e-6)


def test_wheel_torques_through_gears_and_split():
    line = Driveline(ENGINE, gears=(3.5, 2.0, 1.3), final_drive=4.0, efficiency=0.9,
                     front_share=0.4)
    wheels = (30.0, 30.0, 30.0, 30.0)
    # second gear: engine at 2 x 4 x 30 = 240 rad/s, 150 + 100 * 160 / 220 N m
    assert line.engine_speed(2, wheels) == pytest.approx(240.0)
    total = (150.0 + 100.0 * 160.0 / 220.0) * 8.0 * 0.9
    torques = line.wheel_torques(1.0, 2, wheels)
    assert torques == pytest.approx((0.2 * total, 0.2 * total, 0.3 * total, 0.3 * total))
    with pytest.raises(ValueError, match='gear 4 does not exist'):
        line.ratio(4)


def test_the_engine_speed_inertia_takes_j_i2_eta_of_the_drive_torque():
    """J i^2 eta dw/dt by hand; none while the clutch slips; taken off before the split."""
    line = Driveline(ENGINE, gears=(3.5, 2.0, 1.3), final_drive=4.0, efficiency=0.9,
                     front_share=0.4, inertia=1.5)
    wheels = (30.0, 30.0, 30.0, 30.0)
    # second gear, i = 8: 1.5 x 64 x 0.9 x 2 rad/s^2
    assert line.inertia_torque(2, wheels, 2.0) == pytest.approx(1.5 * 64.0 * 0.9 * 2.0)
    # the engine held at its first speed (80 rad/s > 14 x 5 rad/s) does not spin up
    assert line.inertia_torque(1, (5.0, 5.0, 5.0, 5.0), 2.0) == 0.0
    full = sum(line.wheel_torques(1.0, 2, wheels))
    less = line.wheel_torques(1.0, 2, wheels, 100.0)
    assert sum(less) == pytest.approx(full - 100.0)
    assert less[2] / less[0] == pytest.approx(0.6 / 0.4)
    with pytest.raises(ValueError, match='inertia must not be negative'):
        Driveline(ENGINE, gears=(3.5,), final_drive=4.0, inertia=-1.0)


def test_automatic_gear_and_the_slipping_clutch_at_launch():
    line = Driveline(ENGINE, gears=(3.5, 2.0, 1.3), final_drive=4.0, efficiency=0.9,
                     front_share=0.4)
    # ratios 14, 8, 5.2: at 40 rad/s the engine turns 560, 320, 208 rad/s
    wheels = (40.0, 40.0, 40.0, 40.0)
    assert line.gear(wheels, shift_speed=600.0) == 1
    assert line.gear(wheels, shift_speed=500.0) == 2
    assert line.gear(wheels, shift_speed=200.0) == 3  # none below: the top gear
    # at rest the clutch slips: the engine stays at the map's first speed, 80 rad/s,
    # and gives its 150 N m through first gear
    still = (0.0, 0.0, 0.0, 0.0)
    assert line.engine_speed(1, still) == 80.0
    assert line.available_torque(1, still) == pytest.approx(150.0 * 14.0 * 0.9)


def test_bad_drivelines_are_refused():
    with pytest.raises(ValueError, match="unknown differential 'torsen'"):
        Differential('torsen')
    with pytest.raises(ValueError, match='increasing'):
        Engine(np.array([100.0, 50.0]), np.array([10.0, 10.0]))
    with pytest.raises(ValueError, match='front drive share'):
        Driveline(ENGINE, (1.0,), 3.0, front_share=1.2)
