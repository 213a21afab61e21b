# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
Private ROS domains for runs: claimed with an exclusive lock, never shared silently.

Every ``vd run`` / ``vd study`` starts its own ROS graph in a domain of its own
(:data:`DOMAINS`, or ``VD_DOMAIN_ID``). A domain is claimed by an exclusive
``flock`` on ``<runtime dir>/vd/domain-<id>.lock`` (``$XDG_RUNTIME_DIR``, else the
temporary folder per user), held for the run's life: the kernel drops the lock
when the process ends, however it ends (``kill -9`` included), so a claim never
goes stale. A run never starts in a domain another live run holds.

``vd launch`` runs in the caller's ``ROS_DOMAIN_ID`` (other tools join it there) and
claims it the same way (:func:`claim_launch_domain`): a ``vd run`` never lands in a
domain where launched vd nodes serve, and a second ``vd launch`` in it is refused.
"""
from __future__ import annotations

from dataclasses import dataclass
import fcntl
import os
from pathlib import Path
import random
import tempfile

from vd_events.errors import DomainError

#: domains drawn for runs (clear of the default 0 and of what ROS tools tend to use)
DOMAINS = range(101, 216)
#: the highest domain id ROS 2 accepts with the default port layout
MAX_DOMAIN_ID = 232
ENV = 'VD_DOMAIN_ID'
#: the domain ROS nodes join (ROS 2's own variable; unset is domain 0)
ROS_ENV = 'ROS_DOMAIN_ID'




def lock_dir() -> Path:
    base = os.environ.get('XDG_RUNTIME_DIR') or os.path.join(tempfile.gettempdir(),
                                                              f'vd-{os.getuid()}')
    return Path(base) / 'vd'


@dataclass
class DomainClaim:
    domain: int
    _fd: int

    def release(self) -> None:
        if self._fd >= 0:
            os.close(self._fd)  # closing drops the flock
            self._fd = -1


def _try_lock(domain: int) -> DomainClaim | None:
    folder = lock_dir()
    folder.mkdir(parents=True, exist_ok=True, mode=0o700)
    fd = os.open(folder / f'domain-{domain}.lock', os.O_RDWR | os.O_CREAT, 0o600)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        os.close(fd)
        return None
    os.ftruncate(fd, 0)
    os.write(fd, f'{os.getpid()}\n'.encode())
    return DomainClaim(domain, fd)


def holder(domain: int) -> str:
    """Return the pid written by the run holding ``domain`` (for messages)."""
    try:
        return (lock_dir() / f'domain-{domain}.lock').read_text().strip() or '?'
    except OSError:
        return '?'


def requested_domain(variable: str = ENV) -> int | None:
    """Read the environment ``variable`` as a domain id: None if unset, DomainError if bad."""
    text = os.environ.get(variable)
    if text is None or text.strip() == '':
        return None
    try:
        domain = int(text.strip())
    except ValueError:
        domain = -1
    if not 0 <= domain <= MAX_DOMAIN_ID:
        raise DomainError(f'{variable}: expected a ROS domain id 0..{MAX_DOMAIN_ID}, found '
                          f'{text[:40]!r}')
    return domain


def claim_launch_domain() -> DomainClaim:
    """Claim the caller's ``ROS_DOMAIN_ID`` (unset: 0) for ``vd launch``, or refuse it."""
    domain = requested_domain(ROS_ENV) or 0
    try:
        claim = _try_lock(domain)
    except OSError as err:
        raise DomainError(f'cannot claim a ROS domain under {lock_dir()}: '
                          f'{err.strerror or err}') from None
    if claim is None:
        raise DomainError(f'{ROS_ENV}: ROS domain {domain} is in use by another vd run or vd '
                          f'launch (pid {holder(domain)}); set another {ROS_ENV} for this '
                          'launch')
    return claim


def claim_domain() -> DomainClaim:
    """Claim ``VD_DOMAIN_ID`` if set, else a free domain of :data:`DOMAINS` at random."""
    try:
        wanted = requested_domain()
        if wanted is not None:
            claim = _try_lock(wanted)
            if claim is None:
                raise DomainError(f'{ENV}: ROS domain {wanted} is in use by another vd run '
                                  f'or vd launch (pid {holder(wanted)}); unset {ENV} or '
                                  'choose another')
            return claim
        candidates = list(DOMAINS)
        random.shuffle(candidates)
        for domain in candidates:
            claim = _try_lock(domain)
            if claim is not None:
                return claim
    except OSError as err:
        raise DomainError(f'cannot claim a ROS domain under {lock_dir()}: '
                          f'{err.strerror or err}') from None
    raise DomainError(f'every ROS domain {DOMAINS.start}..{DOMAINS.stop - 1} is in use by '
                      'another vd run')
