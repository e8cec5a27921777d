"""Seed 000 in lanes (``lgw.sim.lanes``): the law for a block of cases at once, in SIMD.

The lane kernel of a law is a generated module like the generic kernel
(``lgw.sim.mars.kernel.kernel_text``): the law's generated scalar code
(``lgw.sim.mars.laws.law_source``), the Mars hooks copied as source, and the lane
templates of ``lgw.sim.lanes``, plus three pieces written here:

* the lane form of the law (``lane_law_source``): the very text lambdify wrote for the scalar
  law (its ``share_powers`` form, or the exact form for a law without one), with its exp and
  log bound to ``lgw.sim.vmath.vexp`` / ``vlog`` instead of the C library, inside a loop over
  the lanes of one axis that LLVM vectorises.  The entries that the scalar law sends to
  another branch (``_guard`` at or below TINY, or r = v = 0: ``lgw.sim.mars.laws.numba_law``)
  are then evaluated by the scalar law itself;
* ``lane_pass``: the law's inputs for every running lane, as ``sys_rhs`` forms them (r, v,
  grav, the guidance drag a_m, m), the lane law, and each lane's inputs and results in its
  row of the buffer LB;
* ``law``: the name ``sys_rhs`` calls, here reading lane l's results from LB[l], which it
  receives as the law parameters P (``lane_q``: Q with P replaced by LB[l], whose first
  columns hold P).  It returns the lane result only when asked at exactly the inputs the lane
  pass used; otherwise it counts a miss and evaluates the scalar law, so a change to how
  ``sys_rhs`` calls the law can slow the lane kernel down but never change its results.

What differs from the generic kernel: only the law's exp and log (``lgw.sim.vmath``, within 1
ulp of the C library per call).  Everything else, the plant, the thrust limit, events and
metrics, is the same compiled hook code.  tests/mars/test_lanes.py flies a Table II campaign
both ways and compares outcomes, landing times, fuel and the rest; benchmarks/bench_lanes.py
measures the speed against the generic kernel in the same run.
"""

from __future__ import annotations

import functools
import inspect
import re

from lgw.sim import integrate, lanes
from lgw.sim.codegen import import_line, lambdified_source
from lgw.sim.mars import kernel as mars_kernel

NL = 16  # lanes per block: two AVX-512 vectors of doubles per axis (bench_lanes.py --lanes)
# The lane buffer LB (3 axes, LB_COLS): the law parameters P (NPAR columns, as the scalar law
# reads them), then per input / result k a block of NL columns, lane ln in column
# NPAR + k NL + ln: the inputs r, v, grav, a_m, m the lane pass used (k = 0..4), the results a
# (k = 5) and s2 (k = 6); then the misses (law calls that found no result) and the lane whose
# right-hand side runs (row 0), then the lanes' drag factors (row 0, NL columns).
LB_A = 5
LB_S2 = 6
LB_BLOCKS = 7
# The lane pass's guidance drag a_m differs from sys_rhs's by the drag factor's exp (vexp
# against the C library: a few ulp); a law call is answered from the lane pass when its a_m
# agrees to this relative tolerance (and r, v, grav, m exactly).
AM_RTOL = 1e-14


def lb_layout(npar: int, nl: int) -> dict[str, float]:
    """The lane module's constants for a law with npar parameters and nl lanes: the lane
    buffer's columns, the a_m tolerance."""
    end = npar + LB_BLOCKS * nl
    return {"NL": nl, "NPAR": npar, "AM_RTOL": AM_RTOL, "LB_A": LB_A, "LB_S2": LB_S2,
            "LB_MISS": end, "LB_LANE": end + 1, "LB_FAC": end + 2, "LB_COLS": end + 2 + nl}


def lane_law_source(spec) -> str:
    """The lane form of law ``spec`` (with s2, as the kernel calls it): ``_lane_form``, the
    scalar text of ``law_source`` with exp / log from ``lgw.sim.vmath``, and ``law_lanes``
    (LB, SP, run), which fills the results a, s2 of all NL lanes and three axes from their
    inputs in LB; entries of running lanes that the scalar law evaluates by another branch
    are taken from the scalar law (``law_scalar``)."""
    from lgw.sim.mars.laws import SURFACE_SYMBOLS, _generated

    gen = _generated(spec, True)
    form = "shared" if gen["shared"] is not None else "exact"
    src, imports = lambdified_source(gen[form], "_lane_form")
    # the same text, its exp and log bound to the vectorisable ones (names of laws.explog)
    src = re.sub(r"\b_ln\(", "_vln(", re.sub(r"\b_ex\(", "_vex(", src))
    imports = [i for i in imports if not re.search(r" as _(ln|ex)$", i)]
    npar = len(spec.params)
    pars = [f"p{j}" for j in range(npar)]
    pars += [f"e{j}" for j in range(len(gen["extra"]))]
    load = [f"        p{j} = LB[ax, {j}]" for j in range(npar)]
    load += [f"        e{j} = SP[ax, {SURFACE_SYMBOLS.index(x)}]"
             for j, x in enumerate(gen["extra"])]
    inputs = [f"LB[ax, NPAR + {k} * NL + ln]" for k in range(5)]
    args = ", ".join(inputs + pars)
    if form == "shared":
        other = f"not (abs(_guard({args})) > TINY)"
    else:
        other = f"{inputs[0]} == 0.0 and {inputs[1]} == 0.0"
    out = ["LB[ax, NPAR + LB_A * NL + ln] = a", "LB[ax, NPAR + LB_S2 * NL + ln] = s2"]
    body = "\n".join([
        "def law_lanes(LB, SP, run):  # noqa: N803",
        "    for ax in range(3):",
        *load,
        "        for ln in range(NL):",
        f"            a, s2 = _lane_form({args})",
        *(f"            {o}" for o in out),
        "        for ln in range(NL):",
        f"            if run[ln] and {other}:",
        f"                a, s2 = law_scalar({', '.join(inputs)}, LB, SP, ax)",
        *(f"                {o}" for o in out),
        ""])
    return "\n".join([*sorted(imports), "from lgw.sim.vmath import vexp as _vex",
                      "from lgw.sim.vmath import vlog as _vln", "", src,
                      '_lane_form = numba.njit(_lane_form, error_model="numpy", '
                      'inline="always", fastmath=FASTMATH)', "", body,
                      'law_lanes = numba.njit(law_lanes, error_model="numpy", '
                      "fastmath=FASTMATH)", ""])


def drag_fac_lane_source() -> str:
    """``_drag_fac_lane``: the Mars kernel's drag factor (``lgw.sim.mars.kernel._drag_fac``,
    its source copied) with its exp from ``lgw.sim.vmath``, so that the lane pass's loop over
    lanes vectorises."""
    fn = mars_kernel._drag_fac.py_func
    src = inspect.getsource(fn)
    src = src[src.index("def "):].replace("def _drag_fac(", "def _drag_fac_lane(", 1)
    src = re.sub(r"\bmath\.exp\(", "_vex(", src)
    glb = fn.__globals__
    imports = [import_line(n, glb[n]) for n in sorted(fn.__code__.co_names)
               if n in glb and not inspect.ismodule(glb[n])]
    return "\n".join([*imports, "", src,
                      '_drag_fac_lane = numba.njit(_drag_fac_lane, error_model="numpy", '
                      'inline="always")', ""])


# --- templates (copied into the lane kernel module) -------------------------------------

def law(r, v, grav, a_m, m, P, SP, i):  # noqa: N803  (template)
    """What sys_rhs calls in the lane kernel: P is the lane buffer LB (``lane_q``), whose
    first columns are the law parameters; the result of the selected lane (``lane_select``)
    if asked at the inputs the lane pass used (a_m to AM_RTOL: the lane pass's drag factor
    is ``vexp``'s), else the scalar law (a miss, counted)."""
    b = NPAR + int(P[0, LB_LANE])  # noqa: F821
    if (r == P[i, b] and v == P[i, b + NL] and grav == P[i, b + 2 * NL]  # noqa: F821
            and abs(a_m - P[i, b + 3 * NL]) <= AM_RTOL * abs(a_m)  # noqa: F821
            and m == P[i, b + 4 * NL]):  # noqa: F821
        return P[i, b + LB_A * NL], P[i, b + LB_S2 * NL]  # noqa: F821
    P[i, LB_MISS] += 1.0  # noqa: F821
    return law_scalar(r, v, grav, a_m, m, P, SP, i)  # noqa: F821


def lane_pass(Y, yr, Q, W, run):  # noqa: N803  (template)
    """The law at Y[l, yr] for every running lane l: its inputs as sys_rhs forms them
    (lgw.sim.mars.kernel.sys_rhs: r, v, grav, the guidance drag a_m, m; the drag factor's exp
    from ``lgw.sim.vmath``) into LB, then the lane law (results into LB)."""
    LB = W[0]  # noqa: N806
    (P, SP, grav, area, pkind, gkind, c, fmax, lim, dkind, damp, eps, tol_r, tol_v,
     stop_landing, m_dry, blow_acc) = Q
    # every lane, running or not (a free lane's state is harmless): loops that vectorise
    for ln in range(NL):  # noqa: F821
        LB[0, LB_FAC + ln] = _drag_fac_lane(gkind, Y[ln, yr, 2])  # noqa: F821
    for ax in range(3):
        gr = grav[ax]
        ar = area[ax]
        for ln in range(NL):  # noqa: F821
            m = Y[ln, yr, 6]
            v = Y[ln, yr, 3 + ax]
            LB[ax, NPAR + ln] = Y[ln, yr, ax]  # noqa: F821
            LB[ax, NPAR + NL + ln] = v  # noqa: F821
            LB[ax, NPAR + 2 * NL + ln] = gr  # noqa: F821
            LB[ax, NPAR + 3 * NL + ln] = _drag(gkind, LB[0, LB_FAC + ln], v, ar, m)  # noqa: F821
            LB[ax, NPAR + 4 * NL + ln] = m  # noqa: F821
    law_lanes(LB, SP, run)  # noqa: F821


def lane_q(Q, W):  # noqa: N803  (template)
    """Q as the lanes' sys_rhs receives it: the law parameters P replaced by LB."""
    return (W[0],) + Q[1:]


def lane_select(W, ln):  # noqa: N803  (template)
    W[0][0, LB_LANE] = ln  # noqa: F821


def lane_work(Q):  # noqa: N803  (template)
    """(LB,): P in its first NPAR columns, the input blocks 1 (a harmless state for the lanes
    that have no case), the rest 0."""
    P = Q[0]  # noqa: N806
    LB = np.zeros((3, LB_COLS))  # noqa: F821, N806
    for ax in range(3):
        for j in range(NPAR):  # noqa: F821
            LB[ax, j] = P[ax, j]
        for j in range(NPAR, NPAR + LB_A * NL):  # noqa: F821
            LB[ax, j] = 1.0
    return (LB,)


def lane_misses(W):  # noqa: N803  (template)
    LB = W[0]  # noqa: N806
    return int(LB[0, LB_MISS] + LB[1, LB_MISS] + LB[2, LB_MISS])  # noqa: F821


GLUE = (law, lane_pass, lane_q, lane_select, lane_work, lane_misses)


def glue_source() -> str:
    import inspect
    # inlined where called, as the generic kernel's law and hooks are: a call that passes
    # arrays costs an atomic reference count per array, per lane and axis
    inline = {"law", "lane_q", "lane_select"}
    return "\n".join([*(inspect.getsource(f) + "\n" for f in GLUE),
                      *(f'{f.__name__} = numba.njit({f.__name__}, error_model="numpy"'
                        + (', inline="always")' if f.__name__ in inline else ")")
                        for f in GLUE)])


def lanes_text(spec, nl: int = NL) -> str:
    """The full text of the lane kernel module of law ``spec`` with nl lanes (what the cache
    keys)."""
    from lgw.sim.mars.laws import law_source

    header = "\n".join([law_source(spec, True), "", "law_scalar = law", "",
                        lane_law_source(spec), drag_fac_lane_source(), glue_source()])
    sizes = {"NY": mars_kernel.NY, "NX": mars_kernel.NX, "NS": mars_kernel.NS,
             **lb_layout(len(spec.params), nl)}
    return lanes.lanes_module_source(integrate.KERNEL_IMPORTS, header, sizes,
                                     mars_kernel.hooks_source())


@functools.cache
def _lanes_module(spec, nl: int):
    from lgw.sim import kernel_cache
    slug = re.sub(r"\W", "_", spec.name)
    return kernel_cache.module_for(f"mars_lanes_{slug}", lanes_text(spec, nl), _deps())


def _deps() -> list[str]:
    from lgw.sim import kernel_cache, vmath
    return mars_kernel._deps() + kernel_cache.imported_sources(vmath)


def kernel_module(name: str, nl: int | None = None):
    """The lane kernel module of law ``name`` with nl lanes (default ``NL``):
    ``kernel_parallel``, ``kernel_serial`` with the generic kernel's signature, returning the
    law calls that missed their lane result (0 when the lane pass's inputs are the ones
    sys_rhs asks the law at)."""
    from lgw.sim.mars.laws import get_law
    return _lanes_module(get_law(name), NL if nl is None else int(nl))


_deps()  # read the sources the lane kernels import now, at import (lgw.sim.kernel_cache)
