"""The outputs of a run of :func:`~wheelrail.dynamics.simulate`: rows kept in memory, or
appended to a result store (:mod:`wheelrail.dynamics.store`) through a buffer of one chunk."""

from __future__ import annotations

import numpy as np

from ._fastcontact import KMAX, PATCH_FIELDS, WHEEL_FIELDS
from ._guards import nadal_merge, nadal_scan
from ._speed import profile_eval

__all__ = ["Memory", "Stream", "outputs", "shapes"]


def outputs(n_out, system):
    nw = system.asm.n_ws
    return (np.zeros(n_out), np.zeros((n_out, system.asm.n)),
            np.zeros((n_out, nw, 2, KMAX, len(PATCH_FIELDS))),
            np.zeros((n_out, nw, 2, len(WHEEL_FIELDS))))


def shapes(system):
    nw = system.asm.n_ws
    return {"states": (system.asm.n,), "wheels": (nw, 2, len(WHEEL_FIELDS)),
            "patches": (nw, 2, KMAX, len(PATCH_FIELDS))}


class Memory:
    """The outputs of a run kept in memory (room for ``n_out`` rows)."""

    def __init__(self, n_out, system):
        self.T, self.X, self.OP, self.OW = outputs(n_out, system)
        self.n = 0

    def put(self, T, X, OP, OW):
        take = min(len(T), self.T.size - self.n)
        i = self.n
        self.T[i:i + take], self.X[i:i + take] = T[:take], X[:take]
        self.OP[i:i + take], self.OW[i:i + take] = OP[:take], OW[:take]
        self.n += take

    @property
    def full(self):
        return self.n >= self.T.size

    def arrays(self):
        n = self.n
        return self.T[:n], self.X[:n], self.OP[:n], self.OW[:n]


class Stream:
    """The outputs of a run appended to a result store (:mod:`wheelrail.dynamics.store`)
    through a buffer of one store chunk: the memory does not grow with the duration."""

    def __init__(self, writer, system):
        self.writer, self.system = writer, system
        self.buf = Memory(writer.rows, system)
        self.derailment = None

    full = False

    def put(self, T, X, OP, OW):
        done = 0
        while done < len(T):
            before = self.buf.n
            self.buf.put(T[done:], X[done:], OP[done:], OW[done:])
            done += self.buf.n - before
            if self.buf.full:
                self.flush()

    def flush(self):
        T, X, OP, OW = self.buf.arrays()
        if T.size:
            speed, accel, pos = np.empty(T.shape), np.empty(T.shape), np.empty(T.shape)
            profile_eval(self.system.SP, np.ascontiguousarray(T), speed, accel, pos)
            self.writer.append(t=T, states=X, wheels=OW, patches=OP,
                               speed=np.maximum(speed, self.system.min_speed), position=pos)
            self.derailment = nadal_merge(self.derailment, nadal_scan(self.system, T, OW))
        self.buf.n = 0
