# Copyright 2026 The vd authors
# SPDX-License-Identifier: Apache-2.0
"""
rosbag2 MCAP bags written and read with rosbags (pure Python).

Messages are typed vd_interfaces messages with their definitions embedded, so
Foxglove, PlotJuggler, the ``mcap`` library and ``ros2 bag`` read them. Chunks are
zstd-compressed (MCAP storage compression, which rosbags, ``mcap`` and ``mcap_ros2``
read), every topic records the QoS its publishers offered (``offered_qos_profiles``
in ``metadata.yaml``, rosbag2 format 9, so ``ros2 bag play`` reproduces latching),
``ros_distro`` is ``jazzy``, and a message's log time is its own stamp where it has one
(:func:`log_time`). A bag
is written under ``<name>.partial`` and renamed to ``<name>`` when closed: an
interrupted run never leaves a bag that looks finished (and ``abort()`` removes
the partial one). The writer holds an exclusive lock on ``<name>.partial/writer.lock``
for its life; a partial bag whose lock nobody holds is left by a process that was
killed (``kill -9``) and is replaced by the next writer of the same bag.
"""
from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
import fcntl
from functools import lru_cache
import os
from pathlib import Path
import shutil
from typing import TYPE_CHECKING, Any

from ament_index_python.packages import get_package_share_directory

from vd_data_server.errors import DataError
from vd_data_server.yamlio import load_file
from vd_events.errors import BagError

# rosbags and rclpy (the QoS profiles, the serialisation) are imported where a bag is
# written or read: a run without a bag (and the command line's start) does not pay for them
if TYPE_CHECKING:
    from rclpy.qos import QoSProfile
    from rosbags.interfaces import Qos
    from rosbags.typesys.store import Typestore

PARTIAL_SUFFIX = '.partial'
LOCK_NAME = 'writer.lock'
BAG_VERSION = 9
INTERFACES = 'vd_interfaces'
#: the ROS distribution the bags are written for (metadata ``ros_distro``)
ROS_DISTRO = 'jazzy'
_ROSBAGS_DISTRO = 'ros_distro: rosbags'




@lru_cache(maxsize=1)
def typestore() -> Typestore:
    """Jazzy's types plus every vd_interfaces message, from the installed .msg files."""
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    store = get_typestore(Stores.ROS2_JAZZY)
    msg_dir = Path(get_package_share_directory(INTERFACES)) / 'msg'
    types: dict[str, Any] = {}
    for path in sorted(msg_dir.glob('*.msg')):
        if not path.is_file():  # a dangling link a removed message left in an install
            continue
        types.update(get_types_from_msg(path.read_text(), f'{INTERFACES}/msg/{path.stem}'))
    store.register(types)
    return store


def check_bag_path(path: Path) -> None:
    """Refuse an existing bag (or partial one) and an unwritable parent, before any work."""
    if path.exists():
        raise BagError(f'{path}: bag path already exists (choose another --bag)')
    partial = path.with_name(path.name + PARTIAL_SUFFIX)
    if partial.exists() and _partial_is_live(partial):
        raise BagError(f'{partial}: another run is writing this bag')
    if partial.exists() and not partial.is_dir():
        raise BagError(f'{partial}: is in the way and is not a partial bag (remove it)')
    parent = path.parent
    probe = parent
    while not probe.exists():
        probe = probe.parent
    if not probe.is_dir() or not _writable(probe):
        raise BagError(f'{path}: cannot write under {probe}')


def _writable(folder: Path) -> bool:
    return os.access(folder, os.W_OK | os.X_OK)


def _partial_is_live(partial: Path) -> bool:
    """Tell whether a writer holds the partial bag's lock (a live run writes it)."""
    try:
        fd = os.open(partial / LOCK_NAME, os.O_RDONLY)
    except FileNotFoundError:
        return False
    except OSError:
        return True  # cannot tell: do not touch it
    try:
        fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
    except BlockingIOError:
        return True
    finally:
        os.close(fd)
    return False


@lru_cache(maxsize=1)
def _writer_class() -> type:
    """Return rosbags' Writer whose metadata names the Jazzy distribution."""
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.rosbag2.storage_mcap import McapWriter

    class JazzyMcapWriter(McapWriter):
        """rosbags' MCAP storage, with the metadata record naming the Jazzy distribution."""

        def close(self, version: int, metadata: str) -> None:
            super().close(version, metadata.replace(_ROSBAGS_DISTRO,
                                                    f'ros_distro: {ROS_DISTRO}'))

    class JazzyWriter(Writer):
        STORAGE_PLUGINS = {StoragePlugin.MCAP: JazzyMcapWriter}

        def close(self) -> None:
            super().close()
            text = self.metapath.read_text(encoding='utf-8')
            self.metapath.write_text(
                text.replace(_ROSBAGS_DISTRO, f'ros_distro: {ROS_DISTRO}'), encoding='utf-8')

    return JazzyWriter


def qos_record(profile) -> Qos:
    """Return the bag's record of an rclpy QoSProfile (the same enumerations, by value)."""
    from rosbags.interfaces import (
        Qos,
        QosDurability,
        QosHistory,
        QosLiveliness,
        QosReliability,
        QosTime,
    )

    def duration(d) -> QosTime:
        ns = d.nanoseconds
        return QosTime(ns // 1_000_000_000, ns % 1_000_000_000)

    return Qos(history=QosHistory(int(profile.history)), depth=int(profile.depth),
               reliability=QosReliability(int(profile.reliability)),
               durability=QosDurability(int(profile.durability)),
               deadline=duration(profile.deadline), lifespan=duration(profile.lifespan),
               liveliness=QosLiveliness(int(profile.liveliness)),
               liveliness_lease_duration=duration(profile.liveliness_lease_duration),
               avoid_ros_namespace_conventions=bool(profile.avoid_ros_namespace_conventions))


def offered_profiles(node: Any, topic: str, own: QoSProfile) -> list[QoSProfile]:
    """
    Return the QoS profiles the publishers of ``topic`` offer, as ``node`` discovered them.

    History and depth, which discovery does not carry, are taken from ``own`` (the
    profile vd publishes the topic with, vd_data_server.ros.qos); with no publisher
    discovered yet, ``[own]``.
    """
    from rclpy.qos import HistoryPolicy

    out = []
    for info in node.get_publishers_info_by_topic(topic):
        q = info.qos_profile
        if q.history == HistoryPolicy.UNKNOWN or q.depth == 0:
            q.history, q.depth = own.history, own.depth
        out.append(q)
    return out or [own]


def offered_qos(path: str | Path) -> dict[str, list]:
    """
    Return topic -> the rclpy QoSProfiles its publishers offered, from a bag's metadata.

    What ``ros2 bag play`` publishes with.
    """
    from rclpy.duration import Duration
    from rclpy.qos import (
        DurabilityPolicy,
        HistoryPolicy,
        LivelinessPolicy,
        QoSProfile,
        ReliabilityPolicy,
    )

    def duration(d) -> Duration:
        return Duration(seconds=int(d['sec']), nanoseconds=int(d['nsec']))

    out = {}
    for entry in bag_metadata(path)['topics_with_message_count']:
        topic = entry['topic_metadata']
        out[topic['name']] = [QoSProfile(
            history=HistoryPolicy[q['history'].upper()], depth=int(q['depth']),
            reliability=ReliabilityPolicy[q['reliability'].upper()],
            durability=DurabilityPolicy[q['durability'].upper()],
            deadline=duration(q['deadline']), lifespan=duration(q['lifespan']),
            liveliness=LivelinessPolicy[q['liveliness'].upper()],
            liveliness_lease_duration=duration(q['liveliness_lease_duration']),
            avoid_ros_namespace_conventions=bool(q['avoid_ros_namespace_conventions']))
            for q in topic['offered_qos_profiles']]
    return out


def as_offered(profile: QoSProfile) -> QoSProfile:
    """
    Return ``profile`` as discovery reports a publisher offering it.

    rmw reports a publisher's unset ("system default") liveliness as automatic and its
    unset deadline, lifespan and liveliness lease as infinite: a bag written without a
    live publisher records what one recorded from the graph does.
    """
    from rclpy.duration import Infinite
    from rclpy.qos import LivelinessPolicy, QoSProfile

    liveliness = profile.liveliness
    if liveliness == LivelinessPolicy.SYSTEM_DEFAULT:
        liveliness = LivelinessPolicy.AUTOMATIC
    out = QoSProfile(history=profile.history, depth=profile.depth,
                     reliability=profile.reliability, durability=profile.durability,
                     liveliness=liveliness,
                     avoid_ros_namespace_conventions=profile.avoid_ros_namespace_conventions)
    for name in ('deadline', 'lifespan', 'liveliness_lease_duration'):
        value = getattr(profile, name)
        setattr(out, name, Infinite if value.nanoseconds == 0 else value)
    return out


#: a run's bag metadata: what wrote it (``vd run``'s recorder, in the graph or not)
RECORDER_DATA = {'vd.recorder': 'vd_events recorder'}


def provenance_data(msg: Any) -> dict[str, str]:
    """
    Return a bag's metadata of a run's vd_interfaces/Provenance.

    ``vd.configuration``, ``vd.data_hash``, ``vd.model``, ``vd.fidelity``, ``vd.event``,
    ``vd.master_file``, ``vd.software_version`` and ``vd.modified`` (the keys the run's
    overrides and the master file changed, ``group.key=value unit; ...``, or ``none``).
    """
    out = {f'vd.{key}': str(getattr(msg, key)) for key in (
        'configuration', 'data_hash', 'model', 'fidelity', 'event', 'master_file',
        'software_version')}
    out['vd.modified'] = '; '.join(
        f'{g.group}.{k.key}={k.master_value} {k.unit}'.strip()
        for g in msg.groups for k in g.modified_keys) or 'none'
    return out


def cannot_write(path: Path, err: OSError) -> BagError:
    """Return the error of a bag that cannot be written (a full disk, a read-only mount)."""
    return BagError(f'{path}: cannot write the bag: {err.strerror or err}')


def log_time(msg: Any, fallback_ns: int) -> int:
    """
    Return the log time of ``msg`` in a bag.

    Its ``header.stamp`` (or ``stamp``, or its first transform's stamp), else
    ``fallback_ns`` (the reception time).
    """
    stamp = getattr(msg, 'stamp', None)
    if stamp is None and hasattr(msg, 'header'):
        stamp = msg.header.stamp
    if stamp is None and getattr(msg, 'transforms', None):
        stamp = msg.transforms[0].header.stamp
    if stamp is None:
        return fallback_ns
    ns = int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)
    return ns if ns > 0 else fallback_ns


class BagWriter:
    """Writes rclpy messages (serialised CDR) to an MCAP rosbag2 bag, atomically."""

    def __init__(self, path: str | Path, custom_data: Mapping[str, str] | None = None) -> None:
        # imported before the partial folder exists: a signal during the import
        # leaves nothing behind
        from rclpy.serialization import serialize_message
        from rosbags.rosbag2 import CompressionFormat, CompressionMode, StoragePlugin

        self._serialize = serialize_message

        writer_class = _writer_class()
        self.path = Path(path)
        check_bag_path(self.path)
        # rosbags names the storage file after the bag folder, so the bag is built
        # with its final name inside a '<name>.partial' folder and moved out when done.
        self.partial = self.path.with_name(self.path.name + PARTIAL_SUFFIX)
        self._lock = -1
        self.closed = False
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self.replaced_stale = self.partial.is_dir()
            if self.replaced_stale:  # left by a killed run (check_bag_path saw no live writer)
                shutil.rmtree(self.partial)
            try:
                self.partial.mkdir()
            except FileExistsError:
                raise BagError(f'{self.partial}: another run is writing this bag') from None
            self._lock = os.open(self.partial / LOCK_NAME, os.O_RDWR | os.O_CREAT, 0o644)
            fcntl.flock(self._lock, fcntl.LOCK_EX)
            self._writer = writer_class(self.partial / self.path.name, version=BAG_VERSION,
                                        storage_plugin=StoragePlugin.MCAP)
            self._writer.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
            for key, value in (custom_data or {}).items():
                self._writer.set_custom_data(key, value)
            self._writer.open()
        except OSError as err:  # a full disk, a folder under /proc, a read-only mount
            if self._lock >= 0:
                shutil.rmtree(self.partial, ignore_errors=True)
                self._unlock()
            raise cannot_write(self.path, err) from None
        self._connections: dict[str, Any] = {}
        self.count = 0

    def set_custom_data(self, key: str, value: str) -> None:
        self._writer.set_custom_data(key, value)

    def write(self, topic: str, msg: Any, timestamp_ns: int, qos: Sequence[QoSProfile]) -> None:
        """
        Write ``msg`` at log time ``timestamp_ns``.

        ``qos`` (rclpy QoSProfiles, at least one) is what the topic's publishers offered,
        recorded with the topic's first message: ``ros2 bag play`` publishes with it.
        """
        msgtype = _type_name(msg)
        conn = self._connections.get(topic)
        if conn is None:
            if not qos:
                raise ValueError(f'{topic}: a bag topic needs the QoS its publishers offered')
            conn = self._writer.add_connection(
                topic, msgtype, typestore=typestore(),
                offered_qos_profiles=[qos_record(q) for q in qos])
            self._connections[topic] = conn
        self._writer.write(conn, int(timestamp_ns), self._serialize(msg))
        self.count += 1

    def close(self) -> Path:
        """Finish the bag and give it its final name."""
        if not self.closed:
            self._writer.close()
            (self.partial / self.path.name).rename(self.path)
            (self.partial / LOCK_NAME).unlink()
            self._unlock()
            self.partial.rmdir()
            self.closed = True
        return self.path

    def _unlock(self) -> None:
        if self._lock >= 0:
            os.close(self._lock)
            self._lock = -1

    def abort(self) -> None:
        """Drop an unfinished bag: nothing that looks like a result is left."""
        if not self.closed:
            try:
                self._writer.close()
            finally:
                shutil.rmtree(self.partial, ignore_errors=True)
                self._unlock()
                self.closed = True


def _type_name(msg: Any) -> str:
    """``vd_interfaces/msg/EventResult`` from an rclpy message instance."""
    module = type(msg).__module__.split('.')  # e.g. vd_interfaces.msg._event_result
    return f'{module[0]}/{module[1]}/{type(msg).__name__}'


@dataclass(frozen=True)
class BagMessage:
    topic: str
    msgtype: str
    timestamp: int
    msg: Any  # rosbags dataclass instance


def read_bag(path: str | Path, topics: set[str] | None = None) -> Iterator[BagMessage]:
    """
    Yield every message (deserialised with rosbags) of a finished bag.

    A bag that cannot be read whole (a truncated ``.mcap``, a broken ``metadata.yaml``,
    a message that does not deserialise) raises :class:`BagError` naming the bag.
    """
    from rosbags.rosbag2 import Reader

    path = Path(path)
    bag_metadata(path)
    store = typestore()
    try:
        with Reader(path) as reader:
            conns = [c for c in reader.connections if topics is None or c.topic in topics]
            if not conns:  # rosbags reads every connection when given none
                return
            for conn, timestamp, raw in reader.messages(connections=conns):
                yield BagMessage(conn.topic, conn.msgtype, timestamp,
                                 store.deserialize_cdr(raw, conn.msgtype))
    except BagError:
        raise
    except Exception as err:  # noqa: BLE001 - rosbags and the MCAP reader raise many kinds
        raise BagError(f'{path}: not a readable rosbag2 bag ({_reason(err)})') from None


def _reason(err: BaseException) -> str:
    text = str(err).strip().splitlines()[0] if str(err).strip() else ''
    return f'{type(err).__name__}: {text}' if text else type(err).__name__


def bag_metadata(path: str | Path) -> dict[str, Any]:
    """
    Return a finished bag's ``metadata.yaml`` information, checked for what vd reads of it.

    Read with the bounded YAML loader; a missing, malformed or incomplete file raises
    :class:`BagError` naming the bag.
    """
    path = Path(path)
    meta_file = path / 'metadata.yaml'
    if not meta_file.is_file():
        raise BagError(f'{path}: not a finished rosbag2 bag (no metadata.yaml)')
    try:
        meta = load_file(meta_file, display=str(meta_file))
    except DataError as err:
        raise BagError(f'{path}: broken metadata.yaml ({err.detail})') from None
    info = meta.get('rosbag2_bagfile_information') if isinstance(meta, dict) else None
    if not isinstance(info, dict):
        info = {}
    topics = info.get('topics_with_message_count')
    if not isinstance(topics, list) or not all(
            isinstance(t, dict) and isinstance(t.get('topic_metadata'), dict) for t in topics):
        raise BagError(f'{path}: broken metadata.yaml (no rosbag2_bagfile_information with '
                       'its topics_with_message_count)')
    custom = info.get('custom_data') or {}
    if not isinstance(custom, dict):
        raise BagError(f'{path}: broken metadata.yaml (custom_data is not a mapping)')
    return info


def custom_data(path: str | Path) -> dict[str, str]:

    return {str(k): str(v) for k, v in (bag_metadata(path).get('custom_data') or {}).items()}
