# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Edits of a master file, written back atomically with comments and key order kept.

The workbench (``vd gui``) and ``vd import xlsx`` change master files through
this module. Every edit is applied to a round-trip copy of the file (ruamel.yaml
keeps comments, key order, flow lists and folded texts), the result is validated
with the same code that loads master files (:func:`study.load_study`: variants,
overrides with their units and ranges, geometry, flexible components), and only
a valid result replaces the file: written to a temporary file in the same
folder, the previous content kept as ``<name>.bak``, then renamed over the
original (one ``os.replace``, so a reader sees either the old or the new file,
never half of one). A refused edit leaves the file byte for byte as it was and
raises the :class:`DataError` a load of the edited file would raise.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
import glob
import hashlib
import io
import os
from pathlib import Path
import tempfile
from typing import Any

from ruamel.yaml import YAML
from ruamel.yaml.comments import CommentedMap, CommentedSeq

from .errors import DataError, DataErrors
from .files import locked
from .master import inside
from .shape import PLAIN_NAME as _NAME  # the one rule for configuration and variant names
from .study import Study, load_study
from .yamlio import read_bytes

#: suffix of the copy of the previous content kept next to an edited master file
BACKUP_SUFFIX = '.bak'
#: suffix of the temporary copy an edit is validated in (``.<name>.<random>.check``)
CHECK_SUFFIX = '.check'


def remove_stale_checks(master: Path) -> list[Path]:
    """
    Remove the validation copies of ``master`` a killed editor left; return them.

    Called with the master file locked (:func:`files.locked`): every editor validates
    under that lock, so no live one is using a copy at that moment.
    """
    stale = sorted(master.parent.glob(f'.{glob.escape(master.name)}.*{CHECK_SUFFIX}'))
    for path in stale:
        path.unlink(missing_ok=True)
    return stale


@dataclass(frozen=True)
class Edit:
    """
    One change of a master file, as the workbench page sends it.

    ``op`` is one of :data:`OPS`: ``variant`` (``group``, ``value`` the variant),
    ``override`` (``key`` as ``GROUP.KEY``, ``value`` with its unit; an empty
    ``value`` clears the override), ``flexible`` (``value`` ``on``/``off`` or a
    comma-separated list of components), ``add`` (a new configuration
    ``configuration``, copied from ``source`` when given).
    """

    op: str
    configuration: str
    group: str = ''
    key: str = ''
    value: str = ''
    source: str = ''


OPS = ('variant', 'override', 'flexible', 'add')


@dataclass(frozen=True)
class Fingerprint:
    """What a master file was when it was read: modification time and content hash."""

    mtime_ns: int
    sha256: str


def fingerprint(path: str | Path) -> Fingerprint:
    """Return the fingerprint of the file ``path`` now."""
    real = master_path(path)
    return Fingerprint(real.stat().st_mtime_ns,
                       hashlib.sha256(read_bytes(real, display=str(path))).hexdigest())


class ConflictError(DataError):
    """The file changed since the writer read it: the edit is refused, nothing written."""


def _conflict(display: str) -> ConflictError:
    return ConflictError('changed on disk since it was read (another workbench, vd command or '
                         'editor wrote it): this edit is not written; look at the file as it '
                         'is now and edit again', file=display)


def _yaml() -> YAML:
    yaml = YAML(typ='rt')
    yaml.preserve_quotes = True
    yaml.width = 4096  # never re-wrap a long line
    yaml.indent(mapping=2, sequence=4, offset=2)
    return yaml


def load_document(text: str, *, file: str) -> CommentedMap:
    """Parse the master file as a round-trip document (comments and order kept)."""
    try:
        doc = _yaml().load(text)
    except Exception as err:  # noqa: BLE001 - any parser failure is malformed input
        raise DataError(f'malformed YAML: {err}', file=file) from None
    if not isinstance(doc, CommentedMap):
        raise DataError("expected a mapping with 'study', 'defaults' and 'configurations'",
                        file=file)
    return doc


def dump_document(doc: CommentedMap) -> str:
    stream = io.StringIO()
    _yaml().dump(doc, stream)
    return stream.getvalue()


def _child(parent: CommentedMap, key: str) -> CommentedMap:
    value = parent.get(key)
    if not isinstance(value, CommentedMap):
        value = CommentedMap()
        parent[key] = value
    return value


def apply_edit(doc: CommentedMap, edit: Edit, *, file: str) -> None:
    """Change ``doc`` in place; structural mistakes (unknown op, bad name) raise DataError."""
    if edit.op not in OPS:
        raise DataError(f"unknown edit '{edit.op}' (expected one of: {', '.join(OPS)})",
                        file=file)
    configs = doc.get('configurations')
    if not isinstance(configs, CommentedMap):
        raise DataError('expected a mapping of configuration names', file=file,
                        key='configurations')
    name = edit.configuration
    where = f'configurations.{name}'
    if edit.op == 'add':
        _add_configuration(configs, edit, file=file)
        return
    if name not in configs:
        raise DataError(f"configuration '{name}' does not exist (available: "
                        f"{', '.join(configs)})", file=file)
    body = configs[name]
    if not isinstance(body, CommentedMap):
        body = CommentedMap()
        configs[name] = body
    if edit.op == 'variant':
        _set_variant(doc, body, edit, file=file, where=where)
    elif edit.op == 'override':
        _set_override(body, edit, file=file, where=where)
    else:
        _set_flexible(body, edit.value, file=file, where=where)


def _set_variant(doc: CommentedMap, body: CommentedMap, edit: Edit, *, file: str,
                 where: str) -> None:
    group, variant = edit.group.strip(), edit.value.strip()
    if not group:
        raise DataError('no input group given', file=file, key=f'{where}.variants')
    if not _NAME.match(variant):
        raise DataError(f'variant must be a plain name, found {variant!r}', file=file,
                        key=f'{where}.variants.{group}')
    defaults = doc.get('defaults') if isinstance(doc.get('defaults'), Mapping) else {}
    variants = _child(body, 'variants')
    if str(defaults.get(group, '')) == variant:
        variants.pop(group, None)  # back to the default: the file says so by omission
        if not variants:
            del body['variants']
    else:
        variants[group] = variant


def _set_override(body: CommentedMap, edit: Edit, *, file: str, where: str) -> None:
    key, value = edit.key.strip(), edit.value.strip()
    group, _, rest = key.partition('.')
    if not group or not rest:
        raise DataError(f'expected GROUP.KEY, found {key!r}', file=file, key=f'{where}.overrides')
    if not value:
        overrides = body.get('overrides')
        if isinstance(overrides, CommentedMap):
            overrides.pop(key, None)
            if not overrides:
                del body['overrides']
        return
    _child(body, 'overrides')[key] = value


def _set_flexible(body: CommentedMap, value: str, *, file: str, where: str) -> None:
    text = value.strip()
    body.pop('flexible_components', None)
    if text in ('off', 'false', ''):
        body.pop('flexible', None)  # the default
        return
    if text in ('on', 'true'):
        body['flexible'] = True
        return
    names = [n.strip() for n in text.split(',') if n.strip()]
    bad = [n for n in names if not _NAME.match(n)]
    if bad:
        raise DataError(f'component names may hold letters, digits, _ - . (found {bad[0]!r})',
                        file=file, key=f'{where}.flexible_components')
    seq = CommentedSeq(names)
    seq.fa.set_flow_style()
    body['flexible_components'] = seq


def _add_configuration(configs: CommentedMap, edit: Edit, *, file: str) -> None:
    name = edit.configuration.strip()
    if not _NAME.match(name):
        raise DataError(f"configuration name {name!r}: names may hold letters, digits, '_', "
                        "'-' and '.'", file=file, key='configurations')
    if name in configs:
        raise DataError(f"configuration '{name}' exists already", file=file,
                        key=f'configurations.{name}')
    if edit.source:
        if edit.source not in configs:
            raise DataError(f"configuration '{edit.source}' does not exist (available: "
                            f"{', '.join(configs)})", file=file)
        body = _yaml().load(dump_document(CommentedMap({'c': configs[edit.source]})))['c']
        if not isinstance(body, CommentedMap):
            body = CommentedMap()
        body.pop('description', None)
        body.insert(0, 'description', edit.value.strip() or f'Copy of {edit.source}.')
    else:
        body = CommentedMap({'description': edit.value.strip() or 'New configuration.'})
    configs[name] = body


def validate_text(text: str, master: Path) -> Study:
    """
    Load ``text`` as if it were the content of ``master``.

    The text is checked in a file of the same folder (so the same data root); messages
    name ``master``, exactly as a load of the written file would.
    """
    folder = master.parent
    fd, tmp = tempfile.mkstemp(prefix=f'.{master.name}.', suffix=CHECK_SUFFIX, dir=folder)
    try:
        with os.fdopen(fd, 'w', encoding='utf-8') as stream:
            stream.write(text)
        try:
            return load_study(tmp)
        except DataErrors as err:
            raise DataErrors([_renamed(e, tmp, master) for e in err.errors]) from None
        except DataError as err:
            raise _renamed(err, tmp, master) from None
    finally:
        os.unlink(tmp)


def _renamed(err: DataError, tmp: str, master: Path) -> DataError:
    def fix(text: str | None) -> str | None:
        return text.replace(tmp, str(master)) if text else text

    return DataError(fix(err.detail) or '', file=fix(err.file), key=fix(err.key))


def master_path(path: str | Path) -> Path:
    """Return the file an edit writes: the real file behind a symbolic link."""
    return Path(os.path.realpath(path))


def write_atomically(path: Path, text: str) -> None:
    """Replace ``path`` with ``text``; the previous content is kept as ``<name>.bak``."""
    previous = path.read_bytes() if path.exists() else None
    if previous is not None:
        backup = path.with_name(path.name + BACKUP_SUFFIX)
        _replace_with(backup, previous)
    _replace_with(path, text.encode('utf-8'), mode=path.stat().st_mode if previous else None)


def _replace_with(path: Path, data: bytes, mode: int | None = None) -> None:
    fd, tmp = tempfile.mkstemp(prefix=f'.{path.name}.', suffix='.tmp', dir=path.parent)
    try:
        with os.fdopen(fd, 'wb') as stream:
            stream.write(data)
            stream.flush()
            os.fsync(stream.fileno())
        if mode is not None:
            os.chmod(tmp, mode & 0o7777)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def edit_master(path: str | Path, edits: Sequence[Edit], *,
                expected: Fingerprint | None = None) -> bool:
    """
    Apply ``edits`` to the master file at ``path``, validate, write atomically.

    The file is locked from its reading to its replacement (:func:`files.locked`), so
    concurrent editors queue instead of losing updates. ``expected``, when given, is
    the fingerprint of the file as the editor last read it (the workbench's page): a
    file changed since raises :class:`ConflictError`. Returns whether the file changed.
    On any error (a bad value, an unknown variant, a broken structure, a conflict)
    raises DataError and the file is unchanged.
    """
    real = master_path(path)
    display = str(path)
    with locked(real):
        remove_stale_checks(real)
        read = fingerprint(real)
        if expected is not None and read != expected:
            raise _conflict(display)
        text = read_bytes(real, display=display).decode('utf-8', errors='strict')
        doc = load_document(text, file=display)
        for edit in edits:
            apply_edit(doc, edit, file=display)
        new_text = dump_document(doc)
        try:
            validate_text(new_text, real)
        except DataErrors as err:
            raise DataErrors([_renamed(e, str(real), Path(display))
                              for e in err.errors]) from None
        except DataError as err:
            raise _renamed(err, str(real), Path(display)) from None
        if new_text == text:
            return False
        if fingerprint(real) != read:  # an editor outside vd wrote it meanwhile
            raise _conflict(display)
        write_atomically(real, new_text)
        return True


def write_master(path: str | Path, doc: Mapping[str, Any], *, root: Path | None = None) -> str:
    """
    Write a whole master file (``vd import xlsx``): validated first, then atomically.

    ``root``, when given, is a folder the file must lie under. Returns the text written.
    """
    target = Path(os.path.realpath(path)) if Path(path).exists() else Path(path).absolute()
    if root is not None and not inside(root, target):
        raise DataError(f'is outside the data root {root}: not written', file=str(path))
    if not target.parent.is_dir():
        raise DataError('its folder does not exist', file=str(path))
    stream = io.StringIO()
    _yaml().dump(doc, stream)
    text = stream.getvalue()
    if not target.exists():
        validate_text(text, target)
        write_atomically(target, text)
        return text
    with locked(target):
        remove_stale_checks(target)
        validate_text(text, target)
        if target.read_text(encoding='utf-8') != text:
            write_atomically(target, text)
    return text
