# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The ROS plumbing every vd package shares.

Names, QoS profiles, the standard node main, launch arguments.
"""
