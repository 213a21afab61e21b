# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Road surfaces the tires stand on, ROS-free.

A surface gives the ground height at points of the ground plane (ISO 8855 earth axes,
z up) and a friction scale: flat, a straight road with a height profile per wheel track
(ISO 8608 random roads from a seed, single obstacles: bump, pothole, kerb) and ASAM
OpenCRG files. Each says what it is (``description``: class and seed, obstacle, file hash)
so that a result can name the road it was run on.
"""
