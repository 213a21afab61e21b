# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Running events through the ROS graph.

The runner (embedded, distributed), the sweep dispatcher, the graph and its domain, the lock-
step pair.
"""
