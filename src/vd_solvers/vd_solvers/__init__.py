# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""vd solvers: analytical, K&C and full-vehicle models (ROS-free cores + node shells)."""
__version__ = '0.1.0'
