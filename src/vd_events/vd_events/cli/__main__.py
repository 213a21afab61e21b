# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""``python -m vd_events.cli``: the vd command-line tool (what ``./vd`` runs)."""
from vd_events.cli.main import exit_with, main

exit_with(main())
