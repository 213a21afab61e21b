# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Everything a person reads.

The HTML pages (Jinja2 templates), their figures and tables, display units.
"""
