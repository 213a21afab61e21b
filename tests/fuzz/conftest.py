# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Hypothesis profiles for the tests.

``ci`` (the default, part of ``make test``: seconds, deterministic)
and ``fuzz`` (``make fuzz``: many more examples, random).
"""
from __future__ import annotations

import os

from hypothesis import HealthCheck, settings

settings.register_profile('ci', max_examples=20, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile('fuzz', max_examples=400, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get('HYPOTHESIS_PROFILE', 'ci'))
