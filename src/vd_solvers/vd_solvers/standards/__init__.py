# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Procedures and criteria of standards and regulations, ROS-free (FMVSS 126 / UN R140)."""
