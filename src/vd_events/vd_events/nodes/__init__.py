# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The node processes of vd_events (``ros2 run vd_events ...``).

Thin shells over the other rooms.
"""
