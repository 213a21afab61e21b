# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The ``vd`` command-line tool (ARCHITECTURE §5): parse, run the verb's handler, report.

Bad input never ends in a traceback: every expected error is printed as
``file: key: message`` lines (or ``{"error": ...}`` with ``--json``) and the
exit code is 2. Nothing is written before the inputs are validated.

A verb's module is imported when the verb runs (:func:`load_handler`), so ``vd data
status`` does not pay for rclpy, Pinocchio, matplotlib and plotly, which the run, report
and sweep verbs import (docs/architecture.md lists this and the other deliberate late
imports).
"""
from __future__ import annotations

import argparse
from collections.abc import Callable, Sequence
import importlib
import json
import os
import signal
import sys
from typing import NoReturn

from vd_data_server.errors import DataError
from vd_events.cli.parsers import build_parser
from vd_events.errors import EventsError, Interrupted

EXIT_OK = 0
EXIT_USAGE = 2
EXIT_INTERRUPTED = 130


def load_handler(target: str) -> Callable[[argparse.Namespace], int]:
    """Import the module of a verb's handler (``module:function``) and return the function."""
    module, _, function = target.partition(':')
    return getattr(importlib.import_module(module), function)


def main(argv: Sequence[str] | None = None) -> int:
    args = build_parser().parse_args(list(sys.argv[1:] if argv is None else argv))
    want_json = bool(getattr(args, 'json', False))
    previous = signal.signal(signal.SIGTERM, _terminate)
    try:
        return load_handler(args.handler)(args)
    except Interrupted as err:
        _report_error(str(err), want_json)
        return EXIT_INTERRUPTED
    except (DataError, EventsError) as err:
        _report_error(str(err), want_json)
        return EXIT_USAGE
    except OSError as err:  # a file or folder the input named cannot be used
        where = f'{err.filename}: ' if err.filename else ''
        _report_error(f'{where}{err.strerror or err}', want_json)
        return EXIT_USAGE
    except KeyboardInterrupt:
        _report_error('interrupted', want_json)
        return EXIT_INTERRUPTED
    finally:
        signal.signal(signal.SIGTERM, previous)


def _terminate(signum, frame) -> None:
    """SIGTERM ends a run like Ctrl-C: its nodes stop, its partial bag is removed."""
    raise KeyboardInterrupt


def _report_error(message: str, want_json: bool) -> None:
    if want_json:
        print(json.dumps({'error': message}))
    else:
        print(message, file=sys.stderr)


__all__ = ['main', 'exit_with', 'load_handler', 'EXIT_OK', 'EXIT_USAGE', 'EXIT_INTERRUPTED']


def exit_with(code: int) -> NoReturn:
    """
    End the process with ``code`` (the module entry points: ``python -m vd_events.cli``).

    An interrupted run exits through ``os._exit`` once its output is flushed: CPython ends
    a process by SIGINT, whatever the code, once a KeyboardInterrupt has left any code run
    by ``exec`` of a string (namedtuple, dataclass and numba wrappers), even one ``main``
    then handled, and the caller would see a signal instead of EXIT_INTERRUPTED.
    """
    if code == EXIT_INTERRUPTED:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    sys.exit(code)


if __name__ == '__main__':
    exit_with(main())
