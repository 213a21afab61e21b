# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""The study cache: the same study as a load, and a new load whenever a file it read changes."""
from __future__ import annotations

from pathlib import Path
import pickle
import threading

from numpy.testing import assert_allclose
import pytest

from vd_data_server import disk_cache, study_cache
from vd_data_server.errors import DataError
from vd_data_server.study import load_study
from vd_data_server.study_cache import cached_study
from vdtest import replace_once

TIRE = 'tires/Sedan_Pac02Tire.tir'


@pytest.fixture(autouse=True)
def private_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Each test its own cache folder (never the user's)."""
    monkeypatch.setenv('XDG_CACHE_HOME', str(tmp_path / 'cache'))
    return tmp_path / 'cache' / 'vd' / 'studies'


@pytest.fixture
def loads(monkeypatch: pytest.MonkeyPatch) -> list[Path]:
    """Record the master files ``cached_study`` loaded from the files (not from the cache)."""
    calls: list[Path] = []

    def counted(master_path, **kwargs):
        calls.append(Path(master_path))
        return load_study(master_path, **kwargs)

    monkeypatch.setattr(study_cache, 'load_study', counted)
    return calls


def _same(a, b) -> None:
    """Two studies with the same JSON, configurations (every value) and data hashes."""
    assert a.to_json() == b.to_json()
    assert a.configurations == b.configurations
    assert {n: c.data_hash for n, c in a.configurations.items()} == \
        {n: c.data_hash for n, c in b.configurations.items()}
    assert (a.status, a.groups, a.warnings) == (b.status, b.groups, b.warnings)


def test_the_cached_study_is_the_loaded_study(sedan_master: Path, loads: list[Path],
                                              private_cache: Path) -> None:
    first = cached_study(sedan_master)
    second = cached_study(sedan_master)
    assert loads == [sedan_master]  # the second came from the cache
    assert disk_cache.folder('studies') == private_cache
    assert len(list(private_cache.glob('*.pickle'))) == 1
    _same(second, load_study(sedan_master))
    _same(first, second)


def test_editing_a_data_file_loads_the_study_again(sample_root: Path, sedan_master: Path,
                                                    loads: list[Path]) -> None:
    cached_study(sedan_master)
    replace_once(sample_root / 'sedan/front_spring/X.yaml', 'rate: 30.0', 'rate: 32.5')
    after = cached_study(sedan_master)
    assert len(loads) == 2
    assert_allclose(after.configurations['baseline'].group('front_spring').scalar('rate'),
                    32.5e3, rtol=1e-12)
    _same(after, load_study(sedan_master))
    cached_study(sedan_master)  # the new entry
    assert len(loads) == 2


def test_editing_the_tire_file_or_the_master_loads_the_study_again(
        sample_root: Path, sedan_master: Path, loads: list[Path]) -> None:
    before = cached_study(sedan_master)
    tire = sample_root / TIRE
    text = tire.read_text(encoding='ascii')
    assert text.count('= 16.6 ') == 1  # LONGVL, the measurement speed
    tire.write_text(text.replace('= 16.6 ', '= 16.7 '), encoding='ascii')
    after = cached_study(sedan_master)
    assert len(loads) == 2
    for name in before.configurations:
        assert after.configurations[name].data_hash != before.configurations[name].data_hash
    sedan_master.write_text(sedan_master.read_text(encoding='utf-8') + '\n# a comment\n',
                            encoding='utf-8')
    cached_study(sedan_master)
    assert len(loads) == 3


def test_a_removed_file_loads_again_and_reports_it(sample_root: Path, sedan_master: Path,
                                                   loads: list[Path]) -> None:
    cached_study(sedan_master)
    (sample_root / TIRE).unlink()
    with pytest.raises(DataError, match='Sedan_Pac02Tire.tir'):
        cached_study(sedan_master)
    assert len(loads) == 2


def test_a_study_that_does_not_load_is_not_kept(sample_root: Path, sedan_master: Path,
                                                loads: list[Path], private_cache: Path) -> None:
    replace_once(sample_root / 'sedan/front_spring/X.yaml', 'rate: 30.0', 'rate: stiff')
    for _ in range(2):
        with pytest.raises(DataError, match='front_spring/X.yaml'):
            cached_study(sedan_master)
    assert len(loads) == 2
    assert not list(private_cache.glob('*'))


def test_a_damaged_entry_is_loaded_again(sedan_master: Path, loads: list[Path],
                                         private_cache: Path) -> None:
    cached_study(sedan_master)
    (entry,) = private_cache.glob('*.pickle')
    entry.write_bytes(entry.read_bytes()[:100])
    _same(cached_study(sedan_master), load_study(sedan_master))
    assert len(loads) == 2
    files, study = pickle.loads(entry.read_bytes())  # written again, whole
    assert Path(next(iter(files))).is_file()


def test_an_entry_names_every_file_the_load_read(sample_root: Path, sedan_master: Path,
                                                 private_cache: Path) -> None:
    study = cached_study(sedan_master)
    (entry,) = private_cache.glob('*.pickle')
    files, _ = pickle.loads(entry.read_bytes())
    read = {Path(p).resolve() for p in files}
    expected = {sedan_master.resolve(), (sample_root / TIRE).resolve()}
    for config in study.configurations.values():
        expected |= {(sample_root / g.file).resolve() for g in config.groups.values()
                     if g.file}
    assert expected <= read
    assert all(p.is_relative_to(sample_root.resolve()) for p in read)


def test_runs_writing_one_entry_together_leave_a_whole_entry(sedan_master: Path,
                                                             private_cache: Path) -> None:
    expected = load_study(sedan_master)
    results: list = []
    threads = [threading.Thread(target=lambda: results.append(cached_study(sedan_master)))
               for _ in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert len(results) == 4
    for study in results:
        _same(study, expected)
    assert [p.name for p in private_cache.iterdir() if not p.name.endswith('.pickle')] == []
    _same(cached_study(sedan_master), expected)


def test_the_oldest_entries_beyond_the_limit_are_removed(sample_root: Path, tmp_path: Path,
                                                         monkeypatch: pytest.MonkeyPatch,
                                                         private_cache: Path) -> None:
    monkeypatch.setattr(study_cache, 'MAX_ENTRIES', 2)
    masters = []
    for n in range(3):  # three master files: three entries
        master = sample_root / 'studies' / f'copy{n}.yaml'
        master.write_bytes((sample_root / 'studies' / 'sedan.yaml').read_bytes())
        masters.append(master)
        cached_study(master)
    assert len(list(private_cache.glob('*.pickle'))) == 2
