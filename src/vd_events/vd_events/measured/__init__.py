# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Measured data.

Rig and vehicle-test readers (CSV, VBOX), import into bags, replay, comparison with simulation.
"""
