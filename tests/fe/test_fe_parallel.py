"""The explicit rolling run on 1 and 2 threads: the same numbers bit for bit.

The parallel kernels (element forces in parity-ordered chunks, the contact over slave
chunks, the node update with fixed-chunk partial sums) never let two threads add to the
same number and sum in an order that does not depend on the threads.
"""

import numba
import numpy as np

import wheelrail as wr
from wheelrail.fe import J2Plastic, RollingCase, solve
from wheelrail.fe.materials import R900A_HARDENING


def test_rolling_is_bitwise_identical_on_one_and_two_threads():
    flat = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")
    case = RollingCase(wheel=flat, rail=wr.profiles.load("60E1"), radius=0.46, load=7500.0,
                       mu=0.2, creepage=(7e-4, 2e-4, 0.0), mesh_size=2e-3, element="reduced",
                       mass_scaling=400, depth=3, half_width=3, half_length=3, travel=0.005,
                       material=J2Plastic(2.1e11, 0.28, 1.7e8, hardening=R900A_HARDENING))
    default = numba.get_num_threads()
    runs = {}
    try:
        for threads in (1, min(2, numba.config.NUMBA_NUM_THREADS)):
            numba.set_num_threads(threads)
            runs[threads] = solve(case, progress=False, output_every=1)
    finally:
        numba.set_num_threads(default)
    r1, r2 = runs[1], runs[max(runs)]
    np.testing.assert_array_equal(r1.u, r2.u)
    np.testing.assert_array_equal(r1.state.committed, r2.state.committed)
    for name in ("Fx", "Fy", "Fn", "internal", "contact_work"):
        np.testing.assert_array_equal(r1.dataset[name].values, r2.dataset[name].values)
    assert float(r1.fields.rail_equivalent_plastic_strain.max()) > 0
    # after a run the kernels are cached: the time estimate of the next run must not add
    # the one-off compile time (it did, +35 s, when inlined helpers were checked for a cache)
    from wheelrail.cli.fe import _kernels_cached
    assert _kernels_cached()


def test_task_counter_hands_out_each_task_once_and_only_in_its_phase():
    from numba import njit, prange

    from wheelrail.fe._explicit import _TAKE, _open_tasks, _take_task

    @njit(parallel=True)
    def take_all(ctl, p, owner, order):
        for w in prange(2):                      # thread 0 from the front, thread 1 from the back
            t = _take_task(ctl, p, w == 1)
            last = -1
            while t >= 0:
                owner[t] += w + 1
                if (w == 0 and t < last) or (w == 1 and last >= 0 and t > last):
                    order[0] = 1                 # out of order
                last = t
                t = _take_task(ctl, p, w == 1)

    for n in (1, 7, 200):
        ctl = np.zeros(32, np.int64)
        ctl[_TAKE] = _open_tasks(5, n)           # phase 5, tasks 0 ... n - 1
        owner = np.zeros(n, np.int64)
        order = np.zeros(1, np.int64)
        take_all(ctl, 5, owner, order)
        assert np.all((owner == 1) | (owner == 2))       # each task taken by one thread once
        assert order[0] == 0                             # front ascending, back descending
        lo, hi = ctl[_TAKE] & 0xFFFF, (ctl[_TAKE] >> 16) & 0xFFFF
        assert ctl[_TAKE] >> 32 == 5 and lo == hi       # the range is used up, still phase 5
        take_all(ctl, 4, owner, order)                   # a late thread of phase 4 takes nothing
        take_all(ctl, 6, owner, order)                   # nor one of phase 6 before it opens
        assert np.all((owner == 1) | (owner == 2))
    ctl = np.zeros(32, np.int64)
    ctl[_TAKE] = _open_tasks(0, 4)
    assert [_take_task(ctl, 0, b) for b in (True, False, True, False, False)] == [3, 0, 2, 1, -1]


def test_rolling_loop_finishes_when_fewer_threads_run_it_than_it_was_told(monkeypatch):
    """run_steps keeps its threads in one region with its own waits: a thread waits only for
    tasks another thread has taken, so the loop also ends (with the same numbers) if its
    parallel loop over ``nthr`` runs on fewer threads."""
    import wheelrail.fe.explicit as EX

    flat = wr.Profile(np.linspace(-0.04, 0.04, 9), np.zeros(9), kind="wheel")
    case = RollingCase(wheel=flat, rail=wr.profiles.load("60E1"), radius=0.46, load=7500.0,
                       mu=0.2, creepage=(7e-4, 2e-4, 0.0), mesh_size=2e-3, element="reduced",
                       mass_scaling=400, depth=3, half_width=3, half_length=3, travel=0.002)
    default = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        r1 = solve(case, progress=False, output_every=1)
        monkeypatch.setattr(EX.numba, "get_num_threads", lambda: 3)
        r3 = solve(case, progress=False, output_every=1)
    finally:
        monkeypatch.undo()
        numba.set_num_threads(default)
    np.testing.assert_array_equal(r1.u, r3.u)
    np.testing.assert_array_equal(r1.dataset["Fx"].values, r3.dataset["Fx"].values)

