# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""vd events: event runner, recorder, post-processing and the vd command-line tool."""
