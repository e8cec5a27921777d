"""The generic batched integrator: classical RK4 and adaptive Dormand-Prince 5(4) over N cases.

A system supplies a compiled vector field and its own event and metric hooks; this module
supplies the stepping (RK4 with a fixed step, or Dormand-Prince 5(4) with scipy RK45's error
control, a PI step controller and a step limit), non-finite detection, the trajectory record,
the cubic Hermite helpers for locating events inside a step, and the parallel loop over cases.
The seed 000 client is ``lgw.sim.mars.kernel``.

How a kernel is assembled.  numba resolves global names when it compiles, and ``cache=True``
only works for functions defined in a real source file whose globals are importable (a closure
over a compiled law gets a fresh identity in every process, so its cache never hits).  A kernel
is therefore a generated module (``lgw.sim.kernel_cache``): the system's generated law, then the
system's hook functions and then ``case`` / ``kernel`` below, copied as source, so that in that
module the names the templates use resolve to that system's hooks.  The functions here marked
"template" are plain Python (not compiled in this module); everything else is compiled once.

The hook contract (names in the generated module; ``i`` is the case, ``C`` the tuple of per-case
input arrays (first axis = case), ``Q`` the tuple of shared values, ``R`` the tuple of per-case
result arrays):
  NY, NX, NS                      state size, auxiliary outputs of the vector field, trackers;
  sys_init(i, C, Q, y, S)         the initial state into y (NY), trackers S (NS) initialised;
  sys_rhs(t, Y, yr, K, kr, X, i, C, Q)
                                  y' at (t, Y[yr]) into K[kr]; auxiliary outputs (command,
                                  sliding variables, ...) into X (NX).  Called at one site
                                  (inlined): the stages, and last the new node;
  sys_start(i, y, X, S, C, Q, R)  events at t = 0 (X: aux at y); returns True to stop at once;
  sys_step(i, t, h, y, k1, yn, k1n, XL, X, S, C, Q, R) -> (code, theta)
                                  events and metrics of one accepted step from (t, y, y' = k1)
                                  to (t + h, yn, k1n); XL the aux at y, X at yn.  code CONTINUE,
                                  STOP_AT_NODE (accept the node, then stop: e.g. landing), or
                                  STOP_INSIDE (stop at t + theta h on the Hermite interpolant,
                                  the node is not accepted: e.g. dry mass);
  sys_finish(i, t, y, S, C, Q, R) write the case's results;
  sys_sample(i, k, t, y, S, C, Q, R) -> stop
                                  optional (sampled-data systems, below; a no-op stub is
                                  supplied when the system does not define it).
The integrator itself writes the generic outcomes G = (nonfinite, t_end, y_end, steps,
step_limit) and, when recording, y and X at every accepted node.

Integration options O = (method, dt, nsteps, rtol, atol, max_step, t_max, max_steps, ts, nsub,
record), built by ``integration_tuple`` from ``lgw.sim.options.IntegrationOptions``.

Sampled data with a zero-order hold (``integration_tuple(..., sample=(ts, nsub))``, ts > 0; off
when ts = 0, the default, which leaves every existing client's arithmetic as it was).  A
digital controller reads the state at the sample instants t_k = k ts and holds its output
until t_k+1.  The held output is part of the state: components of y whose derivative sys_rhs
sets to 0 (so RK4 and dopri5 keep them exactly constant between samples).  At t = 0 (before
sys_rhs and sys_start) and at every t_k reached, the integrator calls sys_sample(i, k, t_k, y,
...), which evaluates the controller from y and writes the new held values into y (it may also
record per-sample outputs into R, and return True to stop the case at t_k); then y' at t_k is
recomputed.  Between samples the plant is integrated by RK4 with exactly ``nsub`` steps of
ts / nsub per sample (node times k ts + j ts / nsub), or by dopri5 with its steps clipped so
that none crosses a sample instant (a step that would reach past t_k ends exactly at t_k, so
the control jump is never inside a step and the error control stays meaningful).  The
horizon is K = ceil(t_max / ts) samples; t_max should be a multiple of ts.  Events (sys_step)
work as without sampling.  Note: dopri5's RMS error norm averages over all NY components, the
held ones included (their error is 0).
"""

from __future__ import annotations

import ast
import copy
import inspect
import math
from collections.abc import Iterable
from concurrent.futures import ThreadPoolExecutor

import numba
import numpy as np
from lgw.sim.options import IntegrationOptions

METHOD_CODE = {"rk4": 0, "dopri5": 1}
# sys_step's return codes
CONTINUE = 0
STOP_AT_NODE = 1
STOP_INSIDE = 2

# dopri5 step control: PI controller with Hairer & Wanner's DOPRI5 beta (Solving ODEs I,
# II.4), growth at most 10x per step (as scipy's RK45) and none right after a rejection.
# Measured on seed 000 Table II: beta 0, 0.04, 0.08 take 40, 39, 38 attempts per case at
# rtol 1e-4 (~13 of them rejected, at the non-smooth arrivals of s1, s2 at 0).
PI_BETA = 0.04
PI_MAXFAC = 10.0
# Bisection steps for an event inside a step: 2^-60 of the step, below double precision.
BISECT_ITERS = 60

# Dormand & Prince (1980) 5(4) tableau, as in scipy's RK45 (Hairer, Norsett & Wanner, Solving
# ODEs I, Table 5.2): stage nodes C, coefficients A, 5th-order weights B (the 7th stage is the
# FSAL derivative at the new node), error weights E = B - B*.
DP_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
DP_A = np.array([
    [0, 0, 0, 0, 0, 0],
    [1 / 5, 0, 0, 0, 0, 0],
    [3 / 40, 9 / 40, 0, 0, 0, 0],
    [44 / 45, -56 / 15, 32 / 9, 0, 0, 0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0, 0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0]])
DP_B = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0])
DP_E = np.array([71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])


# --- compiled helpers (shared by every system) --------------------------------------------

@numba.njit(error_model="numpy", cache=True)
def _herm(p0: float, d0: float, p1: float, d1: float, h: float, th: float) -> float:
    """Cubic Hermite interpolant at th in [0, 1] of a step of length h with values p0, p1 and
    derivatives d0, d1 at its ends (O(h^4) accurate, like RK4 itself)."""
    t2 = th * th
    t3 = t2 * th
    return ((2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + th) * h * d0
            + (-2 * t3 + 3 * t2) * p1 + (t3 - t2) * h * d1)


@numba.njit(error_model="numpy", cache=True)
def _herm_min(p0: float, d0: float, p1: float, d1: float, h: float, b: float) -> float:
    """Minimum over th in [0, b] of the cubic Hermite interpolant (``_herm``): the end points
    and the roots of its derivative, a quadratic in th."""
    lo = min(p0, _herm(p0, d0, p1, d1, h, b))
    qa = 6.0 * p0 + 3.0 * h * d0 - 6.0 * p1 + 3.0 * h * d1
    qb = -6.0 * p0 - 4.0 * h * d0 + 6.0 * p1 - 2.0 * h * d1
    qc = h * d0
    if qa == 0.0:
        if qb != 0.0:
            th = -qc / qb
            if 0.0 < th < b:
                lo = min(lo, _herm(p0, d0, p1, d1, h, th))
        return lo
    disc = qb * qb - 4.0 * qa * qc
    if disc < 0.0:
        return lo
    sq = math.sqrt(disc)
    for th in ((-qb - sq) / (2.0 * qa), (-qb + sq) / (2.0 * qa)):
        if 0.0 < th < b:
            lo = min(lo, _herm(p0, d0, p1, d1, h, th))
    return lo


@numba.njit(error_model="numpy", cache=True)
def _band(sa: float, sb: float, eps: float) -> tuple[float, float]:
    """[lo, hi] in [0, 1] where the linear interpolant of s has |s| <= eps (lo > hi: empty)."""
    ds = sb - sa
    if ds == 0.0:
        return (0.0, 1.0) if abs(sa) <= eps else (1.0, 0.0)
    a = (-eps - sa) / ds
    b = (eps - sa) / ds
    lo = min(a, b)
    hi = max(a, b)
    return max(lo, 0.0), min(hi, 1.0)


@numba.njit(error_model="numpy", cache=True)
def _herm_first_below(p0: float, d0: float, p1: float, d1: float, h: float,
                      level: float) -> float:
    """Bisection for the first th in [0, 1] with Hermite(th) <= level, given p1 <= level
    (the crossing of a monotone quantity such as the mass reaching the dry mass)."""
    a = 0.0
    b = 1.0
    for _ in range(BISECT_ITERS):
        mid = 0.5 * (a + b)
        if _herm(p0, d0, p1, d1, h, mid) <= level:
            b = mid
        else:
            a = mid
    return b


@numba.njit(error_model="numpy", cache=True)
def _herm_first_under(p0: float, d0: float, p1: float, d1: float, h: float, level: float,
                      a: float, b: float) -> float:
    """The first th in [a, b] (within [0, 1]) where the cubic Hermite interpolant (``_herm``)
    is strictly below ``level``, or 2.0 if there is none: the first crossing of a surface by a
    component that need not be monotone over the step (a dip below the ground and back that
    lies between the nodes).  The interval is cut at the roots of the cubic's derivative into
    monotone pieces, the first piece that ends below the level is bisected (BISECT_ITERS);
    the result is the bisection's upper end, a point where the interpolant is below the level.
    """
    if b < a:
        return 2.0
    if _herm(p0, d0, p1, d1, h, a) < level:
        return a
    # derivative: qa th^2 + qb th + qc (as _herm_min)
    qa = 6.0 * p0 + 3.0 * h * d0 - 6.0 * p1 + 3.0 * h * d1
    qb = -6.0 * p0 - 4.0 * h * d0 + 6.0 * p1 - 2.0 * h * d1
    qc = h * d0
    c1 = 2.0
    c2 = 2.0
    if qa == 0.0:
        if qb != 0.0:
            c1 = -qc / qb
    else:
        disc = qb * qb - 4.0 * qa * qc
        if disc >= 0.0:
            sq = math.sqrt(disc)
            r1 = (-qb - sq) / (2.0 * qa)
            r2 = (-qb + sq) / (2.0 * qa)
            c1 = min(r1, r2)
            c2 = max(r1, r2)
    lo = a
    for k in range(3):
        hi = c1 if k == 0 else (c2 if k == 1 else b)
        if not (a < hi < b) and k < 2:
            continue
        if hi <= lo:
            continue
        if _herm(p0, d0, p1, d1, h, hi) < level:
            # the interpolant is monotone on [lo, hi], >= level at lo, < level at hi
            x0 = lo
            x1 = hi
            for _ in range(BISECT_ITERS):
                mid = 0.5 * (x0 + x1)
                if _herm(p0, d0, p1, d1, h, mid) < level:
                    x1 = mid
                else:
                    x0 = mid
            return x1
        lo = hi
    return 2.0


# --- templates (copied into each generated kernel module) --------------------------------

def kernel(C, Q, R, O, G, rec_y, rec_x):  # noqa: N803  (template)
    """Every case of a chunk, one after the other (template; the hooks are the generated
    module's).  Parallelism is over pieces of a chunk, in threads (``run_chunk``): the kernel
    is compiled once, serial and ``nogil``, for one loop-index type (numba's parfor lowering
    compiled the per-case code a second time for an unsigned index, and its gufunc linked and
    re-optimised the whole integrator again: about half of a cold build)."""
    method, dt, nsteps, rtol, atol, hmax, t_max, max_steps, ts, nsub, record = O
    nonfinite, t_end, y_end, nstep_out, steplim = G
    for i in range(G[1].shape[0]):
        Y = np.empty((3, NY))  # y, the stage input, the new node  # noqa: F821
        # RK4: k1..k4 and y' at the new node (row 4); dopri5: k1..k6 and k7 = y' at the new node
        K = np.empty((7, NY))  # noqa: F821
        nst = 4 if method == 0 else 6  # rhs calls per step; the last one is at the new node
        y, yt, yn = Y[0], Y[1], Y[2]
        k1, k2, k3, k4, k1n = K[0], K[1], K[2], K[3], K[nst]
        X = np.empty(NX)  # auxiliary outputs of the latest rhs call  # noqa: F821
        XL = np.empty(NX)  # ... at the current node  # noqa: F821
        S = np.empty(NS)  # the system's trackers  # noqa: F821
        sys_init(i, C, Q, y, S)  # noqa: F821
        ksamp = 0  # sampled data: the index of the latest sample
        # sampled data: the controller is due at the top of the loop (sample 0 at t = 0, then
        # each sample instant reached): one call site, so one inlined copy of sys_sample
        sample_due = ts > 0.0
        stop0 = False
        t = 0.0
        step = 0  # accepted steps
        attempts = 0  # dopri5: accepted + rejected steps
        stalled = False
        rejected = False
        bad = False
        err_old = 1e-4
        h_try = min(dt, hmax)
        done = False
        started = False
        # y' and the auxiliary outputs at the node (t, y) are due: at t = 0, and at a sample
        # instant once the controller has set its new output
        at_node = True
        h = 0.0
        t_new = 0.0
        on_sample = False  # sampled data: this step ends at a sample instant
        while True:
            if sample_due:
                sample_due = False
                stop = sys_sample(i, ksamp, t, y, S, C, Q, R)  # noqa: F821
                if started:
                    done = stop
                else:
                    stop0 = stop
            if not at_node:
                if done:
                    break
                on_sample = False
                if method == 0:
                    if step >= nsteps:
                        break
                    h = dt
                    if ts > 0.0:
                        sub = step % nsub
                        on_sample = sub == nsub - 1
                        t_new = (ksamp + 1) * ts if on_sample else ksamp * ts + (sub + 1) * dt
                    else:
                        t_new = (step + 1) * dt
                else:
                    rem = t_max - t
                    if rem <= 1e-12 * t_max:
                        break
                    if attempts >= max_steps:
                        stalled = True
                        break
                    if ts > 0.0:
                        t_smp = min((ksamp + 1) * ts, t_max)
                        rem = t_smp - t
                        on_sample = not h_try < rem * (1.0 - 1e-9)
                        h = rem if on_sample else h_try
                        t_new = t_smp if on_sample else t + h
                    else:
                        h = h_try if h_try < rem * (1.0 - 1e-9) else rem
                        t_new = t + h if h < rem else t_max
            # The node (stage -1: y' at (t, y) into K[0]) or the RK4 / Dormand-Prince stages of
            # a step.  All of them, and the new node (whose derivative is the next step's k1),
            # share one rhs call site: rhs is inlined, and its cost in numba's front end and in
            # LLVM is per copy (four copies made the compile several times slower)
            finite = True
            for stage in range(-1 if at_node else 0, 0 if at_node else nst):
                yr = 1
                tst = t + 0.5 * h
                if stage < 0:
                    yr = 0
                    tst = t
                elif stage == nst - 1:
                    # the new node (its derivative is the next step's k1)
                    for j in range(NY):  # noqa: F821
                        if method == 1:
                            acc = 0.0
                            for q in range(6):
                                acc += DP_B[q] * K[q, j]
                            yn[j] = y[j] + h * acc
                        else:
                            yn[j] = y[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
                        if not math.isfinite(yn[j]):
                            finite = False
                    if not finite:
                        break
                    yr = 2
                    tst = t_new
                elif method == 1:
                    st = stage + 1
                    for j in range(NY):  # noqa: F821
                        acc = 0.0
                        for q in range(st):
                            acc += DP_A[st, q] * K[q, j]
                        yt[j] = y[j] + h * acc
                    tst = t + DP_C[st] * h
                elif stage == 0:
                    for j in range(NY):  # noqa: F821
                        yt[j] = y[j] + 0.5 * h * k1[j]
                elif stage == 1:
                    for j in range(NY):  # noqa: F821
                        yt[j] = y[j] + 0.5 * h * k2[j]
                else:
                    for j in range(NY):  # noqa: F821
                        yt[j] = y[j] + h * k3[j]
                    tst = t + h
                sys_rhs(tst, Y, yr, K, stage + 1, X, i, C, Q)  # noqa: F821
            if at_node:
                at_node = False
                if not started:  # t = 0
                    started = True
                    done = sys_start(i, y, X, S, C, Q, R)  # noqa: F821
                    if stop0:
                        done = True
            else:
                if not finite:
                    bad = True
                    break
                if method == 1:
                    # error control as in scipy's RK45 (Hairer, Norsett & Wanner II.4): RMS of
                    # h E.K / (atol + rtol max(|y|, |y_new|)); reject above 1, safety 0.9
                    attempts += 1
                    errn = 0.0
                    for j in range(NY):  # noqa: F821
                        acc = 0.0
                        for q in range(7):
                            acc += DP_E[q] * K[q, j]
                        sc = atol + rtol * max(abs(y[j]), abs(yn[j]))
                        errn += (h * acc / sc) ** 2
                    errn = math.sqrt(errn / NY)  # noqa: F821
                    if not errn <= 1.0:  # NaN rejects too
                        h_try = h * max(0.2, 0.9 * errn ** -0.2) if errn == errn else 0.2 * h
                        rejected = True
                        continue
                    # PI control (Hairer & Wanner's DOPRI5: beta = 0.04); no growth right
                    # after a rejection (as scipy's RK45)
                    fac = 0.9 * max(errn, 1e-10) ** (-0.2 + 0.75 * PI_BETA) * err_old ** PI_BETA
                    fac = min(PI_MAXFAC, max(0.2, fac))
                    if rejected:
                        fac = min(fac, 1.0)
                    rejected = False
                    err_old = max(errn, 1e-4)
                    h_try = min(h * fac, hmax)
                code, theta = sys_step(i, t, h, y, k1, yn, k1n, XL, X, S, C, Q, R)  # noqa: F821
                if code == STOP_INSIDE:
                    for j in range(NY):  # noqa: F821
                        y[j] = _herm(y[j], k1[j], yn[j], k1n[j], h, theta)
                    t = t + theta * h
                    break
                for j in range(NY):  # noqa: F821
                    y[j] = yn[j]
                    k1[j] = k1n[j]
                t = t_new
                step += 1
                if on_sample and code != STOP_AT_NODE:
                    # sampled data: the controller reads y(t_k) and holds its new output (at the
                    # top of the loop); then y' at t_k with it, and the record of the node (the
                    # next pass, at_node)
                    ksamp += 1
                    sample_due = True
                    at_node = True
                    continue
                if code == STOP_AT_NODE:
                    done = True
            # the node (t = 0, a sample instant, or the step's new node): its auxiliary
            # outputs, and its record
            for j in range(NX):  # noqa: F821
                XL[j] = X[j]
            if record:
                for j in range(NY):  # noqa: F821
                    rec_y[i, step, j] = y[j]
                for j in range(NX):  # noqa: F821
                    rec_x[i, step, j] = XL[j]
        sys_finish(i, t, y, S, C, Q, R)  # noqa: F821
        nonfinite[i] = bad
        nstep_out[i] = step
        steplim[i] = stalled
        t_end[i] = t
        for j in range(NY):  # noqa: F821
            y_end[i, j] = yn[j] if bad else y[j]


def template_source(system_source: str | None = None) -> str:
    """The source of the template, as written into each generated kernel module (compiled
    there as ``kernel``, ``KERNEL_FOOTER``), with the hooks of ``INLINED_HOOKS`` defined in
    ``system_source`` written into it (``inline_source``) where that is possible."""
    src = inspect.getsource(kernel)
    return src if system_source is None else inline_source(src, system_source, INLINED_HOOKS)


def _bound_and_read(fn: ast.FunctionDef) -> tuple[set[str], set[str]]:
    """(the names a function binds: its parameters and every name it assigns; the names it
    reads and never binds: its globals)."""
    bound = {a.arg for a in fn.args.args}
    read = set()
    for node in ast.walk(fn):
        if isinstance(node, ast.Name):
            (bound if isinstance(node.ctx, ast.Store | ast.Del) else read).add(node.id)
    return bound, read - bound


def _inlinable(fn: ast.FunctionDef) -> bool:
    """A hook that can be written into the template: positional parameters only, no nested
    function, lambda, comprehension, global, yield, try or with, and a last statement that
    returns or a body with no return at all (every path then leaves with a value, or none
    does)."""
    a = fn.args
    if a.vararg or a.kwarg or a.kwonlyargs or a.posonlyargs or a.defaults:
        return False
    banned = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ListComp, ast.SetComp,
              ast.DictComp, ast.GeneratorExp, ast.Global, ast.Nonlocal, ast.Yield,
              ast.YieldFrom, ast.ClassDef, ast.Try, ast.With)
    if any(isinstance(n, banned) for b in fn.body for n in ast.walk(b)):
        return False
    returns = [n for n in ast.walk(fn) if isinstance(n, ast.Return)]
    return not returns or isinstance(fn.body[-1], ast.Return)


class _Rename(ast.NodeTransformer):
    def __init__(self, names: set[str], prefix: str) -> None:
        self.names = names
        self.prefix = prefix

    def visit_Name(self, node: ast.Name) -> ast.Name:  # noqa: N802  (ast's visitor name)
        if node.id in self.names:
            node.id = self.prefix + node.id
        return node


class _Returns(ast.NodeTransformer):
    """``return v`` -> ``target = v; break`` out of the loop that wraps the hook's body; a
    return inside one of the hook's own loops also sets ``flag``, tested after each loop that
    holds one (``if flag: break``), out to the wrapping loop."""

    def __init__(self, target: ast.expr | None, flag: str) -> None:
        self.target = target
        self.flag = flag

    def visit_Return(self, node: ast.Return) -> list[ast.stmt]:  # noqa: N802
        out: list[ast.stmt] = []
        if self.target is not None and node.value is not None:
            out.append(ast.Assign(targets=[copy.deepcopy(self.target)], value=node.value))
        return [*out, ast.Assign(targets=[ast.Name(self.flag, ast.Store())],
                                 value=ast.Constant(True)), ast.Break()]

    def _loop(self, node: ast.For | ast.While) -> ast.stmt | list[ast.stmt]:
        inner = any(isinstance(n, ast.Return) for n in ast.walk(node))
        self.generic_visit(node)
        if not inner:
            return node
        return [node, ast.If(test=ast.Name(self.flag, ast.Load()), body=[ast.Break()],
                             orelse=[])]

    visit_For = _loop  # noqa: N815
    visit_While = _loop  # noqa: N815


def inline_source(template: str, system_source: str, hooks: Iterable[str]) -> str:
    """The template's source with each call statement of a hook in ``hooks`` (``hook(...)``
    or ``target = hook(...)``) replaced by the hook's body, as written in ``system_source``:
    its parameters and locals renamed ``_<hook>_<name>`` and bound to the call's arguments,
    each ``return v`` an assignment of the target and a break out of a loop run once (out of
    the hook's own loops first, by a flag ``_<hook>_returned``).

    Why: numba's ``inline='always'`` translates the callee again at each call site and then
    copies its IR block by block, each copy carrying the callee's whole scope (cost blocks x
    variables); for seed 000's vector field and step hook that was a fifth of the kernel's
    build.  Written into the source, the body is translated once with the kernel.  The
    arithmetic is the same statements in the same order.  A hook that cannot be written in
    (``_inlinable``), or whose globals a template local would shadow, stays a call (numba
    inlines it, ``hook_jit``)."""
    tree = ast.parse(template)
    kfn = tree.body[0]
    defs = {n.name: n for n in ast.parse(system_source).body if isinstance(n, ast.FunctionDef)}
    k_bound, k_read = _bound_and_read(kfn)
    todo = {}
    for name in hooks:
        fn = defs.get(name)
        if fn is None or not _inlinable(fn):
            continue
        bound, read = _bound_and_read(fn)
        prefix = f"_{name}_"
        if "returned" in bound or read & k_bound or any(prefix + b in k_bound | k_read
                                                        for b in (*bound, "returned")):
            continue
        todo[name] = (fn, bound, prefix)

    def expand(stmt: ast.stmt) -> list[ast.stmt] | None:
        call = stmt.value if isinstance(stmt, ast.Expr | ast.Assign) else None
        if not (isinstance(call, ast.Call) and isinstance(call.func, ast.Name)
                and call.func.id in todo) or call.keywords:
            return None
        fn, bound, prefix = todo[call.func.id]
        params = [a.arg for a in fn.args.args]
        if len(call.args) != len(params) or any(isinstance(a, ast.Starred) for a in call.args):
            return None
        target = None
        if isinstance(stmt, ast.Assign):
            if len(stmt.targets) != 1:
                return None
            target = stmt.targets[0]
        body = copy.deepcopy(fn.body)
        if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
            body = body[1:]  # the docstring
        has_return = any(isinstance(n, ast.Return) for b in body for n in ast.walk(b))
        if target is not None and not has_return:
            return None
        mod = ast.Module(body=body, type_ignores=[])
        mod = _Rename(bound, prefix).visit(mod)
        flag = prefix + "returned"
        mod = _Returns(target, flag).visit(mod)
        out: list[ast.stmt] = [ast.Assign(targets=[ast.Name(prefix + p, ast.Store())], value=a)
                               for p, a in zip(params, call.args, strict=True)]
        if has_return:
            out += [ast.Assign(targets=[ast.Name(flag, ast.Store())], value=ast.Constant(False)),
                    ast.While(test=ast.Constant(True), body=mod.body, orelse=[])]
        else:
            out += mod.body or [ast.Pass()]
        return out

    def walk(stmts: list[ast.stmt]) -> list[ast.stmt]:
        new = []
        for st in stmts:
            rep = expand(st)
            if rep is not None:
                new += rep
                continue
            for field in ("body", "orelse"):
                if isinstance(getattr(st, field, None), list):
                    setattr(st, field, walk(getattr(st, field)))
            new.append(st)
        return new

    renamed = {prefix + b for _, bound, prefix in todo.values() for b in (*bound, "returned")}
    if not todo or any(_bound_and_read(fn)[1] & renamed for fn, _, _ in todo.values()):
        return template  # (a hook reading a global named like another's renamed local)
    kfn.body = walk(kfn.body)
    return ast.unparse(ast.fix_missing_locations(tree)) + "\n"


KERNEL_IMPORTS = (
    "import math",
    "import numba",
    "import numpy as np",
    "from lgw.sim.integrate import (CONTINUE, DP_A, DP_B, DP_C, DP_E, PI_BETA, PI_MAXFAC,",
    "    STOP_AT_NODE, STOP_INSIDE, _band, _herm, _herm_first_below, _herm_first_under,",
    "    _herm_min)",
)

# numba builds, besides a function's own code, a CPython wrapper (to call it from Python) and a
# C wrapper (to call it through a pointer) for every function it compiles, and optimises and
# caches both.  A function that only compiled code calls (a hook run once per case, a helper of a
# generated module, a part of a generated law) needs neither: without them a cold mars build
# takes a fifth less CPU (docs/sim.md).  numba does not check the flag: calling such a function
# from Python crashes the interpreter, so it is given only to generated names that nothing in
# Python calls (``tests/test_warmup.py`` checks which).  The kernel keeps its CPython wrapper.
CALLEE_ONLY = "no_cpython_wrapper=True, no_cfunc_wrapper=True"

KERNEL_FOOTER = '''
kernel = numba.njit(kernel, error_model="numpy", nogil=True, cache=True, no_cfunc_wrapper=True)
'''

# The hooks numba inlines into the kernel (its IR): those of every stage, step and sample.  As a
# call, the vector field cost ~25 % of seed 000's run speed (the law's parameter-only terms are
# no longer hoisted out of the step loop), and the step and sample hooks 7-48 % of seed 001's
# and 002's (each call passes and unpacks the tuples C, Q, R: tens of arrays, reference counts
# on each).  The hooks run once per case (init, start, finish) are compiled as functions of
# their own: numba's front end is superlinear in a function's size, and they are a third of it.
# Small scalar helpers (``_herm``, ``_band``, ...) are not inlined by numba: each numba inline
# re-translates the helper and grows the caller's IR (seed 000's step hook calls ``_herm`` at a
# dozen sites: a third of the kernel's front end); as calls of float arguments they are
# compiled once, cached, and inlined by LLVM instead, with the same arithmetic (docs/sim.md).
INLINED_HOOKS = ("sys_rhs", "sys_step", "sys_sample")


def callee_source(functions: Iterable[tuple[str, str]]) -> list[str]:
    """The lines of a generated module defining functions [(name, source)] that only its
    kernel calls (a system's generated laws and plant terms), each cached and compiled
    without wrappers (``CALLEE_ONLY``), for every system alike."""
    body = []
    for name, src in functions:
        body += [src, f"{name} = numba.njit({name}, cache=True, error_model='numpy', "
                      f"{CALLEE_ONLY})", ""]
    return body


def hook_jit(names: Iterable[str], cache: bool = False,
             inline: Iterable[str] = ()) -> list[str]:
    """The lines compiling a system's hooks in its generated module (``INLINED_HOOKS`` and
    the system's helpers named in ``inline`` inlined, the others plain functions), for every
    system alike.  cache=True for hooks in a module of their own that several kernels share
    (``hooks_module_source``)."""
    opts = ", cache=True" if cache else ""
    inl = set(INLINED_HOOKS) | set(inline)
    return [f"{n} = numba.njit({n}, error_model='numpy'{opts}"
            + (", inline='always')" if n in inl else f", {CALLEE_ONLY})") for n in names]


def hooks_text(hooks: Iterable, helpers: Iterable = (), *, consts: dict | None = None,
               imports: Iterable[str] = (), inline: Iterable = (), called: Iterable = (),
               cache: bool = False) -> str:
    """A system's hooks as written into a generated module, for every system alike: the
    ``imports`` lines, the constants (tracker slots, codes: ``NAME = value``), the source of
    each helper and hook, then their compilation.  A helper ``h`` is compiled as ``h_fn``
    (cached; inlined by numba if in ``inline``) and, if also in ``called``, as ``h_call`` (a
    plain call: for a hook run once per case that need not copy an inlined helper again); the
    hooks by ``hook_jit`` (cached if ``cache``: a module of hooks that several kernels share)."""
    helpers = tuple(helpers)
    hooks = tuple(hooks)
    inl = set(inline)

    def jit(f, suffix: str, inlined: bool) -> str:
        return (f"{f.__name__}{suffix} = numba.njit({f.__name__}, error_model='numpy', "
                "cache=True" + (", inline='always')" if inlined else f", {CALLEE_ONLY})"))

    return "\n".join([*imports, "", *(f"{k} = {v!r}" for k, v in (consts or {}).items()), "",
                      *(inspect.getsource(f) + "\n" for f in helpers + hooks),
                      *(jit(f, "_fn", f in inl) for f in helpers),
                      *(jit(f, "_call", False) for f in called),
                      *hook_jit((f.__name__ for f in hooks), cache)])


SAMPLE_STUB = '''
def sys_sample(i, k, t, y, S, C, Q, R):  # noqa: N803  (no sampled-data controller)
    return False


sys_sample = numba.njit(sys_sample, inline="always")
'''


def kernel_module_source(header: str, system_source: str, sizes: dict[str, int]) -> str:
    """A kernel module: the system's header (its generated law), the sizes NY, NX, NS, the
    system's hooks (with a no-op ``sys_sample`` when the system has none), the integrator
    templates and their compilation."""
    consts = "\n".join(f"{k} = {int(v)}" for k, v in sizes.items())
    stub = "" if "def sys_sample(" in system_source else SAMPLE_STUB
    return "\n".join(["# generated by lgw.sim.integrate: do not edit (a cache entry)",
                      *KERNEL_IMPORTS, "", header, "", consts, "", system_source, stub, "",
                      template_source(system_source + stub), KERNEL_FOOTER])


def hooks_module_source(system_source: str, sizes: dict[str, int]) -> str:
    """A module of hooks that do not depend on what varies between a system's kernels (seed
    000's law): compiled once, cached, and imported by each of its kernel modules, so that a
    further kernel compiles only what differs (``lgw.sim.mars.kernel``)."""
    consts = "\n".join(f"{k} = {int(v)}" for k, v in sizes.items())
    return "\n".join(["# generated by lgw.sim.integrate: do not edit (a cache entry)",
                      *KERNEL_IMPORTS, "", consts, "", system_source, ""])


def integration_tuple(opt: IntegrationOptions, t_max: float,
                      sample: tuple[float, int] | None = None) -> tuple:
    """The kernel's O tuple for the options and horizon t_max (s).

    sample = (ts, nsub): sampled data with a zero-order hold at ts (s) (module docstring);
    K = ceil(t_max / ts) samples, the horizon K ts.  RK4 then steps ts / nsub (``opt.dt`` is
    not used; dopri5 starts with min(opt.dt, ts)), and nsteps = K nsub.  None: no sampling."""
    if sample is None:
        nsteps = int(math.ceil(t_max / opt.dt - 1e-9))
        return (METHOD_CODE[opt.method], float(opt.dt), nsteps, float(opt.rtol),
                float(opt.atol), float(opt.max_step), float(t_max), int(opt.max_steps), 0.0, 1,
                bool(opt.record))
    ts, nsub = float(sample[0]), sample[1]
    if not (math.isfinite(ts) and ts > 0):
        raise ValueError(f"sample time must be finite and > 0, got {ts!r}")
    if isinstance(nsub, bool) or not isinstance(nsub, int | np.integer) or nsub < 1:
        raise ValueError(f"substeps per sample must be an integer >= 1, got {nsub!r}")
    k = int(math.ceil(t_max / ts - 1e-9))
    dt = ts / nsub if opt.method == "rk4" else min(float(opt.dt), ts)
    return (METHOD_CODE[opt.method], dt, k * int(nsub), float(opt.rtol), float(opt.atol),
            float(opt.max_step), k * ts, int(opt.max_steps), ts, int(nsub), bool(opt.record))


def kernel_args(args: tuple) -> tuple:
    """The kernel's input tuple (C or Q) with every array C-contiguous and writable (a copy
    only where one is not: a read-only view such as ``np.broadcast_to`` gives).  numba types
    read-only and non-contiguous arrays apart, and each new type is another full build of
    the kernel (a single Section 5 case of seed 001 passed read-only gains, a campaign
    writable ones: two builds)."""
    return tuple(np.array(a, order="C") if isinstance(a, np.ndarray)
                 and not (a.flags.c_contiguous and a.flags.writeable) else a for a in args)


def generic_outputs(n: int, ny: int) -> dict[str, np.ndarray]:
    """The per-case arrays the integrator writes: nonfinite, t_end, y_end, steps, step_limit."""
    return {"nonfinite": np.zeros(n, bool), "t_end": np.empty(n), "y_end": np.empty((n, ny)),
            "steps": np.zeros(n, np.int64), "step_limit": np.zeros(n, bool)}


GENERIC_FIELDS = ("nonfinite", "t_end", "y_end", "steps", "step_limit")


# Pieces per thread of a chunk (dynamic scheduling: a thread that finishes early takes the
# next piece, so cases of uneven length, e.g. landing at different times, balance out).
PIECES_PER_THREAD = 4
_POOL: ThreadPoolExecutor | None = None


def threads() -> int:
    """Threads the kernels run in: numba's setting (``NUMBA_NUM_THREADS``, default the CPU
    count), read without starting numba's threading layer."""
    return max(1, int(numba.config.NUMBA_NUM_THREADS))


def _pool(n: int) -> ThreadPoolExecutor:
    global _POOL
    if _POOL is None or _POOL._max_workers != n:
        _POOL = ThreadPoolExecutor(n, thread_name_prefix="lgw-kernel")
    return _POOL


def run_chunk(kernel_fn, sl: slice, C: tuple, Q: tuple, R: tuple, O: tuple,  # noqa: N803
              G: tuple, rec_y: np.ndarray, rec_x: np.ndarray, parallel: bool = True) -> None:
    """Run cases ``sl`` (a slice of the first axis of C, R, G and, when recording, of the
    records): the slices are views, so the results land in the full arrays.

    parallel=True cuts the chunk into pieces run by ``threads()`` threads (the kernel is
    ``nogil``); parallel=False runs it in the calling thread (executors such as dask that
    parallelise over chunks themselves).  Every case is integrated on its own, so the results
    do not depend on the pieces or the threads."""
    record = O[-1]

    def piece(p: slice) -> None:
        kernel_fn(tuple(a[p] for a in C), Q, tuple(a[p] for a in R), O,
                  tuple(a[p] for a in G), rec_y[p] if record else rec_y,
                  rec_x[p] if record else rec_x)

    start, stop, _ = sl.indices(G[1].shape[0])
    n = max(0, stop - start)
    nt = min(threads(), n) if parallel else 1
    if nt <= 1:
        piece(slice(start, stop))
        return
    size = -(-n // (nt * PIECES_PER_THREAD))
    futures = [_pool(nt).submit(piece, slice(a, min(a + size, stop)))
               for a in range(start, stop, size)]
    try:
        for f in futures:
            f.result()
    finally:  # an error or an interrupt: pieces not started yet are dropped
        for f in futures:
            f.cancel()
