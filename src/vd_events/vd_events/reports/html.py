# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
The reports' HTML: Jinja2 templates (``templates/``) with one stylesheet, autoescaped.

Every page (``report.html``, ``study.html``, ``compare.html``, ``sweep.html``) extends
``base.html``, which inlines ``style.css``, so a page is one file that opens offline.
Values reach the templates as data; the templates escape them, so a configuration or
channel name can never break the page. :func:`write_page` renders and writes atomically.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
import math
from pathlib import Path
from typing import Any

import jinja2
import markupsafe

from vd_data_server.files import atomic_write


def number(value: Any, fmt: str = '.4g') -> str:
    """Format a number for a table cell; '–' for NaN/inf/None (a metric not computed)."""
    if value is None:
        return '–'
    try:
        v = float(value)
    except (TypeError, ValueError):
        return str(value)
    return format(v, fmt) if math.isfinite(v) else '–'


@dataclass(frozen=True)
class Cell:
    """A table cell: its text, a style class (``ok``, ``bad``, ``mod``...), a hover title."""

    text: str
    cls: str = ''
    title: str = ''
    small: str = ''  # a second, smaller line (a unit under a column name)
    href: str = ''
    header: bool = False  # a row heading (<th>)


def cell(value: Any) -> Cell:
    """Return ``value`` as a Cell (numbers formatted by :func:`number`)."""
    if isinstance(value, Cell):
        return value
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return Cell(number(value), cls='num')
    return Cell('' if value is None else str(value))


@dataclass
class Table:
    """A table of a section: a heading row and rows of cells (values or Cells)."""

    head: Sequence[Any]
    rows: Sequence[Sequence[Any]]
    caption: str = ''
    level: int = 3
    cls: str = ''

    def __post_init__(self) -> None:
        self.head = [cell(h) for h in self.head]
        self.rows = [[cell(c) for c in row] for row in self.rows]


@dataclass(frozen=True)
class Image:
    """A figure file of the page's folder (or a data URI), with its alternative text."""

    src: str
    alt: str = ''


@dataclass
class Section:
    """A part of a page; every page is a list of sections (``templates/section.html``)."""

    title: str = ''
    level: int = 2
    paragraphs: list[str] = field(default_factory=list)
    images: list[Image] = field(default_factory=list)
    #: interactive plots: HTML that plotly made (trusted, not escaped)
    figures: list[markupsafe.Markup] = field(default_factory=list)
    tables: list[Table] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    subsections: list['Section'] = field(default_factory=list)


def images(names: Sequence[str]) -> list[Image]:
    """Return the figure files ``names`` as Images (alternative text: the file name)."""
    return [Image(n, n) for n in names]


ENV = jinja2.Environment(
    loader=jinja2.PackageLoader('vd_events.reports', 'templates'),
    autoescape=jinja2.select_autoescape(('html',), default_for_string=True),
    undefined=jinja2.StrictUndefined,  # a name missing from the data is a bug, not a blank
    trim_blocks=True, lstrip_blocks=True,
)
ENV.filters['num'] = number


def render(template: str, **context: Any) -> str:
    """Render ``templates/<template>`` with ``context``."""
    return ENV.get_template(template).render(**context)


def write_page(path: Path, title: str, sections: Sequence[Section],
               intro: Sequence[str] = (), script: str = '') -> Path:
    """
    Render a page (``templates/page.html``) and write it atomically to ``path``.

    ``script``: JavaScript the page needs inline (plotly.js for the interactive plots).
    """
    return atomic_write(path, render('page.html', title=title, intro=list(intro),
                                     sections=list(sections),
                                     script=markupsafe.Markup(script) if script else ''))


__all__ = ['Cell', 'Table', 'Image', 'Section', 'cell', 'images', 'render', 'write_page',
           'number', 'ENV']
