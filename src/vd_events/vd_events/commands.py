"""vd subcommands beyond ``vd data``: run, study, report, launch, bench."""
from __future__ import annotations

import argparse
from collections.abc import Callable

HANDLERS: dict[str, Callable[[argparse.Namespace], int]] = {}


def add_subcommands(sub: argparse._SubParsersAction) -> None:
    """Register the subcommands on the ``vd`` parser."""
