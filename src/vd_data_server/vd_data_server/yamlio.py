"""Safe YAML loading that remembers line numbers, for precise error messages."""
from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from .errors import DataError


class LineDict(dict):
    """A mapping that knows the source line of each of its keys (1-based)."""

    lines: dict[str, int]


class _Loader(yaml.SafeLoader):
    """SafeLoader (no arbitrary objects) whose mappings record key lines."""


def _construct_mapping(loader: _Loader, node: yaml.MappingNode) -> LineDict:
    result = LineDict()
    result.lines = {}
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node, deep=True)
        if not isinstance(key, (str, int, float)):
            raise yaml.constructor.ConstructorError(
                None, None, f"unsupported key {key!r}", key_node.start_mark)
        key = str(key)
        if key in result:
            raise yaml.constructor.ConstructorError(
                None, None, f"duplicate key '{key}'", key_node.start_mark)
        result[key] = loader.construct_object(value_node, deep=True)
        result.lines[key] = key_node.start_mark.line + 1
    return result


_Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)


def loads(text: str, *, file: str) -> Any:
    """Parse YAML text; a syntax error becomes a ``DataError`` with the line."""
    try:
        return yaml.load(text, Loader=_Loader)  # noqa: S506 - _Loader derives from SafeLoader
    except yaml.MarkedYAMLError as err:
        mark = err.problem_mark or err.context_mark
        where = f" (line {mark.line + 1}, column {mark.column + 1})" if mark else ""
        raise DataError(f"malformed YAML: {err.problem or err.context}{where}", file=file) from None
    except yaml.YAMLError as err:
        raise DataError(f"malformed YAML: {err}", file=file) from None


def load_file(path: Path, *, display: str) -> Any:
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise DataError("file not found", file=display) from None
    except (OSError, UnicodeDecodeError) as err:
        raise DataError(f"cannot read file: {err}", file=display) from None
    return loads(text, file=display)


def line_of(mapping: Any, key: str) -> int | None:
    return getattr(mapping, "lines", {}).get(key)
