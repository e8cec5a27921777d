"""Claims of the bounded cascade law (``lgw.theory.mars.bounded``), with verdicts.

Every step is computed from the SymPy expressions of ``bounded`` (the law the simulator runs)
or, for the numeric bounds, checked against an independent route: the per-axis closed loop
integrated by ``scipy.integrate.solve_ivp`` (rtol 1e-9) from the law's own lambdified
expression, not the simulator's compiled code.  ``all_claims()`` lists them in report order.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from lgw.theory.evidence import Cited, Claim, FromClaim, Search, Step
from lgw.theory.mars import bounded as B
from lgw.theory.mars.mss import am, ap, grav, r, v
from lgw.theory.provers import prove_arb, prove_identity, prove_nonneg, prove_z3
from lgw.theory.symbolic import LAMBDIFY_MODULES, memo, on_branch, sig

X = sp.Symbol("x", positive=True)  # |r| on a branch
LAW = B.NAME
FIXED_TIME_REF = ("Aldana-Lopez, Gomez-Gutierrez et al., IJRNC 29 (2019), exact settling time "
                  "of s' = -k1 sig(s,e1) - k2 sig(s,e2); seed 000 Lemma 2")
COMPARISON_REF = "Khalil, Nonlinear Systems, 3rd ed., Lemma 3.4 (comparison lemma)"

# the equations field of these claims: the workbench's own laws, not in seed 000
_EQ = "beyond the paper"


def _branches(expr: sp.Expr, sym: sp.Symbol, statement: str) -> list[Step]:
    """expr == 0 on sym > 0 and on sym < 0 (sig and Abs become powers)."""
    return [prove_identity(sp.powsimp(on_branch(expr, {sym: sg})[0], force=True),
                           f"{statement} ({sym} {'>' if sg > 0 else '<'} 0)")
            for sg in (1, -1)]


@memo
def claim_derivative() -> Claim:
    """s' = -k1 sig(s,e1) - k2 sig(s,e2) + a_p identically; V = s^2/2 gives the fixed-time
    inequality of seed 000 Lemma 2 on s."""
    steps = _branches(sp.diff(B.psi(), r) - B.dpsi(), r, "d psi/dr equals the law's psi'(r)")
    sdot = sp.diff(B.surface(), r) * v + sp.diff(B.surface(), v) * (B.law_bounded() + grav + am
                                                                     + ap)
    target = B.reaching(B.surface()) + ap
    steps += _branches(sdot - target, r, "s' along r' = v, v' = a + g + a_m + a_p is "
                       "-k1 sig(s,e1) - k2 sig(s,e2) + a_p")
    s = B.S
    vdot = s * (B.reaching(s) + ap)
    want = -B.k1 * sp.Abs(s) ** (B.e1 + 1) - B.k2 * sp.Abs(s) ** (B.e2 + 1) + s * ap
    steps += _branches(vdot - want, s, "V = s^2/2: V' = -k1|s|^(e1+1) - k2|s|^(e2+1) + s a_p")
    return Claim("bounded-derivative", _EQ, "Lyapunov derivative of the bounded law",
                 "(not in seed 000)", "V' = -k1|s|^(e1+1) - k2|s|^(e2+1) + s a_p for V = s^2/2, "
                 "s = v + psi(r)", steps, law=LAW,
                 derived_expr=sp.Eq(sp.Symbol("Vdot"), want), statement="workbench")


@memo
def claim_finite() -> Claim:
    """The command is finite and continuous on R^2: every power in it has a nonnegative
    exponent or a base bounded away from 0, and sig(s, e) is continuous for e > 0."""
    steps = []
    law = B.law_bounded()
    for p in sorted(law.atoms(sp.Pow), key=sp.default_sort_key):
        base, ex = p.as_base_exp()
        if ex.is_Integer and ex > 0:
            continue
        if base.free_symbols & {r, v}:
            # the base is delta + |r| (> 0) or |r| with exponent p2 - 1 > 0 under p2 > 1
            if base.has(B.delta):
                steps.append(prove_nonneg(base - B.delta, f"base {sp.sstr(base)} >= delta > 0"))
            else:
                steps.append(prove_nonneg((ex).subs(B.p2, 1 + sp.Symbol("eps", positive=True)),
                                          f"exponent {sp.sstr(ex)} >= 0 on {sp.sstr(base)} "
                                          "(p2 > 1)"))
    for f in sorted(law.atoms(sig), key=sp.default_sort_key):
        steps.append(prove_nonneg(f.args[1], f"sig(., {sp.sstr(f.args[1])}) has a positive "
                                  "exponent: continuous, 0 at 0", strict=True))
    return Claim("bounded-command-finite", _EQ, "The bounded law's command is finite and "
                 "continuous everywhere", "(not in seed 000)",
                 "no negative power of |r| or |s| occurs; psi'(r) <= c1/sqrt(delta) + "
                 "c2 p2 |r|^(p2-1) is finite at r = 0", steps, law=LAW, statement="workbench")


@memo
def claim_psi_monotone() -> Claim:
    """psi' > 0; c1 phi' decreases in |r|; psi >= c1 |r|/sqrt(delta + |r|) (used by the cell
    bound of the command and by the inverse bound of ``psi_inv_upper``)."""
    on_pos = {r: X}
    dpsi_pos = B.dpsi().subs(on_pos)
    dphi = B.c1 * (B.delta + X / 2) * (B.delta + X) ** sp.Rational(-3, 2)
    ddphi = sp.diff(dphi, X)
    want = -B.c1 * (B.delta + X / 4) * (B.delta + X) ** sp.Rational(-5, 2)
    steps = [prove_nonneg(dpsi_pos, "psi'(x) > 0 for x = |r| > 0", strict=True),
             prove_identity(ddphi - want, "d/dx [c1 phi'(x)] = -c1 (delta + x/4)(delta+x)^(-5/2)"),
             prove_nonneg(-want, "so c1 phi' is nonincreasing in x"),
             prove_nonneg(B.psi().subs(on_pos) - B.c1 * X / sp.sqrt(B.delta + X),
                          "psi(x) - c1 x/sqrt(delta + x) = c2 x^p2 >= 0"),
             prove_nonneg(sp.diff(B.c2 * X ** B.p2, X), "c2 x^p2 is nondecreasing")]
    return Claim("bounded-psi-monotone", _EQ, "Shape of the velocity reference psi",
                 "(not in seed 000)", "psi increasing, c1 phi' nonincreasing, psi >= c1 phi",
                 steps, law=LAW, statement="workbench")


@memo
def claim_slide_time() -> Claim:
    """On s = 0 (r' = -psi(r)) the time from |r| = x0 to x1 is at most (F(x0) - F(x1))/c1."""
    d = B.delta
    F = 2 * sp.sqrt(d + X) + sp.sqrt(d) * (sp.log(X) - 2 * sp.log(sp.sqrt(d + X) + sp.sqrt(d)))
    steps = [prove_identity(sp.diff(F, X) - sp.sqrt(d + X) / X,
                            "dF/dx = sqrt(delta + x)/x = 1/(c1 phi(x)) * c1"),
             prove_nonneg(B.psi().subs(r, X) - B.c1 * X / sp.sqrt(d + X),
                          "psi >= c1 phi, so 1/psi <= 1/(c1 phi)")]
    Xb = sp.Symbol("X", positive=True)
    tail = Xb ** (1 - B.p2) / (B.c2 * (B.p2 - 1))
    steps.append(prove_identity(sp.diff(tail, Xb) + 1 / (B.c2 * Xb ** B.p2),
                                "d/dX X^(1-p2)/(c2 (p2-1)) = -1/(c2 X^p2): the tail beyond X "
                                "is finite (fixed time from any r)"))
    return Claim("bounded-slide-time", _EQ, "Sliding-phase time bound (closed form)",
                 "(not in seed 000)", "T_r <= (F(x0) - F(x1))/c1, F(x) = 2 sqrt(delta+x) + "
                 "sqrt(delta) ln(x/(sqrt(delta+x)+sqrt(delta))^2); from any r: "
                 "<= (F(X)-F(x1))/c1 + X^(1-p2)/(c2(p2-1))", steps, law=LAW,
                 derived_expr=sp.Eq(sp.Symbol("F"), F), statement="workbench")


def _quadrature_search(bg, n: int = 40, seed: int = 0) -> Step:
    from scipy.integrate import quad
    rng = np.random.default_rng(seed)
    worst, pt = np.inf, {}
    for _ in range(n):
        i = int(rng.integers(3))
        x1 = float(10 ** rng.uniform(-2, 0))
        x0 = float(10 ** rng.uniform(0, 3.5))
        q, _ = quad(lambda x, i=i: 1.0 / float(B.psi_np(x, bg, i)), x1, x0, limit=200)
        m = float(B.slide_time(x0, x1, bg, i)) - q
        if m < worst:
            worst, pt = m, {"axis": i, "x0": x0, "x1": x1, "quad": q}
    counter = None
    if worst < 0:
        from lgw.theory.evidence import Witness
        counter = Witness(dict(pt), worst, "scipy.integrate.quad vs closed form",
                          _slide_recheck(bg, pt), "mpmath.quad at 30 digits of int dx/psi(x) "
                          "from psi's SymPy expression, against the closed form", seed)
    return Step("slide_time >= int dx/psi(x) by adaptive quadrature (this gain set)",
                Search({"x0": (1, 10**3.5), "x1": (0.01, 1), "axis": (0, 2)},
                       "scipy.integrate.quad vs closed form", n, worst, pt, seed, counter,
                       tolerance=1e-9, budget=f"{n} random (axis, x0, x1)"))


def _slide_recheck(bg, pt: dict) -> float:
    """slide_time - int_x1^x0 dx/psi(x), the integral by mpmath at 30 digits from psi's SymPy
    expression (an independent route to the closed form and to scipy's quadrature)."""
    import mpmath

    i = pt["axis"]
    vals = dict(zip(B.PARAMS, bg.params()[i], strict=False))
    f = sp.lambdify(X, B.psi().subs(r, X).subs({k: sp.Float(v, 30) for k, v in vals.items()}),
                    modules="mpmath")  # x = |r| > 0: psi is odd
    with mpmath.workdps(30):
        q = mpmath.quad(lambda x: 1 / f(x), [pt["x1"], pt["x0"]])
    return float(B.slide_time(pt["x0"], pt["x1"], bg, i)) - float(q)


def claim_invariants(g=None) -> Claim:
    """State bounds for all t >= 0: |s| <= S_b, |r| <= R_b, |v| <= V_b (``axis_box_bounds``),
    judged for the ``[bounded]`` table of the gain set ``g`` (the default without one)."""
    bg, src = _bounded_of(g)
    s = B.S
    steps = [prove_nonneg(B.k1 * sp.Abs(s) ** (B.e1 + 1) + B.k2 * sp.Abs(s) ** (B.e2 + 1),
                          "V' = -(k1|s|^(e1+1) + k2|s|^(e2+1)) <= 0 without disturbance: |s| "
                          "is nonincreasing")]
    # sign lemma: |v| > P >= |psi(r)| implies s v > 0 (s = v + psi), by z3 on reals
    vv, pp, PP = sp.symbols("v psi P", real=True)
    steps.append(prove_z3(sp.StrictGreaterThan((vv + pp) * vv, 0),
                          [sp.Abs(pp) <= PP, sp.Abs(vv) > PP],
                          "|v| > P >= |psi(r)| implies s v > 0, so d|v|/dt = -psi'|v| - k(|s|) "
                          "(+ a_p sgn v) < 0 there: |v| <= max(|v0|, psi(R_b) + s_nb)"))
    steps += _branches(sp.sign(r) * (B.surface() - B.psi()) - sp.sign(r) * v, r,
                       "d|r|/dt = sgn(r) v = sgn(r) s - psi(|r|) (psi odd)")
    steps.append(Step("so |r| <= max(|r0|, psi^(-1)(S_b)) and the time bounds follow",
                      Cited(COMPARISON_REF, "comparison lemma for d|r|/dt <= S_b - psi(|r|)",
                            tuple(steps[-2:]))))
    steps.append(Step("[claim bounded-psi-monotone] the cell bounds of sup psi' min(...)",
                      FromClaim(claim_psi_monotone())))
    hyps = _exponent_steps(bg)
    deriv = Step("[claim bounded-derivative] s' = -k1 sig(s,e1) - k2 sig(s,e2)",
                 FromClaim(claim_derivative()))
    steps += [*hyps,
              Step("s reaches 0 within the exact T_s(S) from |s| <= S",
                   Cited(FIXED_TIME_REF, "fixed-time settling of the reaching law",
                         (deriv, hyps[0]))),
              Step("[claim bounded-slide-time] then |r| reaches rho within T_r",
                   FromClaim(claim_slide_time())),
              _two_phase_step()]
    return Claim("bounded-invariants", _EQ, "State, command and time bounds over a box",
                 "(not in seed 000)", "|r| <= R_b, |v| <= V_b, |a+g+a_m| <= u_b, landing by "
                 "T_s + T_r (lgw.theory.mars.bounded.axis_box_bounds, evaluated in double "
                 f"precision) for the gains of {src}", steps, law=LAW, scope="gain-set",
                 searches=(_ivp_search(bg), _quadrature_search(bg)),
                 numbers={"gains": src, "bounds": _box_numbers(bg, B.axis_box_bounds)},
                 statement="workbench")


@memo
def _u_numeric(sat: bool = False):
    """The commanded v' without disturbance (a + g + a_m), lambdified from the SymPy law."""
    if sat:
        u = B.law_bounded_sat() + grav + am
        return sp.lambdify((r, v, *B.PARAMS_SAT), u, modules=LAMBDIFY_MODULES)
    u = B.law_bounded() + grav + am
    return sp.lambdify((r, v, *B.PARAMS), u, modules=LAMBDIFY_MODULES)


# The Table III box per axis (seed 000 Table III; the tuner's envelope adds Table II).
TABLE3_AXES = (B.AxisBox(-1000.0, 200.0, -15.0, 45.0), B.AxisBox(0.0, 2000.0, -100.0, 0.0),
               B.AxisBox(1000.0, 1500.0, -75.0, 0.0))


S_EPS = 1e-7  # m/s


def fly_axis(bg, i: int, r0: float, v0: float, t_max: float = 300.0,
             tol: tuple[float, float] = (0.1, 0.1), method: str = "RK45") -> dict[str, float]:
    """One axis of the closed loop by solve_ivp (``method``, RK45 by default; rtol = atol =
    1e-10) from the SymPy law:
    max |r|, |v|, |u| along the way and the first time |r| <= tol[0] and |v| <= tol[1].

    Two phases: the full loop until |s| = S_EPS (a terminal event; the reaching law is not
    Lipschitz at s = 0 and the step size would shrink without end), then the sliding phase
    r' = -psi(r), v = -psi(r) (|s| is nonincreasing and stays 0 once it is 0; starting it at
    |s| = S_EPS errs by at most S_EPS in v and 2 sqrt(S_EPS)/k1 in time, both far below the
    margins compared).  ``bg`` a ``bounded_sat.SatGains`` flies ``law_bounded_sat``: |s| > w0
    outside Omega, so the event is met inside it, where the two laws coincide."""
    from scipy.integrate import solve_ivp
    f = _u_numeric(hasattr(bg, "w0"))
    P = bg.params()[i]

    def rhs(t, y):
        return [y[1], float(f(y[0], y[1], *P))]

    def s_zero(t, y):  # |s| = S_EPS: the rest of the reaching phase lasts < 2 sqrt(S_EPS)/k1
        return abs(y[1] + float(B.psi_np(y[0], bg, i))) - S_EPS
    s_zero.terminal = True
    kw = {"rtol": 1e-10, "atol": 1e-10, "dense_output": True, "method": method}
    one = solve_ivp(rhs, (0.0, t_max), [r0, v0], events=s_zero, **kw)
    t1 = float(one.t[-1])
    ts = np.linspace(0.0, t1, max(int(t1 * 50), 2))
    rr, vv = one.sol(ts)
    if t1 < t_max:
        two = solve_ivp(lambda t, y: [-float(B.psi_np(y[0], bg, i))], (t1, t_max),
                        [float(one.y[0, -1])], **kw)
        ts2 = np.linspace(t1, t_max, max(int((t_max - t1) * 50), 2))
        r2 = two.sol(ts2)[0]
        ts, rr, vv = np.r_[ts, ts2], np.r_[rr, r2], np.r_[vv, -B.psi_np(r2, bg, i)]
    u = np.asarray(f(rr, vv, *P), float)
    inside = (np.abs(rr) <= tol[0]) & (np.abs(vv) <= tol[1])
    t_land = float(ts[np.argmax(inside)]) if inside.any() else np.inf
    return {"r": float(np.max(np.abs(rr))), "v": float(np.max(np.abs(vv))),
            "u": float(np.max(np.abs(u))), "t_land": t_land}


RECHECK_METHOD = "Radau"  # the independent route of a box-bound violation (implicit, stiff)


def _box_recheck(gains, bounds, pt: dict) -> float:
    """The relative margin of the worst point's quantity, re-flown by ``RECHECK_METHOD``."""
    i = pt["axis"]
    d = bounds(gains, i, TABLE3_AXES[i])
    o = fly_axis(gains, i, pt["r0"], pt["v0"], t_max=1.2 * d["T_land"] + 5,
                 method=RECHECK_METHOD)
    bound = {"r": d["R_b"], "v": d["V_b"], "u": d["u_b"], "t_land": d["T_land"]}[pt["quantity"]]
    return (bound - o[pt["quantity"]]) / bound


def _box_witness(gains, bounds, worst: float, pt: dict, seed: int):
    """A violation of the box bounds as a witness, re-checked by another integrator."""
    from lgw.theory.evidence import Witness
    if not worst < 0:
        return None
    return Witness(dict(pt), worst, "solve_ivp RK45 1e-10 (two phases) on the SymPy law",
                   _box_recheck(gains, bounds, pt), f"the same flight by solve_ivp "
                   f"{RECHECK_METHOD} rtol = atol = 1e-10", seed)


def _worst_box_margin(gains, bounds, fixed_points, rng, n: int):
    """Least relative margin (bound - observed)/bound of the box bounds ``bounds(gains, i,
    box)`` (R_b, V_b, u_b, T_land) against ``fly_axis`` over each Table III axis box: the
    box's ``fixed_points(box)`` (corners, r0 = 0) and n random states.  Returns (worst, the
    point and quantity where it is attained, evaluations)."""
    worst, pt, evals = np.inf, {}, 0
    for i, box in enumerate(TABLE3_AXES):
        d = bounds(gains, i, box)
        pts = fixed_points(box) + [(rng.uniform(box.r_lo, box.r_hi),
                                    rng.uniform(box.v_lo, box.v_hi)) for _ in range(n)]
        for r0, v0 in pts:
            o = fly_axis(gains, i, r0, v0, t_max=1.2 * d["T_land"] + 5)
            evals += 1
            for key, bound in (("r", d["R_b"]), ("v", d["V_b"]), ("u", d["u_b"]),
                               ("t_land", d["T_land"])):
                m = (bound - o[key]) / bound
                if m < worst:
                    worst, pt = m, {"axis": i, "r0": r0, "v0": v0, "quantity": key,
                                    "bound": bound, "observed": o[key]}
    return worst, pt, evals


def _ivp_search(bg, n: int = 12, seed: int = 1) -> Step:
    rng = np.random.default_rng(seed)
    worst, pt, evals = _worst_box_margin(
        bg, B.axis_box_bounds, lambda box: [
            (box.r_lo, box.v_lo), (box.r_hi, box.v_hi), (box.r_lo, box.v_hi),
            (box.r_hi, box.v_lo), (min(max(0.0, box.r_lo), box.r_hi), box.v_lo)], rng, n)
    return Step("bounds >= the solve_ivp closed loop (this gain set, Table III box per axis: "
                "corners, r0 = 0 and random states)",
                Search({"box": "seed 000 Table III per axis", "gains": "this gain set"},
                       "solve_ivp RK45 1e-10 (two phases) on the SymPy law", evals, worst, pt, seed,
                       _box_witness(bg, B.axis_box_bounds, worst, pt, seed), relative=True,
                       budget=f"5 corner states + {n} random states per axis"))


def _box_numbers(bg, bounds) -> dict[str, dict[str, float]]:
    """The box bounds per axis (Table III), the numbers a gain-set claim reports."""
    keys = ("R_b", "V_b", "u_b", "T_s", "T_r", "T_land")
    out = {}
    for i, box in enumerate(TABLE3_AXES):
        d = bounds(bg, i, box)
        out["xyz"[i]] = {k: float(d[k]) for k in keys if k in d}
    return out


def _bounded_of(g) -> tuple:
    """The [bounded] table of gain set ``g`` (``Gains.extra``) and where it came from."""
    extra = getattr(g, "extra", None) if g is not None else None
    has = bool(extra) and "bounded" in extra
    return B.bounded_from_extra(extra), ("the gain file's [bounded] table" if has
                                         else "DEFAULT_BOUNDED (no [bounded] table)")


def _sat_of(g) -> tuple:
    from lgw.theory.mars import bounded_sat as BS
    extra = getattr(g, "extra", None) if g is not None else None
    has = bool(extra) and BS.TABLE in extra
    return BS.sat_from_extra(extra), ("the gain file's [bounded-sat] table" if has
                                      else "DEFAULT_SAT (no [bounded-sat] table)")


@memo
def claim_fixed_time() -> Claim:
    """Fixed time from every state: s reaches 0 by T_s* (exact), then the sliding phase by
    ``slide_time_global``; with |a_p,i| <= a_max the practical version with s_nb, theta, by a
    direct proof (seed 000's Theorem 1 is not cited: the workbench refutes its wording, claim
    theorem1, and its eta would be state-dependent here, a_max |s|)."""
    from lgw.theory.mars.claims import _neighbourhood_steps

    am_ = sp.Symbol("a_max", positive=True)
    th = sp.Symbol("theta", positive=True)
    deriv = Step("[claim bounded-derivative] V' = -k1|s|^(e1+1) - k2|s|^(e2+1) + s a_p",
                 FromClaim(claim_derivative()))
    nb = _neighbourhood_steps(B.k1, B.k2, B.e1, B.e2, am_, th, "s")
    steps = [
        deriv,
        Step("s reaches 0 within T_s* = Gamma closed form (exact least bound)",
             Cited(FIXED_TIME_REF, "fixed-time settling of the reaching law", (deriv,))),
        *nb,
        Step("with |a_p| <= a_max, |s| enters s_nb = min{(a_max/((1-theta)k1))^(1/e1), "
             "(a_max/((1-theta)k2))^(1/e2)} within (T(S) - T(s_nb))/theta: outside it "
             "d|s|/dt <= -theta k(|s|)",
             Cited(COMPARISON_REF, "comparison lemma for d|s|/dt <= -theta k(|s|) outside the "
                   "neighbourhood", (deriv, nb[-1]))),
        Step("[claim bounded-slide-time] then the sliding phase within T_r",
             FromClaim(claim_slide_time())),
    ]
    return Claim("bounded-fixed-time", _EQ, "Fixed-time / practical fixed-time landing",
                 "(not in seed 000)", "T_land <= T_s* + T_r,global from every state; the "
                 "landing set is |r| <= rho <= 0.1 m, |v| <= psi(rho) + s_nb <= 0.1 m/s "
                 "(practical: r -> 0 only exponentially inside it)", steps, law=LAW,
                 statement="workbench")


@memo
def all_claims() -> tuple[Claim, ...]:
    """The bounded laws' claims that hold or fail whatever the valid gains."""
    return (claim_derivative(), claim_finite(), claim_psi_monotone(), claim_slide_time(),
            claim_fixed_time(), claim_sat_invariance(), claim_sat_outside(), claim_sat_growth())


def gain_set_claims(g=None) -> list[Claim]:
    """The bounded laws' box bounds judged for the ``[bounded]`` and ``[bounded-sat]`` tables
    of gain set ``g`` (their defaults where the file has none)."""
    return [claim_invariants(g), claim_sat_bounds(g)]


@memo
def claim_sat_invariance() -> Claim:
    """For ``law_bounded_sat``: on the boundary |v| = W(r) of Omega_in = {|v| <= W(r)},
    d/dt (|v| - W(r)) < 0 (no disturbance), so Omega_in is forward invariant; inside it the law
    is ``law_bounded``.  Computed on the branch v > 0 (the law is odd in (r, v)) for r > 0
    (moving away) and r < 0 (moving toward): Z' = -2 psi' W - k(|s|) and Z' = -k(w0)."""
    Wx = B.psi().subs(r, X) + B.w0  # W at |r| = x
    steps = []
    for sgn_r in (1, -1):
        rr = sgn_r * X
        Wv = Wx
        s_b = Wv + B.psi().subs(r, rr)  # s on the boundary v = W
        vdot = (-B.dpsi().subs(r, rr) * Wv + B.reaching(s_b))  # sat(v) = W there
        zdot = vdot - sp.diff(Wx, X) * sgn_r * Wv  # d|r|/dt = sgn(r) v = sgn_r W
        zdot = sp.simplify(sp.powsimp(on_branch(zdot, {})[0], force=True))
        if sgn_r > 0:
            target = (-2 * B.dpsi().subs(r, X) * Wv - B.k1 * sig(s_b, B.e1)
                      - B.k2 * sig(s_b, B.e2))
            steps.append(prove_identity(zdot - target, "r > 0, v = W (away): Z' = -2 psi' W - "
                                        "k1 sig(s,e1) - k2 sig(s,e2)"))
            steps.append(prove_nonneg(-target, "... < 0 (s = 2 psi(x) + w0 > 0)", strict=True))
        else:
            steps.append(prove_identity(sp.simplify(s_b - B.w0), "r < 0, v = W (toward): s = w0"))
            target = -B.k1 * B.w0 ** B.e1 - B.k2 * B.w0 ** B.e2
            steps.append(prove_identity(zdot - target, "... and Z' = -k1 w0^e1 - k2 w0^e2 < 0"))
    return Claim("bounded-sat-invariance", _EQ, "Saturated variant: the exact-cancellation "
                 "region is forward invariant", "(not in seed 000)", "d(|v| - W(r))/dt < 0 on "
                 "|v| = W(r): once |v| <= psi(|r|) + w0 the variant is the bounded law", steps,
                 law=LAW, statement="workbench")


# --- the saturated variant's box bounds (lgw.theory.mars.bounded_sat) ----------------------

def _sat_outside_law() -> sp.Expr:
    """v' of ``law_bounded_sat`` with sat(v, W) replaced by W (the branch v > W(r))."""
    W = B.sat_limit()
    law = B.law_bounded_sat()
    sat = [m for m in law.atoms(sp.Max)]
    return law.xreplace({sat[0]: W}) + grav + am + ap


@memo
def claim_sat_outside() -> Claim:
    """Outside Omega (v > W(r), the case v < -W(r) is the mirror image: the law is odd in
    (r, v)): s > w0 and v' = -psi'(r) W(r) - k(s) + a_p <= -D, D = inf psi'W + k(w0) - a_max,
    so T_out <= (v0 - w0)/D and r moves by <= (v0^2 - w0^2)/(2D) (``axis_box_bounds_sat``)."""
    steps = _branches(B.psi().subs(r, -r) + B.psi(), r, "psi is odd: psi(-r) = -psi(r)")
    steps.append(prove_nonneg(B.psi().subs(r, X) + B.psi().subs(r, X), "r > 0: psi(|r|) + "
                              "psi(r) = 2 psi(x) >= 0 (r < 0: = 0 by oddness)"))
    vv, pa, pr, ww, w0 = sp.symbols("v psi_abs psi_r W w0", real=True)
    steps.append(prove_z3(sp.StrictGreaterThan(vv + pr, w0),
                          [vv > ww, sp.Eq(ww, pa + w0), pa + pr >= 0],
                          "v > W = psi(|r|) + w0 and psi(|r|) + psi(r) >= 0 imply s = v + "
                          "psi(r) > w0"))
    vdot = _sat_outside_law()
    want = -B.dpsi() * B.sat_limit() + B.reaching(B.surface()) + ap
    steps.append(prove_identity(vdot - want, "v > W: sat(v, W) = W, v' = -psi'(r) W(r) - "
                                "k1 sig(s,e1) - k2 sig(s,e2) + a_p"))
    sp_ = sp.Symbol("sigma", positive=True)
    steps.append(prove_nonneg(sp.diff(B.k1 * sp_ ** B.e1 + B.k2 * sp_ ** B.e2, sp_),
                              "k(sigma) = k1 sigma^e1 + k2 sigma^e2 increases, so k(s) > k(w0)",
                              strict=True))
    D, v0 = sp.symbols("D v_0", positive=True)
    steps.append(prove_identity(sp.integrate(vv / D, (vv, w0, v0)) - (v0**2 - w0**2) / (2 * D),
                                "dr = v dt <= -v dv/D: r moves by <= int_w0^v0 v/D dv = "
                                "(v0^2 - w0^2)/(2D) while outside"))
    return Claim("bounded-sat-outside", _EQ, "Saturated variant: outside the "
                 "exact-cancellation region |v| decreases at a rate >= D", "(not in seed 000)",
                 "v > psi(|r|) + w0 implies s > w0 and v' <= -(inf psi'W + k(w0) - a_max): "
                 "T_out <= (v0 - w0)/D, excursion <= (v0^2 - w0^2)/(2D)", steps, law=NAME_SAT,
                 statement="workbench")


@memo
def claim_sat_growth() -> Claim:
    """In Omega |r| grows only while |s| > psi(|r|); with y = min |r| so far, |r| - y <=
    G(psi(y), min(S, 2 psi(y) + w0)), G(p, S) = int_p^S (sigma - p)/(k1 sigma^e1) d sigma in
    closed form (``bounded_sat.growth_bound``)."""
    p_, S_, sg_ = sp.symbols("p S sigma", positive=True)
    e1 = B.e1
    G = ((S_ ** (2 - e1) - p_ ** (2 - e1)) / (2 - e1)
         - p_ * (S_ ** (1 - e1) - p_ ** (1 - e1)) / (1 - e1)) / B.k1
    steps = [prove_identity(sp.expand(sp.diff(G, S_) - (S_ - p_) / (B.k1 * S_ ** e1)),
                            "dG/dS = (S - p)/(k1 S^e1)"),
             prove_identity(G.subs(S_, p_), "G(p, p) = 0"),
             prove_nonneg(B.k2 * sg_ ** B.e2, "k(sigma) >= k1 sigma^e1 (k2 sigma^e2 >= 0)"),
             prove_nonneg(sg_ ** (-e1) / B.k1, "the integrand's weight "
                          "1/(k1 sigma^e1) > 0: G increases in S and decreases in p",
                          strict=True)]
    vv, pa, pr, w0 = sp.symbols("v psi_abs psi_r w0", real=True)
    steps.append(prove_z3(sp.Abs(vv + pr) <= 2 * pa + w0,
                          [sp.Abs(vv) <= pa + w0, sp.Abs(pr) <= pa, w0 > 0],
                          "in Omega |v| <= psi(|r|) + w0, so |s| <= 2 psi(|r|) + w0"))
    steps.append(Step("so |r(t)| <= sup_y y + G(psi(y), min(S, 2 psi(y) + w0)) (d|r|/dt <= "
                      "|s| - psi(|r|), d|s|/dt = -k(|s|) in Omega)",
                      Cited(COMPARISON_REF, "comparison lemma in the variable |s|",
                            tuple(steps))))
    return Claim("bounded-sat-growth", _EQ, "Saturated variant: growth of |r| inside "
                 "the exact-cancellation region", "(not in seed 000)",
                 "|r(t)| <= sup_{y <= R_in} y + G(psi(y), min(S, 2 psi(y) + w0))", steps,
                 law=NAME_SAT, derived_expr=sp.Eq(sp.Symbol("G"), G),
                 statement="workbench")


def _sat_cells_search(sg, n: int = 6, seed: int = 3) -> Step:
    """The cell bounds (inf psi'W, sup psi' W) against a dense sampling of the functions."""
    from lgw.theory.mars import bounded_sat as BS
    rng = np.random.default_rng(seed)
    worst, pt, evals = np.inf, {}, 0
    for _ in range(n):
        i, R = int(rng.integers(3)), float(10 ** rng.uniform(0, 3.5))
        x = np.linspace(0.0, R, 20001)
        dpsi = (sg.c1[i] * (sg.delta[i] + x / 2) * (sg.delta[i] + x) ** -1.5
                + sg.c2[i] * sg.p2 * x ** (sg.p2 - 1))
        f = dpsi * (B.psi_np(x, sg, i) + sg.w0[i])
        lo, hi = BS.inf_dpsi_w(sg, i, R), BS.sup_dpsi_speed(sg, i, R)
        evals += len(x)
        for m, q in ((f.min() - lo, "inf"), (hi - f.max(), "sup")):
            if m < worst:
                worst, pt = float(m), {"axis": i, "R": R, "which": q}
    return Step("cell bounds of inf/sup psi'(x) W(x) on [0, R] vs 20,001-point sampling "
                "(this gain set)", Search({"R": (1, 10**3.5), "axis": (0, 2)},
                                          "dense sampling", evals, worst, pt, seed,
                                          budget=f"{n} random (axis, R), 20,001 points each"))


def _sat_ivp_search(sg, n: int = 4, seed: int = 2) -> Step:
    from lgw.theory.mars import bounded_sat as BS
    rng = np.random.default_rng(seed)
    worst, pt, evals = _worst_box_margin(
        sg, BS.axis_box_bounds_sat, lambda box: [
            (a, b) for a in (box.r_lo, box.r_hi, min(max(0.0, box.r_lo), box.r_hi))
            for b in (box.v_lo, box.v_hi)], rng, n)
    return Step("box bounds >= the solve_ivp closed loop of law_bounded_sat (this gain set, "
                "Table III per axis: corners, r0 = 0 and random states)",
                Search({"box": "seed 000 Table III per axis", "gains": "this gain set"},
                       "solve_ivp RK45 1e-10 (two phases) on the SymPy law", evals, worst, pt,
                       seed, _box_witness(sg, BS.axis_box_bounds_sat, worst, pt, seed),
                       relative=True, budget=f"6 corner states + {n} random states per axis"))


def _exponent_steps(bg) -> list[Step]:
    """The settling lemma's 0 < e1 < 1 < e2 and the sliding phase's p2 > 1, checked on the
    gain set by Arb (a point box each)."""
    e1_, e2_, p2_ = sp.symbols("e1 e2 p2", positive=True)
    return [prove_arb(sp.Min(e1_, 1 - e1_, e2_ - 1), {e1_: (bg.e1, bg.e1), e2_: (bg.e2, bg.e2)},
                      f"0 < e1 = {bg.e1:g} < 1 < e2 = {bg.e2:g} (the settling lemma's "
                      "exponents)", strict=True,
                      recheck=lambda p: min(p["e1"], 1 - p["e1"], p["e2"] - 1)),
            prove_arb(p2_ - 1, {p2_: (bg.p2, bg.p2)}, f"p2 = {bg.p2:g} > 1 (the sliding "
                      "phase's fixed-time tail)", strict=True, recheck=lambda p: p["p2"] - 1)]


def _two_phase_step() -> Step:
    """T_land = T_s + T_r is a bound when each phase is (|s| stays 0 once it is 0)."""
    t_land, t_s, t_r, Ts, Tr = sp.symbols("t_land t_s t_r T_s T_r", real=True)
    return prove_z3(sp.Le(t_land, Ts + Tr),
                    [sp.Le(t_land, t_s + t_r), sp.Le(t_s, Ts), sp.Le(t_r, Tr), sp.Ge(t_s, 0),
                     sp.Ge(t_r, 0)],
                    "T_land <= T_s + T_r: s reaches 0 by T_s and stays (V' <= 0), then the "
                    "sliding phase takes at most T_r")


def _sat_hypothesis_steps(sg) -> list[Step]:
    """The hypotheses the composition's lemmas need, checked on the gain set by Arb: the
    settling lemma's 0 < e1 < 1 < e2, the sliding phase's p2 > 1, and k(w0) > a_max (= 0
    here) for the invariance of Omega and a positive outside deceleration D."""
    k1_, k2_, w0_, e1_, e2_ = sp.symbols("k1 k2 w0 e1 e2", positive=True)
    out = _exponent_steps(sg)
    for i in range(3):
        box = {k1_: (float(sg.k1[i]),) * 2, k2_: (float(sg.k2[i]),) * 2,
               w0_: (float(sg.w0[i]),) * 2, e1_: (sg.e1, sg.e1), e2_: (sg.e2, sg.e2)}
        out.append(prove_arb(k1_ * w0_**e1_ + k2_ * w0_**e2_, box,
                             f"k(w0) = k1 w0^e1 + k2 w0^e2 > a_max = 0 on axis {'xyz'[i]}: "
                             "Omega is invariant and D >= k(w0) > 0", strict=True,
                             recheck=lambda p: p["k1"] * p["w0"] ** p["e1"]
                             + p["k2"] * p["w0"] ** p["e2"]))
    return out


def _sat_composition_step() -> Step:
    """T_land = max(T_out + T_s(S_entry), T_s(S_start)) + T_r is a bound when each phase is."""
    t_land, t_reach, t_r, A, Bq, Mx, Tr = sp.symbols("t_land t_reach t_r A B M T_r", real=True)
    return prove_z3(sp.Le(t_land, Mx + Tr),
                    [sp.Le(t_land, t_reach + t_r), sp.Le(t_r, Tr), sp.Ge(t_r, 0),
                     sp.Or(sp.Le(t_reach, A), sp.Le(t_reach, Bq)), sp.Ge(Mx, A), sp.Ge(Mx, Bq)],
                    "T_land <= max(T_out + T_s(S_entry), T_s(S_start)) + T_r: s reaches 0 by "
                    "A = T_out + T_s(S_entry) (start outside Omega) or B = T_s(S_start) (start "
                    "inside), then the sliding phase takes at most T_r")


def claim_sat_bounds(g=None) -> Claim:
    """The box bounds of ``axis_box_bounds_sat`` (time, state, command) for the
    ``[bounded-sat]`` table of gain set ``g`` (the default without one)."""
    from lgw.theory.mars import bounded_sat as BS
    sg, src = _sat_of(g)
    lemmas = [Step(f"[claim {c.id}] {c.title}", FromClaim(c))
              for c in (claim_sat_outside(), claim_sat_invariance(), claim_sat_growth(),
                        claim_derivative(), claim_slide_time(), claim_psi_monotone())]
    hyps = _sat_hypothesis_steps(sg)
    settle = Step("in Omega s' = -k1 sig(s,e1) - k2 sig(s,e2): s reaches 0 within the exact "
                  "T_s(S) from |s| <= S", Cited(FIXED_TIME_REF, "fixed-time settling of the "
                                                "reaching law", (lemmas[3], hyps[0])))
    steps = [*lemmas, *hyps, settle, _sat_composition_step()]
    return Claim("bounded-sat-bounds", _EQ, "Saturated variant: state, command and time "
                 "bounds over a box", "(not in seed 000)", "|r| <= R_b, |v| <= V_b, |a+g+a_m| "
                 "<= u_b, landing by T_land (lgw.theory.mars.bounded_sat.axis_box_bounds_sat, "
                 f"evaluated in double precision) for the gains of {src}", steps, law=NAME_SAT,
                 scope="gain-set", searches=(_sat_cells_search(sg), _sat_ivp_search(sg)),
                 numbers={"gains": src, "bounds": _box_numbers(sg, BS.axis_box_bounds_sat)},
                 statement="workbench")


NAME_SAT = "bounded-sat"


