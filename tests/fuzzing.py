# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Strategies and the property shared by the fuzz tests.

The property: either a clean error or a valid result - never a traceback (an exception
of another type), a hang or a huge message.
"""
from __future__ import annotations

from collections.abc import Iterator
import contextlib
import signal
from typing import Any

from hypothesis import strategies as st

#: seconds one example may take before it counts as a hang
HANG = 10.0
#: longest message a clean error may have (the per-problem cut times the problem limit)
MAX_MESSAGE = 60_000


class Hang(Exception):
    pass


@contextlib.contextmanager
def no_hang(seconds: float = HANG) -> Iterator[None]:
    def alarm(signum, frame):
        raise Hang(f'no answer after {seconds:g} s')

    previous = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)


def clean(err: Exception) -> None:
    """Check that ``err`` is a clean error: one or more readable lines, bounded."""
    text = str(err)
    assert text, f'empty message from {type(err).__name__}'
    assert len(text) <= MAX_MESSAGE, len(text)
    assert 'Traceback' not in text


UNITS = ['', 'mm', 'm', 'N/mm', 'N', 'kN', 'deg', 'rad', 'kg', 'g', 'N*m/deg', 'N/(mm*0)',
         '1/0', 'mm**99999', '(', '%', 'furlong', 'N/mm/mm', 'm/s', 'Pa', 'bar', 'e', '*',
         'N*s/mm', 'kg*m^2', 'inf', 'nan']
NUMBER_TEXTS = st.one_of(
    st.integers(min_value=-10**500, max_value=10**500).map(str),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.sampled_from(['', '-', '.', '1e', '1e999', '-0', '0', '1e-400', 'nan', 'inf', '1_000',
                     '0x10', '+.5', '9' * 400]),
)
QUANTITIES = st.builds(lambda n, sep, u: f'{n}{sep}{u}', NUMBER_TEXTS, st.sampled_from(['', ' ']),
                       st.sampled_from(UNITS))
SCALARS = st.one_of(
    st.none(), st.booleans(),
    st.integers(min_value=-10**500, max_value=10**500),
    st.floats(allow_nan=True, allow_infinity=True),
    QUANTITIES,
    st.text(max_size=20),
)
VALUES = st.recursive(SCALARS, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=8), inner, max_size=3)),
    max_leaves=8)


def paths(tree: Any, prefix: tuple = ()) -> list[tuple]:
    """Every path (keys / indices) into a YAML tree, the root included."""
    out = [prefix]
    if isinstance(tree, dict):
        for key, value in tree.items():
            out += paths(value, prefix + (key,))
    elif isinstance(tree, list):
        for index, value in enumerate(tree):
            out += paths(value, prefix + (index,))
    return out


def mutate(data: st.DataObject, tree: Any, rounds: int = 3) -> Any:
    """Return the tree with a few random edits: replace a node, delete a key, add a key."""
    import copy

    tree = copy.deepcopy(tree)
    for _ in range(data.draw(st.integers(1, rounds))):
        where = data.draw(st.sampled_from(paths(tree)))
        action = data.draw(st.sampled_from(['replace', 'delete', 'add']))
        if not where:
            if action == 'replace':
                tree = data.draw(VALUES)
            continue
        parent = tree
        for step in where[:-1]:
            parent = parent[step]
        last = where[-1]
        if action == 'replace':
            parent[last] = data.draw(VALUES)
        elif action == 'delete':
            del parent[last]
        elif isinstance(parent, dict):
            parent[data.draw(st.text(max_size=10))] = data.draw(VALUES)
        else:
            parent.append(data.draw(VALUES))
    return tree
