# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Design of experiments over override factors.

Sweep plans, sweeps and their analysis, optimisation.
"""
