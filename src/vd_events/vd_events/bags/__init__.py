# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
rosbag2 MCAP bags.

Writing and reading them, a run's messages from its outcome, the recorder node.
"""
