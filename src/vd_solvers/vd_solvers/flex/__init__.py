# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Flexible suspension components (thesis 3.3).

Beam-FE frames generated from the hard points, statically condensed to their
attachment nodes, and imported reduced stiffness matrices. ROS-free; the K&C
model (:mod:`vd_solvers.kc`) embeds them.
"""
