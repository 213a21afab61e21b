# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""vd data side: vehicle data files, master files, feedback, data-server node."""
