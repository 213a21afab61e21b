# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The benchmark suite (``make bench``).

Timings of the product against its peers, never in pass/fail tests.
"""
