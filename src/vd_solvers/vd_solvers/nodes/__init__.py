# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The solver nodes (``ros2 run vd_solvers ...``).

The shared action shell and one node per family.
"""
