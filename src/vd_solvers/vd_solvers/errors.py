# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""Precise error types of the solvers."""
from __future__ import annotations


class SolverError(Exception):
    """
    A model could not produce a trustworthy answer.

    The message names the configuration, the event and the step where known.
    """


class BeyondLimitError(SolverError):
    """The requested operating point lies beyond what the vehicle can hold."""
