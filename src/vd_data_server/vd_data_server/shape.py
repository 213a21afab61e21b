# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Check the shape of a YAML tree against a spec of :mod:`.schema`.

One walker for every file that is described by specs: master files
(``schema.MASTER``) and study plans (``vd_events.studies.plan.PLAN``) here, and the
sections and name maps of data files (``datafile.py`` converts their leaves to SI
on top). Every problem is collected as ``file: key: message (line N)``; unknown keys
are errors. The walker checks shapes, types, choices and plain names; what needs
more than one value (a variant per required group, overrides against the data) is
checked by the loader afterwards.
"""
from __future__ import annotations

from collections.abc import Mapping
import re
from typing import Any

from . import schema
from .errors import DataError, DataErrors
from .yamlio import line_of

#: a plain name: no path separators, no leading dot (never '..')
PLAIN_NAME = re.compile(r'^[A-Za-z0-9][A-Za-z0-9_.-]*$')


class Collector:
    """The problems of one file, each with its key and line."""

    def __init__(self, file: str) -> None:
        self.file = file
        self.errors: list[DataError] = []
        self.warnings: list[str] = []

    def add(self, key: str, message: str, container: Any = None, name: Any = None) -> None:
        line = line_of(container, name) if name is not None else None
        suffix = f' (line {line})' if line else ''
        self.errors.append(DataError(message + suffix, file=self.file, key=key or None))

    def raise_if_any(self) -> None:
        if len(self.errors) == 1:
            raise self.errors[0]
        if self.errors:
            raise DataErrors(self.errors)


def join(path: str, key: Any) -> str:
    return f'{path}.{key}' if path else str(key)


def kind_of(node: Any) -> str:
    return 'nothing' if node is None else f'{type(node).__name__} {node!r}'


def section_keys(spec: schema.Section, node: Mapping[str, Any], path: str, col: Collector,
                 parent: Any, name: Any) -> None:
    """Report the unknown keys, the one-of groups and the missing required keys of a section."""
    key = path or str(name)
    for sub in node:
        if sub not in spec.fields:
            col.add(join(path, sub), f"unknown key (expected one of: {', '.join(spec.fields)})",
                    node, sub)
    for group in spec.one_of:
        given = [g for g in group if g in node]
        if len(given) != 1:
            col.add(key, f"give exactly one of: {', '.join(group)} (found "
                    f"{', '.join(given) if given else 'none'})", parent, name)
    for sub, sub_spec in spec.fields.items():
        if sub not in node and sub_spec.required and not any(sub in g for g in spec.one_of):
            col.add(join(path, sub), 'missing required key', parent, name)


def check(spec: schema.Spec, node: Any, path: str, col: Collector, parent: Any = None,
          name: Any = None) -> None:
    """Check ``node`` (found under key ``name`` of ``parent``) against ``spec``."""
    key = path or str(name)
    if node is None and not spec.required:
        return  # an optional key left blank is as if it were not there
    if isinstance(spec, schema.Section):
        if node is None and not any(f.required for f in spec.fields.values()):
            return  # a section of optional keys may be left empty
        if not isinstance(node, Mapping):
            col.add(key, f'expected a mapping, found {kind_of(node)}', parent, name)
            return
        section_keys(spec, node, path, col, parent, name)
        for sub, sub_spec in spec.fields.items():
            if sub in node:
                check(sub_spec, node[sub], join(path, sub), col, node, sub)
        return
    if isinstance(spec, schema.MapOf):
        if node is None and spec.empty:
            return
        if not isinstance(node, Mapping) or not (node or spec.empty):
            col.add(key, f'expected {spec.expected}, found {kind_of(node)}', parent, name)
            return
        for sub, value in node.items():
            if spec.keys is not None:
                problem = leaf_problem(spec.keys, sub)
                if problem:
                    col.add(join(path, sub), problem, node, sub)
                    continue
            check(spec.value, value, join(path, sub), col, node, sub)
        return
    if isinstance(spec, schema.ListOf):
        if spec.alternative is not None and node == spec.alternative:
            return
        if not isinstance(node, list) or (spec.non_empty and not node):
            alternative = f"'{spec.alternative}' or " if spec.alternative else ''
            what = f"{'non-empty ' if spec.non_empty else ''}list of {spec.what}"
            col.add(key, f'expected {alternative}a {what}, found {node!r}', parent, name)
            return
        for i, item in enumerate(node):
            check(spec.value, item, f'{key}[{i}]', col, parent, name)
        return
    problem = leaf_problem(spec, node)
    if problem:
        col.add(key, problem, parent, name)


def leaf_problem(spec: schema.Spec, node: Any) -> str | None:
    """Return what is wrong with a text, name, flag or raw value ``node``, or None."""
    if isinstance(spec, schema.Text):
        if not isinstance(node, str) or not node:
            return f'expected a text, found {kind_of(node)}'
        if spec.choices and node not in spec.choices:
            return spec.refusal.format(value=node, choices=', '.join(spec.choices))
        return None
    if isinstance(spec, schema.Name):
        plain = isinstance(node, str) or (spec.numbers and isinstance(node, int)
                                          and not isinstance(node, bool))
        if not plain or not PLAIN_NAME.match(str(node)):
            return spec.refusal.format(value=node)
        return None
    if isinstance(spec, schema.Flag):
        if isinstance(node, bool):
            return None
        if spec.or_list and isinstance(node, list) and all(
                isinstance(c, str) and c for c in node):
            return None
        alternatives = f'true, false or a list of {spec.or_list}' if spec.or_list \
            else 'true or false'
        return f'expected {alternatives}, found {node!r}'
    if isinstance(spec, schema.Raw):
        return None
    raise TypeError(spec)  # pragma: no cover - the leaves of non-data specs are above
