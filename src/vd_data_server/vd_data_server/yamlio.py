# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Safe YAML loading that remembers line numbers, for precise error messages.

Every file is bounded before it is built into Python objects: its size
(:data:`MAX_FILE_BYTES`), its nesting depth (:data:`MAX_DEPTH`) and the number
of nodes it holds once aliases are expanded (:data:`MAX_NODES`, against
"billion laughs" alias bombs). A file over a limit is refused with a message
that names the limit.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from .errors import DataError
from .reads import note_read

#: largest file read (data, master, plan, .tir), bytes; the sample files are < 20 kB
MAX_FILE_BYTES = 1 << 20
#: deepest nesting of mappings and sequences in a YAML file
MAX_DEPTH = 64
#: most nodes a YAML file may hold with its aliases expanded
MAX_NODES = 100_000
#: most digits of a whole number (Python refuses to convert longer ones: 4300)
MAX_DIGITS = 4000


class LineDict(dict):
    """A mapping that knows the source line of each of its keys (1-based)."""

    lines: dict[str, int]


class _OverLimit(yaml.constructor.ConstructorError):
    """A well-formed value over one of the limits (not malformed YAML)."""


class _Loader(yaml.SafeLoader):
    """SafeLoader (no arbitrary objects) whose mappings record key lines."""


class _FastLoader(getattr(yaml, 'CSafeLoader', yaml.SafeLoader)):  # type: ignore[misc]
    """
    The same loader on libyaml's parser (when PyYAML has it).

    A valid file loads several times faster; a file it refuses is read again by
    :class:`_Loader`, whose messages the tests and users know.
    """


def _construct_mapping(loader: _Loader, node: yaml.MappingNode) -> LineDict:
    result = LineDict()
    result.lines = {}
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node, deep=True)
        if not isinstance(key, (str, int, float)):
            raise yaml.constructor.ConstructorError(
                None, None, f'unsupported key {key!r}', key_node.start_mark)
        key = str(key)
        if key in result:
            raise yaml.constructor.ConstructorError(
                None, None, f"duplicate key '{key}'", key_node.start_mark)
        result[key] = loader.construct_object(value_node, deep=True)
        result.lines[key] = key_node.start_mark.line + 1
    return result


def _construct_int(loader: _Loader, node: yaml.ScalarNode) -> int:
    """Build a YAML integer, refused above :data:`MAX_DIGITS` digits with its line."""
    digits = sum(c.isdigit() for c in str(node.value))
    if digits > MAX_DIGITS:
        raise _OverLimit(
            None, None, f'number too large ({digits} digits, the limit is {MAX_DIGITS})',
            node.start_mark)
    return yaml.SafeLoader.construct_yaml_int(loader, node)


for _loader in (_Loader, _FastLoader):
    _loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)
    _loader.add_constructor('tag:yaml.org,2002:int', _construct_int)


def _check_size(text: str, file: str, loader: type = _Loader) -> None:
    """
    Refuse a file over :data:`MAX_DEPTH` or :data:`MAX_NODES`.

    Depth and alias-expanded node count come from the event stream (no recursion,
    no expansion).
    """
    stack: list[int] = [0]  # expanded node count of each open collection
    anchors: list[str | None] = [None]
    sizes: dict[str, int] = {}
    for event in yaml.parse(text, Loader=loader):  # noqa: S506 - parsing only
        if isinstance(event, (yaml.MappingStartEvent, yaml.SequenceStartEvent)):
            if len(stack) > MAX_DEPTH:
                mark = event.start_mark
                raise DataError(f'exceeds the limit of {MAX_DEPTH} nesting levels (line '
                                f'{mark.line + 1})', file=file)
            stack.append(1)
            anchors.append(event.anchor)
            continue
        if isinstance(event, (yaml.MappingEndEvent, yaml.SequenceEndEvent)):
            size, anchor = stack.pop(), anchors.pop()
            if anchor is not None:
                sizes[anchor] = size
        elif isinstance(event, yaml.ScalarEvent):
            size = 1
            if event.anchor is not None:
                sizes[event.anchor] = 1
        elif isinstance(event, yaml.AliasEvent):
            size = sizes.get(event.anchor, 1)
        else:
            continue
        stack[-1] += size
        if stack[-1] > MAX_NODES or sum(stack) > MAX_NODES:
            mark = event.start_mark
            raise DataError(f'exceeds the limit of {MAX_NODES} values with its aliases expanded '
                            f'(line {mark.line + 1})', file=file)


def loads(text: str, *, file: str) -> Any:
    """Parse YAML text; a syntax error becomes a ``DataError`` with the line."""
    if hasattr(yaml, 'CSafeLoader'):
        try:
            _check_size(text, file, _FastLoader)
            return yaml.load(text, Loader=_FastLoader)  # noqa: S506 - a SafeLoader
        except yaml.YAMLError:
            pass  # read again below: the messages are the pure-Python parser's
    try:
        _check_size(text, file)
        return yaml.load(text, Loader=_Loader)  # noqa: S506 - _Loader derives from SafeLoader
    except yaml.MarkedYAMLError as err:
        mark = err.problem_mark or err.context_mark
        where = f' (line {mark.line + 1}, column {mark.column + 1})' if mark else ''
        what = '' if isinstance(err, _OverLimit) else 'malformed YAML: '
        raise DataError(f'{what}{err.problem or err.context}{where}', file=file) from None
    except yaml.YAMLError as err:
        raise DataError(f'malformed YAML: {err}', file=file) from None


def read_bytes(path: Path, *, display: str) -> bytes:
    """Return a file's bytes, refused above :data:`MAX_FILE_BYTES` (checked before reading)."""
    try:
        with path.open('rb') as stream:
            data = stream.read(MAX_FILE_BYTES + 1)
    except FileNotFoundError:
        raise DataError('file not found', file=display) from None
    except IsADirectoryError:
        raise DataError('is a folder, not a file', file=display) from None
    except OSError as err:
        raise DataError(f'cannot read file: {err.strerror or err}', file=display) from None
    if len(data) > MAX_FILE_BYTES:
        raise DataError(f'exceeds the limit of {MAX_FILE_BYTES >> 20} MiB per file',
                        file=display)
    note_read(path, data)
    return data


def load_file(path: Path, *, display: str) -> Any:
    data = read_bytes(path, display=display)
    try:
        text = data.decode('utf-8')
    except UnicodeDecodeError as err:
        raise DataError(f'cannot read file: not UTF-8 text (byte {err.start})',
                        file=display) from None
    return loads(text, file=display)


def line_of(mapping: Any, key: str) -> int | None:
    return getattr(mapping, 'lines', {}).get(key)
