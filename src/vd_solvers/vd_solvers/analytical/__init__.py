# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Analytical models: bicycle and two-track steady state (thesis 3.1)."""
