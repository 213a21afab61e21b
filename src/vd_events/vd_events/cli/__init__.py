# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The ``vd`` command line.

Its grammar (parsers), the entry point (main) and one module per verb.
"""
