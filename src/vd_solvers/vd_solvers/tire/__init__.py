# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Tire models: Magic Formula from .tir files and the thesis simple tire."""
