"""Lane-stepped integration: a block of cases advances together so that the law's
transcendental functions run as SIMD instructions across cases.

The generic integrator (``lgw.sim.integrate``) flies one case at a time; its right-hand side
calls the law for each axis, and the law's powers |s|^q = exp(q ln|s|) are C-library calls,
one value at a time.  Here NL cases ("lanes") are stepped in lockstep: at every stage all
lanes' law inputs are gathered, the law is evaluated for all lanes and axes in one loop that
LLVM vectorises (the same generated law with exp / log bound to ``lgw.sim.vmath``), and then
the system's own right-hand side runs per lane, unchanged, with a ``law`` that returns the
lane result it was given (it checks that its inputs are the ones the lane pass used, and
evaluates the scalar law itself when they are not: results never depend on the lane pass
guessing the inputs right, only the speed does).

Stepping, per lane, is the generic integrator's (``integrate.case``): RK4 with the fixed step
dt, or Dormand-Prince 5(4) with each lane's own step size, error control and PI controller
(a lane whose attempt is rejected retries a smaller step in the next round while the others
step on).  Every round each running lane makes one step attempt: RK4 and dopri5 alike make
the same number of right-hand-side calls per attempt in every lane, so the lanes stay in
lockstep without waiting.  A lane whose case has ended takes the next case of its block
(``sys_init``, the right-hand side at t = 0, ``sys_start``), so the lanes stay full until the
block runs out of cases.  The hooks (events, metrics, results) are the system's, called per
lane with the same arguments as from ``integrate.case``; a case's result therefore does not
depend on which lane or block flies it, only on the law's arithmetic (``lgw.sim.vmath``:
within 1 ulp of the C library per call).

Not supported here (the caller uses the generic kernel): recording trajectories and sampled
data (ts > 0).

The system supplies, besides the hooks of ``lgw.sim.integrate``:
  NL                            lanes per block;
  lane_pass(Y, yr, Q, W, run)   the law for every running lane at its state Y[l, yr]: writes
                                what its ``law`` will be asked and the results into W;
  lane_q(Q, W)                  the shared values Q as the lanes' right-hand side receives
                                them (the system's ``law`` reads the lane results through
                                them);
  lane_select(W, l)             lane l's right-hand side is next (its ``law`` is to return
                                lane l's results);
  lane_work(Q)                  the scratch arrays W of one block;
  lane_misses(W)                how many law calls did not find their lane result.

Blocks: the parallel kernel cuts a chunk into blocks of at most BLOCK_LANES * NL cases (each
lane flies about BLOCK_LANES cases in turn); at a block's end its lanes run out of cases one
by one (about one case length of BLOCK_LANES with fewer lanes busy: a few per cent), and the
blocks of a chunk (4096 cases: 16 of 256) spread evenly over the threads.
"""

from __future__ import annotations

import inspect

import numba
import numpy as np
from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

BLOCK_LANES = 16  # cases per lane and block of the parallel kernel (module docstring)

# --- compiled helpers ---------------------------------------------------------------------


@intrinsic
def _as_pointer(typingctx, addr):
    """The float64 pointer at integer address addr (LLVM inttoptr)."""
    if not isinstance(addr, types.Integer):
        return None

    def codegen(context, builder, signature, args):
        return builder.inttoptr(args[0], ir.PointerType(ir.DoubleType()))
    return types.CPointer(types.float64)(addr), codegen


@intrinsic
def unowned(typingctx, tup):
    """The tuple with every array in it replaced by a view that holds no reference (a null
    meminfo): the hooks unpack C, Q and R for every lane and step, and numba counts a
    reference for each array unpacked, an atomic add and release that its pruning pass
    leaves in place there (a quarter of a first lane kernel's time).  Valid while the
    caller holds the arrays themselves (all of ``lanes_run``)."""
    if not isinstance(tup, types.BaseTuple):
        return None

    def codegen(context, builder, signature, args):
        (ty,) = signature.args
        val = args[0]
        for k, item_ty in enumerate(ty.types):
            if isinstance(item_ty, types.Array):
                ary = context.make_array(item_ty)(context, builder,
                                                  value=builder.extract_value(val, k))
                ary.meminfo = cgutils.get_null_value(ary.meminfo.type)
                ary.parent = cgutils.get_null_value(ary.parent.type)
                val = builder.insert_value(val, ary._getvalue(), k)
        return val
    return tup(tup), codegen


# Lane ln's rows of the block's state arrays, as the hooks take them (one case's y, K, X,
# S).  numba reference-counts every array it binds to a name or passes (an atomic add and a
# release, which its pruning pass does not remove inside the inlined hooks: a quarter to a
# third of a first lane kernel's time), so the views are made from the arrays' addresses,
# taken once per block: they carry no reference count and are valid while the block's
# arrays live, which is all of ``lanes_run``.
@numba.njit(inline="always", cache=True)
def lane_view2(addr, ln, n1, n2):
    """Row ln of a C-contiguous (NL, n1, n2) float64 array at address addr."""
    return numba.carray(_as_pointer(addr + ln * (n1 * n2 * 8)), (n1, n2))


@numba.njit(inline="always", cache=True)
def lane_view1(addr, ln, n1):
    """Row ln of a C-contiguous (NL, n1) float64 array at address addr."""
    return numba.carray(_as_pointer(addr + ln * (n1 * 8)), n1)


def lanes_run(lo, hi, C, Q, R, O, G):  # noqa: N803  (template)
    """Cases lo..hi-1, NL at a time (template; the hooks are the generated module's).
    Returns the number of law calls that missed their lane result (0 when all is well)."""
    method, dt, nsteps, rtol, atol, hmax, t_max, max_steps, ts, nsub, record = O
    C = unowned(C)  # noqa: N806  (no reference counting in the hooks: ``unowned``)  # noqa: F821
    Q = unowned(Q)  # noqa: N806, F821
    R = unowned(R)  # noqa: N806, F821
    G = unowned(G)  # noqa: N806, F821
    nonfinite, t_end, y_end, nstep_out, steplim = G
    W = lane_work(Q)  # noqa: F821
    QL = unowned(lane_q(Q, W))  # Q as the lanes' sys_rhs receives it  # noqa: F821, N806
    Y = np.ones((NL, 3, NY))  # per lane: y, the stage input, the new node  # noqa: F821
    K = np.zeros((NL, 7, NY))  # noqa: F821
    X = np.zeros((NL, NX))  # noqa: F821
    XL = np.zeros((NL, NX))  # noqa: F821
    S = np.zeros((NL, NS))  # noqa: F821
    cs = np.full(NL, -1, np.int64)  # the case each lane flies (-1: free)  # noqa: F821
    run = np.zeros(NL, np.bool_)  # noqa: F821
    bad = np.zeros(NL, np.bool_)  # noqa: F821
    stalled = np.zeros(NL, np.bool_)  # noqa: F821
    rejected = np.zeros(NL, np.bool_)  # noqa: F821
    t = np.zeros(NL)  # noqa: F821
    h = np.zeros(NL)  # noqa: F821
    t_new = np.zeros(NL)  # noqa: F821
    tst = np.zeros(NL)  # noqa: F821
    h_try = np.zeros(NL)  # noqa: F821
    err_old = np.zeros(NL)  # noqa: F821
    step = np.zeros(NL, np.int64)  # noqa: F821
    attempts = np.zeros(NL, np.int64)  # noqa: F821
    pY = Y.ctypes.data  # noqa: N806  (addresses for the lane views: lane_view2)
    pK = K.ctypes.data  # noqa: N806
    pX = X.ctypes.data  # noqa: N806
    pXL = XL.ctypes.data  # noqa: N806
    pS = S.ctypes.data  # noqa: N806
    nst = 4 if method == 0 else 6
    nxt = lo
    while True:
        # free lanes take the next cases: initial state, y' at t = 0, events at t = 0
        fresh = False
        for ln in range(NL):  # noqa: F821
            run[ln] = False
            if cs[ln] < 0 and nxt < hi:
                cs[ln] = nxt
                nxt += 1
                sys_init(cs[ln], C, Q, lane_view2(pY, ln, 3, NY)[0], lane_view1(pS, ln, NS))  # noqa: F821
                t[ln] = 0.0
                step[ln] = 0
                attempts[ln] = 0
                bad[ln] = False
                stalled[ln] = False
                rejected[ln] = False
                err_old[ln] = 1e-4
                h_try[ln] = min(dt, hmax)
                run[ln] = True
                fresh = True
        if fresh:
            for ln in range(NL):  # noqa: F821
                tst[ln] = 0.0
            _lanes_rhs(tst, Y, 0, K, 0, X, cs, C, Q, QL, W, run)
            for ln in range(NL):  # noqa: F821
                if run[ln]:
                    for j in range(NX):  # noqa: F821
                        XL[ln, j] = X[ln, j]
                    if sys_start(cs[ln], lane_view2(pY, ln, 3, NY)[0], lane_view1(pX, ln, NX),  # noqa: F821
                                 lane_view1(pS, ln, NS), C, Q, R):  # noqa: F821
                        _lane_end(ln, cs, t, Y, bad, stalled, step, S, C, Q, R, G)
        # the lanes that make a step attempt this round, and their step
        nrun = 0
        for ln in range(NL):  # noqa: F821
            run[ln] = False
            if cs[ln] < 0:
                continue
            if method == 0:
                if step[ln] >= nsteps:
                    _lane_end(ln, cs, t, Y, bad, stalled, step, S, C, Q, R, G)
                    continue
                h[ln] = dt
                t_new[ln] = (step[ln] + 1) * dt
            else:
                rem = t_max - t[ln]
                if rem <= 1e-12 * t_max:
                    _lane_end(ln, cs, t, Y, bad, stalled, step, S, C, Q, R, G)
                    continue
                if attempts[ln] >= max_steps:
                    stalled[ln] = True
                    _lane_end(ln, cs, t, Y, bad, stalled, step, S, C, Q, R, G)
                    continue
                hh = h_try[ln] if h_try[ln] < rem * (1.0 - 1e-9) else rem
                h[ln] = hh
                t_new[ln] = t[ln] + hh if hh < rem else t_max
            run[ln] = True
            nrun += 1
        if nrun == 0:
            if nxt >= hi:
                break
            continue
        # the stages and the new node, all running lanes together (integrate.case)
        for stage in range(nst):
            yr = 1
            last = stage == nst - 1
            for ln in range(NL):  # noqa: F821
                if not run[ln]:
                    continue
                hl = h[ln]
                tst[ln] = t[ln] + 0.5 * hl
                if last:
                    for j in range(NY):  # noqa: F821
                        if method == 1:
                            acc = 0.0
                            for q in range(6):
                                acc += DP_B[q] * K[ln, q, j]  # noqa: F821
                            Y[ln, 2, j] = Y[ln, 0, j] + hl * acc
                        else:
                            Y[ln, 2, j] = Y[ln, 0, j] + hl / 6.0 * (
                                K[ln, 0, j] + 2.0 * K[ln, 1, j] + 2.0 * K[ln, 2, j]
                                + K[ln, 3, j])
                        if not math.isfinite(Y[ln, 2, j]):  # noqa: F821
                            bad[ln] = True
                    tst[ln] = t_new[ln]
                elif method == 1:
                    st = stage + 1
                    for j in range(NY):  # noqa: F821
                        acc = 0.0
                        for q in range(st):
                            acc += DP_A[st, q] * K[ln, q, j]  # noqa: F821
                        Y[ln, 1, j] = Y[ln, 0, j] + hl * acc
                    tst[ln] = t[ln] + DP_C[st] * hl  # noqa: F821
                elif stage == 0:
                    for j in range(NY):  # noqa: F821
                        Y[ln, 1, j] = Y[ln, 0, j] + 0.5 * hl * K[ln, 0, j]
                elif stage == 1:
                    for j in range(NY):  # noqa: F821
                        Y[ln, 1, j] = Y[ln, 0, j] + 0.5 * hl * K[ln, 1, j]
                else:
                    for j in range(NY):  # noqa: F821
                        Y[ln, 1, j] = Y[ln, 0, j] + hl * K[ln, 2, j]
                    tst[ln] = t[ln] + hl
                if bad[ln]:
                    run[ln] = False  # a non-finite new node: no right-hand side there
            if last:
                yr = 2
            _lanes_rhs(tst, Y, yr, K, stage + 1, X, cs, C, Q, QL, W, run)
        # each lane: error control, events, acceptance, end of its case
        for ln in range(NL):  # noqa: F821
            if cs[ln] < 0:
                continue
            if bad[ln]:
                _lane_end(ln, cs, t, Y, bad, stalled, step, S, C, Q, R, G)
                continue
            if not run[ln]:
                continue
            hl = h[ln]
            if method == 1:
                attempts[ln] += 1
                errn = 0.0
                for j in range(NY):  # noqa: F821
                    acc = 0.0
                    for q in range(7):
                        acc += DP_E[q] * K[ln, q, j]  # noqa: F821
                    sc = atol + rtol * max(abs(Y[ln, 0, j]), abs(Y[ln, 2, j]))
                    errn += (hl * acc / sc) ** 2
                errn = math.sqrt(errn / NY)  # noqa: F821
                if not errn <= 1.0:  # NaN rejects too
                    h_try[ln] = hl * max(0.2, 0.9 * errn ** -0.2) if errn == errn else 0.2 * hl
                    rejected[ln] = True
                    continue
                fac = 0.9 * max(errn, 1e-10) ** (-0.2 + 0.75 * PI_BETA) * err_old[ln] ** PI_BETA  # noqa: F821
                fac = min(PI_MAXFAC, max(0.2, fac))  # noqa: F821
                if rejected[ln]:
                    fac = min(fac, 1.0)
                rejected[ln] = False
                err_old[ln] = max(errn, 1e-4)
                h_try[ln] = min(hl * fac, hmax)
            Yl = lane_view2(pY, ln, 3, NY)  # noqa: F821, N806
            Kl = lane_view2(pK, ln, 7, NY)  # noqa: F821, N806
            y = Yl[0]
            yn = Yl[2]
            k1 = Kl[0]
            k1n = Kl[nst]
            code, theta = sys_step(cs[ln], t[ln], hl, y, k1, yn, k1n,  # noqa: F821
                                   lane_view1(pXL, ln, NX), lane_view1(pX, ln, NX),  # noqa: F821
                                   lane_view1(pS, ln, NS), C, Q, R)  # noqa: F821
            if code == STOP_INSIDE:  # noqa: F821
                for j in range(NY):  # noqa: F821
                    y[j] = _herm(y[j], k1[j], yn[j], k1n[j], hl, theta)  # noqa: F821
                t[ln] = t[ln] + theta * hl
                _lane_end(ln, cs, t, Y, bad, stalled, step, S, C, Q, R, G)
                continue
            for j in range(NY):  # noqa: F821
                y[j] = yn[j]
                k1[j] = k1n[j]
            for j in range(NX):  # noqa: F821
                XL[ln, j] = X[ln, j]
            t[ln] = t_new[ln]
            step[ln] += 1
            if code == STOP_AT_NODE:  # noqa: F821
                _lane_end(ln, cs, t, Y, bad, stalled, step, S, C, Q, R, G)
    return lane_misses(W)  # noqa: F821


def _lanes_rhs(tst, Y, yr, K, kr, X, cs, C, Q, QL, W, run):  # noqa: N803  (template)
    """y' of every running lane at (tst[l], Y[l, yr]) into K[l, kr]: the lane pass (the law
    for all lanes at once), then the system's right-hand side per lane.  One compiled copy of
    sys_rhs, called from both sites of ``lanes_run`` (an inlined copy per site doubles the
    compile)."""
    lane_pass(Y, yr, Q, W, run)  # noqa: F821
    pY = Y.ctypes.data  # noqa: N806
    pK = K.ctypes.data  # noqa: N806
    pX = X.ctypes.data  # noqa: N806
    for ln in range(NL):  # noqa: F821
        if run[ln]:
            lane_select(W, ln)  # noqa: F821
            sys_rhs(tst[ln], lane_view2(pY, ln, 3, NY), yr, lane_view2(pK, ln, 7, NY), kr,  # noqa: F821
                    lane_view1(pX, ln, NX), cs[ln], C, QL)  # noqa: F821


def _lane_end(ln, cs, t, Y, bad, stalled, step, S, C, Q, R, G):  # noqa: N803  (template)
    """Lane ln's case has ended: its results (as at the end of ``integrate.case``); the lane
    is free."""
    nonfinite, t_end, y_end, nstep_out, steplim = G
    i = cs[ln]
    pY = Y.ctypes.data  # noqa: N806
    pS = S.ctypes.data  # noqa: N806
    sys_finish(i, t[ln], lane_view2(pY, ln, 3, NY)[0], lane_view1(pS, ln, NS), C, Q, R)  # noqa: F821
    nonfinite[i] = bad[ln]
    nstep_out[i] = step[ln]
    steplim[i] = stalled[ln]
    t_end[i] = t[ln]
    for j in range(NY):  # noqa: F821
        y_end[i, j] = Y[ln, 2, j] if bad[ln] else Y[ln, 0, j]
    cs[ln] = -1


def kernel_parallel(C, Q, R, O, G, rec_y, rec_x):  # noqa: N803  (template)
    """All cases of a chunk in contiguous blocks of at most BLOCK_LANES * NL cases, spread
    over the threads (numba.prange); returns the law calls that missed their lane result
    (``lanes_run``).  rec_y, rec_x are not used (no recording here): the generic kernel's
    signature.  (The block count does not ask numba for its thread count: a kernel that does
    cannot be cached.)"""
    n = G[1].shape[0]
    nblk = max(1, -(-n // (BLOCK_LANES * NL)))  # noqa: F821
    miss = np.zeros(nblk, np.int64)
    for b in numba.prange(nblk):
        miss[b] = lanes_run_fn(b * n // nblk, (b + 1) * n // nblk, C, Q, R, O, G)  # noqa: F821
    return miss.sum()


def kernel_serial(C, Q, R, O, G, rec_y, rec_x):  # noqa: N803  (template)
    """All cases of a chunk in one block, on this thread (executors that parallelise over
    chunks themselves)."""
    return lanes_run_fn(0, G[1].shape[0], C, Q, R, O, G)  # noqa: F821


def template_source() -> str:
    """The lane templates as written into a generated module (``lanes_run`` compiled as
    ``lanes_run_fn``)."""
    return "\n\n".join(inspect.getsource(f) for f in (lanes_run, _lanes_rhs, _lane_end,
                                                       kernel_parallel, kernel_serial))


FOOTER = '''
_lanes_rhs = numba.njit(_lanes_rhs, error_model="numpy")
_lane_end = numba.njit(_lane_end, error_model="numpy")
lanes_run_fn = numba.njit(lanes_run, error_model="numpy", cache=True)
kernel_parallel = numba.njit(kernel_parallel, error_model="numpy", parallel=True, cache=True)
kernel_serial = numba.njit(kernel_serial, error_model="numpy", parallel=False, cache=True)
'''


def lanes_module_source(imports: tuple[str, ...], header: str, sizes: dict[str, float],
                        system_source: str) -> str:
    """A lane kernel module: imports, the system's header (its law, the lane law and the lane
    glue), the sizes (NY, NX, NS, NL, ...), the hooks, the lane templates."""
    consts = "\n".join(f"{k} = {v!r}" for k, v in sizes.items())
    return "\n".join(["# generated by lgw.sim.lanes: do not edit (a cache entry)", *imports,
                      "from lgw.sim.lanes import BLOCK_LANES, lane_view1, lane_view2, unowned",
                      "", consts, "",
                      header, "", system_source, "", template_source(), FOOTER])


def lanes_supported(O: tuple) -> bool:  # noqa: N803
    """True if the integration options O (``integrate.integration_tuple``) can be flown in
    lanes: no recording, no sampled data."""
    return not O[-1] and O[8] == 0.0

