# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Measured data (K&C rigs, vehicle-test logs) into vd bags: column maps and readers."""
