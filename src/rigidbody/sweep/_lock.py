"""One sweep at a time per store: a lock on a file in the store, released by the OS when its process ends.

The lock is a POSIX record lock (``fcntl.lockf``; ``msvcrt.locking`` on Windows) on ``<store>/sweep/lock``,
so a sweep that is killed leaves no lock behind. Such locks are held by a process, not by the processes it
forks, and do not exclude the holding process itself: a second sweep on the same store in the same process
is refused by a table of the stores this process holds. The file also says who holds the lock (process id,
host, start time) for the error message.
"""

from __future__ import annotations

import json
import os
import socket
import sys
import threading
import time
from pathlib import Path

#: the lock file, in the store's directory (in the sub-group ``sweep``, where xarray and zarr do not look)
LOCK_PATH = ("sweep", "lock")

_held: set[str] = set()
_held_guard = threading.Lock()


def _try_lock(fd: int) -> bool:
    if sys.platform == "win32":  # pragma: no cover - tested on POSIX only
        import msvcrt

        try:
            msvcrt.locking(fd, msvcrt.LK_NBLCK, 1)
        except OSError:
            return False
        return True
    import fcntl

    try:
        fcntl.lockf(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        return False
    return True


def _in_use(path: Path, holder: str) -> RuntimeError:
    return RuntimeError(f"store {str(path)!r} is in use: another sweep is writing it{holder}; a store is written "
                        "by one sweep at a time: wait until that sweep ends, or use another store path")


class StoreLock:
    """The lock of one store, held from :meth:`acquire` to :meth:`release`."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.key = str(path.resolve())
        self.fd: int | None = None

    def acquire(self) -> StoreLock:
        """Take the lock, or raise RuntimeError naming the store (and its holder) if another sweep holds it."""
        with _held_guard:
            if self.key in _held:
                raise _in_use(self.path, f" (in this process, pid {os.getpid()})")
            lock_file = self.path.joinpath(*LOCK_PATH)
            lock_file.parent.mkdir(parents=True, exist_ok=True)
            fd = os.open(lock_file, os.O_RDWR | os.O_CREAT | getattr(os, "O_BINARY", 0), 0o644)
            if not _try_lock(fd):
                try:
                    os.lseek(fd, 0, os.SEEK_SET)
                    info = json.loads(os.read(fd, 4096).decode())
                    holder = f" (pid {info['pid']} on {info['host']}, since {info['started']})"
                except (OSError, ValueError, KeyError, TypeError):
                    holder = ""
                os.close(fd)  # this process holds no lock on the file: closing releases nothing
                raise _in_use(self.path, holder)
            info = {"pid": os.getpid(), "host": socket.gethostname(),
                    "started": time.strftime("%Y-%m-%d %H:%M:%S %z")}
            os.ftruncate(fd, 0)
            os.lseek(fd, 0, os.SEEK_SET)
            os.write(fd, json.dumps(info).encode())
            self.fd = fd
            _held.add(self.key)
        return self

    def release(self) -> None:
        with _held_guard:
            if self.fd is not None:
                os.close(self.fd)  # releases the lock
                self.fd = None
                _held.discard(self.key)
