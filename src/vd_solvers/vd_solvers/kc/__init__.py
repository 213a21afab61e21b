# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Quasi-static kinematics & compliance suspension model (thesis 3.2)."""
