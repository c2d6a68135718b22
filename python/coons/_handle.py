# SPDX-License-Identifier: GPL-3.0-or-later
"""Ownership of one C object (a model, body, mesh or volume mesh).

A handle is used through ``with h.use() as ptr:``; ``close()`` marks it
closed and frees the C object once no call is using it, so a thread that
closes a model while another evaluates one of its bodies never frees memory
under a running C call. A child (a body of a model) holds its parent's
handle: it keeps the parent alive, and after the parent is closed its calls
raise :class:`coons.ClosedError` instead of reading freed memory.
"""
import threading

from .errors import ClosedError


class Handle:
    __slots__ = ("_ptr", "_free", "_lock", "_users", "_closed", "what", "__weakref__")

    def __init__(self, ptr, free, what):
        self._ptr = ptr
        self._free = free
        self._lock = threading.RLock()  # re-entered when GC runs __del__ under it
        self._users = 0
        self._closed = False
        self.what = what

    @property
    def closed(self):
        return self._closed

    def use(self):
        return _Use(self)

    def _acquire(self):
        with self._lock:
            if self._closed:
                raise ClosedError("the %s is closed" % self.what)
            self._users += 1
            return self._ptr

    def _release(self):
        ptr = None
        with self._lock:
            self._users -= 1
            if self._closed and self._users == 0:
                ptr = self._ptr
                self._ptr = None
        if ptr is not None:
            self._free(ptr)

    def close(self):
        ptr = None
        with self._lock:
            self._closed = True
            if self._users == 0:
                ptr = self._ptr
                self._ptr = None
        if ptr is not None:
            self._free(ptr)

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass


class _Use:
    __slots__ = ("_h",)

    def __init__(self, h):
        self._h = h

    def __enter__(self):
        return self._h._acquire()

    def __exit__(self, *exc):
        self._h._release()
        return False
