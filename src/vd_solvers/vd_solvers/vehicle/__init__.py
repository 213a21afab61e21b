# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The full-vehicle rung (ROS-free; see docs/models.md).

Pinocchio multibody car, suspension maps from K&C, Magic Formula tires, drivers, the
constant radius turn and the step steer.
"""
