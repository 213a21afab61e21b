# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Physical constants and unit factors, defined once for every rung.

SI inside: these are the only numbers the cores need to go between SI and the
display units of reports and metric names. Values from CODATA via
:mod:`scipy.constants` (standard gravity, ISO 80000-3; the degree).
"""
from __future__ import annotations

from scipy import constants

#: standard acceleration of gravity, m/s^2 (ISO 80000-3: 9.80665 exactly)
STANDARD_GRAVITY: float = constants.g
#: one degree in radians (``x * DEG`` turns degrees into rad, ``x / DEG`` rad into degrees)
DEG: float = constants.degree
