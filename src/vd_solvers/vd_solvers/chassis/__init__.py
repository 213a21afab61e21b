# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The chassis systems the longitudinal and ride events need, ROS-free.

Brakes (line pressure to wheel torque, proportioning, an anti-lock controller), the
driveline (engine map, gears, differentials) and aerodynamics.
"""
