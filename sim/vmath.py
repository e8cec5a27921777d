"""exp and log that LLVM can vectorise across lanes: branch-free arithmetic, no libm call.

``math.exp`` / ``math.log`` compile to calls into the C library, one value at a time; a loop
over lanes of cases that calls them cannot be vectorised, and numba's LLVM on this kind of
machine has no vector math library to substitute (``numba -s``: "SVML: False").  ``vexp`` and
``vlog`` are the classic reductions written in plain floating-point and integer arithmetic,
with the special values chosen by selects, so that the loop vectoriser turns a loop over
lanes into AVX2 / AVX-512 code (8 doubles per instruction with AVX-512).

Accuracy (tests/test_vmath.py, against numpy over the whole double range and the special
values): at most 1 ulp for exp on [-745, 710] and for log on (0, inf), with numpy's values at
0, inf, NaN, overflow and underflow (exp(x) = inf above 709.78, 0 below -745.13; log(0) =
-inf, log(x < 0) = NaN).  Not bitwise equal to the C library (which is correctly rounded in
most cases): a kernel that uses them agrees with its libm form to a few ulp per call.

The bit casts between float64 and int64 are LLVM ``bitcast`` instructions (``_f2i``,
``_i2f``): free, and vectorisable.  Each function keeps its own strict floating-point
semantics (it is compiled without fast-math reassociation, which would fold the Cody-Waite
split ln 2 = LN2_HI + LN2_LO) and LLVM inlines it into the loop that calls it.

exp: x = n ln2 + r with |r| <= ln2 / 2 (Cody & Waite), e^r by its Taylor polynomial of
degree 13 (truncation below 2^-60 relative), 2^n applied in two halves so that results
between the smallest subnormal and DBL_MAX need no special case.  log: x = 2^k m with m in
[sqrt(2)/2, sqrt(2)), log m = 2 atanh(f / (2 + f)), f = m - 1, with fdlibm's e_log.c
polynomial (|error| < 2^-58.45); subnormal x is scaled by 2^54 first.
"""

from __future__ import annotations

import math

import numba
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

# float-exception-free flags that keep the evaluation order: fused multiply-add only
VMATH_FASTMATH = {"contract"}

LOG2E = 1.4426950408889634
LN2_HI = 6.93147180369123816490e-01  # fdlibm: ln 2 high part (trailing zeros)
LN2_LO = 1.90821492927058770002e-10  # ln 2 - LN2_HI
EXP_HI = 709.782712893384  # above: exp overflows (inf)
EXP_LO = -745.1332191019412  # below: exp underflows to 0
DBL_MIN = 2.2250738585072014e-308  # smallest normal double
TWO54 = 18014398509481984.0
SQRT_HALF_BITS = 0x3FE6A09E667F3BCD  # the bits of sqrt(2)/2
MANT_MASK = 0x000FFFFFFFFFFFFF

# 1/k! for k = 13 .. 0: e^r's Taylor polynomial, Horner order
_EXP_COEF = tuple(1.0 / math.factorial(k) for k in range(13, -1, -1))
# fdlibm e_log.c: log(1+f) = f - hfsq + s (hfsq + R(z)), R(z) ~ Lg1 z + ... + Lg7 z^7
LG1 = 6.666666666666735130e-01
LG2 = 3.999999999940941908e-01
LG3 = 2.857142874366239149e-01
LG4 = 2.222219843214978396e-01
LG5 = 1.818357216161805012e-01
LG6 = 1.531383769920937332e-01
LG7 = 1.479819860511658591e-01


@intrinsic
def _f2i(typingctx, x):
    """The bits of a float64 as an int64 (LLVM bitcast)."""
    if x != types.float64:
        return None

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.IntType(64))
    return types.int64(types.float64), codegen


@intrinsic
def _i2f(typingctx, x):
    """The float64 whose bits are the int64 x (LLVM bitcast)."""
    if x != types.int64:
        return None

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], ir.DoubleType())
    return types.float64(types.int64), codegen


C13, C12, C11, C10, C9, C8, C7, C6, C5, C4, C3, C2, C1, C0 = _EXP_COEF


@numba.njit(error_model="numpy", fastmath=VMATH_FASTMATH, cache=True)
def vexp(x: float) -> float:
    """e^x to 1 ulp, vectorisable (module docstring)."""
    xc = min(max(x, EXP_LO), EXP_HI)
    n = math.floor(xc * LOG2E + 0.5)
    r = (xc - n * LN2_HI) - n * LN2_LO
    p = C13
    p = p * r + C12
    p = p * r + C11
    p = p * r + C10
    p = p * r + C9
    p = p * r + C8
    p = p * r + C7
    p = p * r + C6
    p = p * r + C5
    p = p * r + C4
    p = p * r + C3
    p = p * r + C2
    p = p * r + C1
    p = p * r + C0
    ni = numba.int64(n)
    n1 = ni >> 1
    n2 = ni - n1
    res = p * _i2f((n1 + 1023) << 52) * _i2f((n2 + 1023) << 52)
    res = math.inf if x > EXP_HI else res
    res = 0.0 if x < EXP_LO else res
    return x if x != x else res


@numba.njit(error_model="numpy", fastmath=VMATH_FASTMATH, cache=True)
def vlog(x: float) -> float:
    """ln x to 1 ulp, vectorisable (module docstring); ln 0 = -inf, ln(x < 0) = NaN."""
    sub = x < DBL_MIN
    xs = x * TWO54 if sub else x
    b = _f2i(xs) - SQRT_HALF_BITS
    k = (b >> 52) - (54 if sub else 0)
    f = _i2f((b & MANT_MASK) + SQRT_HALF_BITS) - 1.0
    s = f / (2.0 + f)
    z = s * s
    w = z * z
    t1 = w * (LG2 + w * (LG4 + w * LG6))
    t2 = z * (LG1 + w * (LG3 + w * (LG5 + w * LG7)))
    hfsq = 0.5 * f * f
    dk = float(k)
    res = dk * LN2_HI - ((hfsq - (s * (hfsq + t1 + t2) + dk * LN2_LO)) - f)
    res = -math.inf if x == 0.0 else res
    res = math.inf if x == math.inf else res
    return res if x >= 0.0 else math.nan
