#!/usr/bin/env python3
# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Check or add the copyright and SPDX licence header of every source file.

Usage: ``tools/spdx.py [--fix] [PATH ...]`` (default: the tracked Python and shell
files of the repository, upstream packages excluded). Exit 1 when a file lacks the
header and ``--fix`` was not given.
"""
import argparse
from pathlib import Path
import subprocess
import sys

HEADER = ('# Copyright 2026 The vd authors', '# SPDX-License-Identifier: Apache-2.0')
#: upstream sources kept under their own licence
UPSTREAM = ('src/tf2_msgs/', 'src/ackermann_msgs/')
ROOT = Path(__file__).resolve().parents[1]


def tracked() -> list[Path]:
    """Return the repository's Python and shell files, upstream packages excluded."""
    out = subprocess.run(['git', 'ls-files', '*.py', '*.sh', 'vd', '.ci/run'], cwd=ROOT,
                         check=True, capture_output=True, text=True).stdout.split()
    return [ROOT / p for p in out if not p.startswith(UPSTREAM)]


def has_header(text: str) -> bool:
    """Tell whether the SPDX line is among the first lines of ``text``."""
    return HEADER[1] in text.splitlines()[:4]


def add_header(text: str) -> str:
    """Return ``text`` with the header after a shebang line, if any."""
    lines = text.splitlines(keepends=True)
    head = [lines.pop(0)] if lines and lines[0].startswith('#!') else []
    return ''.join(head + [h + '\n' for h in HEADER] + lines)


def main(argv: list[str] | None = None) -> int:
    """Check (or with ``--fix`` add) the headers; return the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--fix', action='store_true', help='add missing headers')
    parser.add_argument('paths', nargs='*', type=Path)
    args = parser.parse_args(argv)
    missing = []
    for path in args.paths or tracked():
        text = path.read_text(encoding='utf-8')
        if has_header(text):
            continue
        if args.fix:
            path.write_text(add_header(text), encoding='utf-8')
        else:
            missing.append(path)
    for path in missing:
        print(f'{path.relative_to(ROOT)}: missing the copyright/SPDX header', file=sys.stderr)
    return 1 if missing else 0


if __name__ == '__main__':
    sys.exit(main())
