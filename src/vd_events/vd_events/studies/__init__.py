# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Studies of many runs.

Study plans (many events x configurations x models) and the rigid-vs-flexible capability
study.
"""
