# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The data server node (``ros2 run vd_data_server data_server``)."""
