"""Newton iterations on the generalized unknowns q = [u (body frames), w] (private).

Residual (gradient of the potential plus inertia terms of the integrator):

    r(q) = K u − f_c(q) + F e_w + r_dyn(q),

with ``f_c`` the penalty contact forces mapped to the body frames (wheel
forces rotated by Qᵀ, their vertical sum acting on the axle dof ``w``) and
``F`` the wheel load. The tangent is K + Tᵀ C T, C the 3×3 contact tangent of
each closed pair (normal penalty, penalty stick or the consistent slip tangent
of the return map) and T the map from q to the pair's relative displacement.
"""

from __future__ import annotations

import numpy as np

from ..errors import ConvergenceError

_DEBUG = False


def contact_tangent_parts(model, c, psi, mu, n_dof):
    """The closed pairs' tangent factors: T (na, 3, 16), C (na, 3, 3), dofs (na, 16).

    The contact tangent is Σ_a T_aᵀ C_a T_a scattered to ``dofs[a]`` (generalized dofs);
    ``na = 0`` gives empty arrays.
    """
    act = np.flatnonzero(c["status"] > 0)
    if act.size == 0:
        return np.zeros((0, 3, 16)), np.zeros((0, 3, 3)), np.zeros((0, 16), np.int64)
    n = c["normal"][act]
    A = model.slave_area[act]
    kt = model.kn[act] * A
    kn = kt * np.clip(-c["gap"][act] / model.g0, 0.0, 1.0)
    C = kn[:, None, None] * n[:, :, None] * n[:, None, :]
    Pt = np.eye(3)[None] - n[:, :, None] * n[:, None, :]
    if mu > 0:
        ft = c["ft"][act]
        stick = c["status"][act] == 1
        C[stick] += kt[stick, None, None] * Pt[stick]
        sl = ~stick
        if np.any(sl):
            fmag = np.linalg.norm(ft[sl], axis=1)
            t = ft[sl] / np.maximum(fmag, 1e-300)[:, None]
            ftr = fmag + kt[sl] * c["slip"][act][sl]
            ratio = fmag / np.maximum(ftr, 1e-300)
            C[sl] += (kt[sl] * ratio)[:, None, None] * (Pt[sl] - t[:, :, None] * t[:, None, :])
            C[sl] += mu * kn[sl, None, None] * t[:, :, None] * n[sl][:, None, :]
    na = act.size
    T = np.zeros((na, 3, 16))
    dofs = np.zeros((na, 16), np.int64)
    Q = model.rotation(psi)
    node = model.slave[act]
    T[:, :, 0:3] = Q[None]
    dofs[:, 0:3] = 3 * node[:, None] + np.arange(3)
    T[:, 2, 3] = 1.0
    dofs[:, 3] = n_dof - 1
    i, j = c["cell"][act, 0], c["cell"][act, 1]
    r, s = c["rt"][act, 0], c["rt"][act, 1]
    wts = [(1 - r) * (1 - s), r * (1 - s), r * s, (1 - r) * s]
    corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
    for m, (ii, jj) in enumerate(corners):
        mn = model.master[ii, jj]
        for d in range(3):
            T[:, d, 4 + 3 * m + d] = -wts[m]
        dofs[:, 4 + 3 * m:7 + 3 * m] = 3 * mn[:, None] + np.arange(3)
    return T, C, dofs


def contact_tangent(model, c, psi, mu, n_dof):
    """Sparse Tᵀ C T of the closed contact pairs (n_dof × n_dof, CSR)."""
    import scipy.sparse as sp

    T, C, dofs = contact_tangent_parts(model, c, psi, mu, n_dof)
    if T.shape[0] == 0:
        return sp.csr_matrix((n_dof, n_dof))
    Ks = np.einsum("aip,aij,ajq->apq", T, C, T)
    rows = np.repeat(dofs[:, :, None], 16, axis=2).ravel()
    cols = np.repeat(dofs[:, None, :], 16, axis=1).ravel()
    return sp.coo_matrix((Ks.ravel(), (rows, cols)), shape=(n_dof, n_dof)).tocsr()


#: Systems with more unknowns than this use AMG-preconditioned GMRES instead of SuperLU.
DIRECT_LIMIT = 200000

#: Factorise with SuperLU's symmetric mode (minimum degree on Aᵀ + A, diagonal pivots, no
#: row interchanges): the Newton matrices are symmetric up to the friction terms and
#: diagonally dominant, and this mode is about 1.7x faster than the default partial
#: pivoting on these meshes (benchmarks/bench_fe.py). False restores the pivoted solve.
SYMMETRIC_FACTOR = True


def factorize(A):
    """Sparse LU factors of A (CSC) — symmetric mode with a pivoted fallback.

    The symmetric-mode factors are accepted when a solve with them leaves a relative
    residual below 1e-10 on a test vector; otherwise (or if a zero pivot occurs) SuperLU's
    partial pivoting is used.
    """
    import scipy.sparse.linalg as sla

    A = A.tocsc()
    if SYMMETRIC_FACTOR:
        try:
            lu = sla.splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                          options=dict(SymmetricMode=True))
            x = np.linspace(1.0, 2.0, A.shape[0])
            b = A @ x
            if np.linalg.norm(lu.solve(b) - x) <= 1e-10 * np.linalg.norm(x):
                return lu
        except RuntimeError:
            pass
    return sla.splu(A, permc_spec="MMD_AT_PLUS_A")


def solve_linear(A, b):
    """Solve the Newton system.

    Small systems: sparse direct (SuperLU via :func:`factorize`).
    Large ones (> :data:`DIRECT_LIMIT` unknowns): GMRES preconditioned by
    smoothed-aggregation AMG (pyamg), relative tolerance 1e-10 — SuperLU's fill-in
    on 3-D hex meshes makes the direct solve minutes long beyond ~50 000 unknowns.
    """
    import scipy.sparse.linalg as sla

    if A.shape[0] <= DIRECT_LIMIT:
        return factorize(A).solve(b)
    import pyamg

    A = A.tocsr()
    ml = pyamg.smoothed_aggregation_solver(A, symmetry="nonsymmetric", max_coarse=2000)
    M = ml.aspreconditioner(cycle="V")
    x, info = sla.gmres(A, b, M=M, rtol=1e-10, atol=0.0, restart=60, maxiter=20)
    if info != 0:
        res = np.linalg.norm(A @ x - b) / max(np.linalg.norm(b), 1e-300)
        if res > 1e-6:
            raise ConvergenceError(f"AMG-GMRES stopped at relative residual {res:.3g} "
                                   f"({A.shape[0]} unknowns)")
    return x


class DirectSolver:
    """Newton-system solver: a fresh sparse factorisation (:func:`solve_linear`) per call.

    Attributes
    ----------
    factorizations, krylov_iterations, solves : int
        Counters (reported in the result's ``info``).
    seconds : float
        Wall time spent in the linear solves [s].
    """

    def __init__(self):
        self.lu = None
        self.factorizations = 0
        self.krylov_iterations = 0
        self.solves = 0
        self.seconds = 0.0

    def solve(self, J, b):
        import time

        t = time.perf_counter()
        self.solves += 1
        self.factorizations += 1
        x = solve_linear(J, b)
        self.seconds += time.perf_counter() - t
        return x


class ReusedFactorSolver(DirectSolver):
    """Newton-system solver that reuses one sparse LU factorisation across iterations and steps.

    ``solve(J, b)`` runs GMRES on ``J x = b`` preconditioned by the SuperLU factors of an
    earlier tangent (the elastic, mass and damping parts of J are constant during a run;
    only the contact part changes). When GMRES needs more than ``max_krylov`` iterations
    (the contact tangent has drifted), J is factorised afresh and solved directly; the new
    factors become the preconditioner. Relative tolerance 1e-10.
    """

    def __init__(self, max_krylov: int = 40, rtol: float = 1e-10):
        super().__init__()
        self.max_krylov = max_krylov
        self.rtol = rtol

    def _factor(self, J):
        self.lu = factorize(J)
        self.factorizations += 1

    def solve(self, J, b):
        import time

        t = time.perf_counter()
        try:
            return self._solve(J, b)
        finally:
            self.seconds += time.perf_counter() - t

    def _solve(self, J, b):
        import scipy.sparse.linalg as sla

        self.solves += 1
        if J.shape[0] > DIRECT_LIMIT:
            return solve_linear(J, b)
        if self.lu is None:
            self._factor(J)
            return self.lu.solve(b)
        n = J.shape[0]
        M = sla.LinearOperator((n, n), matvec=self.lu.solve, dtype=float)
        count = [0]

        def cb(_):
            count[0] += 1

        x, info = sla.gmres(J, b, M=M, rtol=self.rtol, atol=0.0, restart=self.max_krylov,
                            maxiter=1, callback=cb, callback_type="pr_norm")
        self.krylov_iterations += count[0]
        if info == 0:
            return x
        self._factor(J)
        return self.lu.solve(b)


class PardisoSolver(DirectSolver):
    """Newton-system solver: a fresh MKL PARDISO factorisation per call (optional extra).

    PARDISO (real unsymmetric, ``mtype=11``; nested-dissection ordering; on one MKL thread,
    so that runs and restarts are reproducible bit for bit) factorises the 3-D hex meshes' Newton matrices 2.3-4.6x faster
    than SuperLU on one thread (54 061 unknowns: 3.2 s against 14.7 s CPU,
    benchmarks/bench_fe_plastic.py ``linear-solvers``). Every solve is checked: a relative
    residual above 1e-10 (PARDISO perturbs tiny pivots) falls back to SuperLU.

    Raises
    ------
    ImportError
        When pypardiso is not installed (``pip install wheelrail[pardiso]``, x86-64 only).

    References
    ----------
    O. Schenk, K. Gärtner, "Solving unsymmetric sparse systems of linear equations with
    PARDISO", Future Generation Computer Systems 20 (2004) 475–487.
    """

    def __init__(self):
        super().__init__()
        try:
            import pypardiso
        except ImportError as e:
            raise ImportError("linear_solver='pardiso' needs pypardiso (MKL PARDISO): "
                              "pip install 'wheelrail[pardiso]' (x86-64 only)") from e
        self._pardiso = pypardiso.PyPardisoSolver(mtype=11)
        self.fallbacks = 0

    def solve(self, J, b):
        import time
        import warnings

        import scipy.sparse as sp

        t = time.perf_counter()
        self.solves += 1
        self.factorizations += 1
        A = sp.csr_matrix(J)
        A.sort_indices()
        # one MKL thread: a multithreaded factorisation is not reproducible bit for bit
        # (a restart must continue a run exactly); the speed-up over SuperLU was measured
        # on one thread
        local = _mkl_threads_local(self._pardiso)
        before = local(1) if local is not None else None
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", sp.SparseEfficiencyWarning)
                x = self._pardiso.solve(A, np.asarray(b, dtype=float))
        finally:
            if local is not None:
                local(before)
        res = np.linalg.norm(A @ x - b)
        if not np.isfinite(res) or res > 1e-10 * max(np.linalg.norm(b), 1e-300):
            self.fallbacks += 1
            x = solve_linear(J, b)
        self.seconds += time.perf_counter() - t
        return x


def _mkl_threads_local(pardiso):
    """MKL's ``MKL_Set_Num_Threads_Local`` (C interface, int by value; returns the previous
    thread-local setting, 0 = none) of the library pypardiso loaded, or None."""
    import ctypes

    f = getattr(getattr(pardiso, "libmkl", None), "MKL_Set_Num_Threads_Local", None)
    if f is not None:
        f.argtypes, f.restype = [ctypes.c_int], ctypes.c_int
    return f


def pardiso_available() -> bool:
    """Whether MKL PARDISO (pypardiso, the ``pardiso`` extra) can be imported."""
    try:
        import pypardiso  # noqa: F401
    except ImportError:
        return False
    return True


def auto_solver():
    """The fastest installed direct solver: PARDISO if pypardiso imports, else SuperLU."""
    return PardisoSolver() if pardiso_available() else DirectSolver()


#: The Newton-system solvers by their ``linear_solver`` name (the one list of the choices).
LINEAR_SOLVERS = {"auto": auto_solver, "direct": DirectSolver, "reuse": ReusedFactorSolver,
                  "pardiso": PardisoSolver}


def make_solver(name):
    """The Newton-system solver of ``RollingCase.linear_solver``."""
    return LINEAR_SOLVERS[name]()


def newton(model, Kff, free, u, w, psi, s, xs_prev, xm_prev, ft_old, mu, load, *,
           dyn=None, static_scale=1.0, diag=None, tol=3e-3, max_iter=40, solver=None,
           state=None, tangent=None):
    """Solve one (quasi-)static or implicit-dynamic step.

    Parameters
    ----------
    Kff : sparse (n_free, n_free)
        Stiffness restricted to the free generalized dofs (``free`` indexes into
        ``[u.ravel(), w]``), including any constant dynamic terms.
    dyn : callable, optional
        ``dyn(q) -> r_dyn`` extra residual (inertia) on the full vector.
    static_scale : float
        Factor on the static residual and its tangent (1 + α for HHT-α).
    diag : ndarray, optional
        Constant diagonal added to the tangent (over the free dofs): the
        Jacobian of ``dyn`` (lumped mass / (β Δt²) for HHT-α).
    solver : DirectSolver or ReusedFactorSolver, optional
        The linear solver (counts and times its work); default: a fresh
        :class:`DirectSolver`.
    state : PlasticState, optional
        Plastic materials: the residual's internal forces come from the return map from
        ``state.committed``; on return ``state.trial`` belongs to the solution (the caller
        commits it).
    tangent : callable, optional
        ``tangent(q)`` -> the free-dof stiffness at the iterate q (the consistent
        elasto-plastic tangent); replaces the constant ``Kff``.

    tol : float
        Convergence: the largest residual force below ``tol * load`` with an unchanged
        active set. The interpolated (continuous) contact normals make the contact
        forces not exactly the gradient of the penalty energy, which limits the
        attainable residual to about 0.1-0.2 % of the load on curved, inclined
        surfaces; hence 3e-3 by default.

    Returns
    -------
    u, w, contact dict, iterations
    """
    n_dof = 3 * model.n_nodes + 1
    q = np.concatenate([u.ravel(), [w]])
    scale = max(load, 1.0)
    if solver is None:
        solver = DirectSolver()

    def residual(q):
        uu = q[:-1].reshape(-1, 3)
        c = model.contact(uu, q[-1], psi, s, xs_prev, xm_prev, ft_old, mu)
        f_int, _ = model.internal_force(uu, state=state)
        fc, fcw = model.generalized_contact_force(c, psi)
        r = static_scale * np.concatenate([(f_int - fc).ravel(), [load - fcw]])
        if dyn is not None:
            r += dyn(q)
        c["potential"] = 0.5 * float(q[:-1] @ f_int.ravel()) + float(c["energy"].sum()) \
            + load * float(q[-1])
        return r[free], c

    # frictionless elastic statics: minimize the potential
    energy_search = dyn is None and mu == 0.0 and state is None
    rf, c = residual(q)
    norm = np.linalg.norm(rf)
    prev_active = None
    for it in range(1, max_iter + 1):
        active = c["status"].copy()
        same = prev_active is not None and np.array_equal(active, prev_active)
        prev_active = active
        if same and np.max(np.abs(rf)) < tol * scale:
            return q[:-1].reshape(-1, 3).copy(), float(q[-1]), c, it
        Kc = contact_tangent(model, c, psi, mu, n_dof)
        Ks = tangent(q) if tangent is not None else Kff
        J = static_scale * (Ks + Kc[free][:, free])
        if diag is not None:
            import scipy.sparse as sp

            J = J + sp.diags(diag)
        dq = solver.solve(J, -rf)
        # backtracking line search on the residual norm (the penalty contact is only
        # piecewise smooth: a full step can flip the active set back and forth)
        step = 1.0
        for _ in range(8):
            q_try = q.copy()
            q_try[free] += step * dq
            rf_try, c_try = residual(q_try)
            n_try = np.linalg.norm(rf_try)
            if _DEBUG: print("   ls", step, c_try["potential"] - c["potential"], float(rf @ dq), n_try, norm)
            if energy_search:
                ok = c_try["potential"] <= c["potential"] + 1e-4 * step * float(rf @ dq)
            else:
                ok = n_try < norm
            if ok or step < 0.01:
                break
            step *= 0.5
        if _DEBUG:
            print(it, step, np.max(np.abs(rf_try)), int((c_try["status"] > 0).sum()), q_try[-1])
        q, rf, c, norm = q_try, rf_try, c_try, n_try
    raise ConvergenceError(f"Newton did not converge in {max_iter} iterations "
                           f"(residual {np.max(np.abs(rf)):.3g} N, load {load:.4g} N)")
