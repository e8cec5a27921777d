"""``lgw warmup`` and the kernels it builds: after the session's warm-up (tests/conftest.py)
nothing is compiled again, and each kernel has one specialisation whatever the options of a
run (a second one would be a second cold build of the whole integrator)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numba
import numpy as np
import pytest
from lgw.sim.kernel_cache import cache_dir

from tests.test_cli_conventions import run_lgw


@pytest.mark.parametrize("system", ["mars", "lunar", "eros"])
def test_a_second_warmup_compiles_nothing(system) -> None:
    r = run_lgw(["warmup", system, "--json"])
    assert r.code == 0, r.stderr
    doc = json.loads(r.stdout)
    assert doc["command"] == f"warmup {system}" and doc["cache"] == str(cache_dir())
    assert doc["kernels"] and all(k["kernel"].split("/")[0] == system for k in doc["kernels"])
    assert not [k for k in doc["kernels"] if k["compiled"]], doc


def test_warmup_without_a_system_does_every_system() -> None:
    r = run_lgw(["warmup"])
    assert r.code == 0, r.stderr
    for system in ("mars", "lunar", "eros"):
        assert f"{system} kernels" in r.stdout
    assert "compiled" not in r.stdout.replace("kernels", "")  # all loaded from the cache


def _one_specialisation(*dispatchers) -> None:
    for d in dispatchers:
        assert len(d.signatures) == 1, (d, d.signatures)


def test_mars_kernels_have_one_specialisation() -> None:
    from lgw.sim.mars import kernel as K
    from lgw.sim.mars.batch import simulate_batch
    from lgw.sim.mars.campaign import table3_states
    from lgw.theory.mars.gains import default_gains

    g = default_gains()
    r0, v0, m0 = table3_states(3, seed=0)
    runs = [{}, {"method": "dopri5"}, {"record": True, "t_max": 2.0},
            {"thrust_limit": 5e4, "limit": "norm", "disturbance": "sin"},
            {"disturbance": "random", "stop": "t_max", "t_max": 3.0, "parallel": False},
            {"disturbance": "worst", "drag": "printed", "guidance_drag": "none",
             "blowup_accel": np.inf, "t_max": 3.0}]
    for law in ("corrected", "super-twisting"):
        for kw in runs:
            simulate_batch(r0, v0, m0, g, law=law, **{"t_max": 5.0, **kw})
        _one_specialisation(K.kernel_module(law).kernel)


def test_lunar_kernel_has_one_specialisation() -> None:
    from dataclasses import replace

    from lgw.sim.lunar import kernel as K
    from lgw.sim.lunar.batch import simulate
    from lgw.sim.lunar.closed_loop import RunOptions
    from lgw.sim.lunar.scenario import section5_case

    base = RunOptions(t_end=1.0)
    for opts, kw in ((base, {}), (base, {"method": "dopri5"}),
                     (replace(base, failure="step", thrust_pointing="ideal"),
                      {"record": False, "parallel": False}),
                     (replace(base, sat_reading="nominal", failure="none"), {})):
        ctx, X0 = section5_case(opts=opts, n=2)
        simulate(ctx, X0, **kw)
    # a Monte Carlo campaign's per-case failure levels and times (lgw.sim.lunar.campaign)
    simulate(ctx, X0, record=False, failures=(np.array([0.5, 0.7]), np.array([0.2, 0.4])))
    _one_specialisation(K.kernel_module().kernel)


def test_eros_kernel_has_one_specialisation() -> None:
    from lgw.sim.eros import kernel as K
    from lgw.sim.eros.batch import SimOptions, simulate_kernel
    from lgw.sim.eros.campaign import offsets
    from lgw.theory.eros.gains import default_gains

    e0, ed0, ph = offsets(3, seed=0)
    for opts in (SimOptions(t_final=0.1), SimOptions(t_final=0.1, method="dopri5"),
                 SimOptions(t_final=0.1, law="fuzzy", switch="tanh", disturbance="none",
                            gravity="none"),
                 SimOptions(t_final=0.1, law="pdsmc", disturbance="unknown", n_sub=3)):
        simulate_kernel(e0, ed0, default_gains(), opts, ph, parallel=opts.law != "pdsmc")
    _one_specialisation(K.kernel_module().kernel)


def test_eros_descent_kernel_has_one_specialisation() -> None:
    from dataclasses import replace

    from lgw.sim.eros import descent_kernel as K
    from lgw.sim.eros.descent import DescentOptions, Navigation, descent_gains, simulate_descent

    base = DescentOptions(t0=0.0, t_max=2.0)
    e0 = np.array([[1.0, -2.0, 0.5], [0.0, 0.0, 0.0]])
    for opts, kw in ((base, {}), (replace(base, method="dopri5", gravity="two-point"), {}),
                     (replace(base, law="pdsmc", switch="tanh", gravity="polyhedron-exact",
                              controller_gravity="none", nav=Navigation.typical(3), stride=0),
                      {"parallel": False, "srp": [0.0, 1e-6]}),
                     (replace(base, gravity="none", controller_gravity="polyhedron"),
                      {"case_phase": 0.3, "nav_ids": [5, 9]})):
        simulate_descent(e0, np.zeros((2, 3)), descent_gains(), opts, **kw)
    _one_specialisation(K.kernel_module().kernel)


def _scale(x):
    return SCALE * x  # noqa: F821  (a constant of the generated module)


def sys_twice(x):
    return _scale_fn(x) + _scale_call(x)  # noqa: F821


def test_hooks_text_compiles_each_helper_as_asked() -> None:
    """The one hook builder of every system: constants, sources, a helper as ``<name>_fn``
    (numba-inlined only when asked) and as ``<name>_call`` (a plain call), the hooks last."""
    from lgw.sim import integrate, kernel_cache

    text = "import numba\n" + integrate.hooks_text([sys_twice], [_scale], consts={"SCALE": 3.0},
                                                     inline=[_scale], called=[_scale])
    mod = kernel_cache.load_module(f"test_hooks_text_{kernel_cache.key([text])}", lambda: text)
    hook = mod.sys_twice
    # a hook compiled apart has no CPython wrapper (integrate.CALLEE_ONLY): compiled code calls it
    assert numba.njit(lambda x: hook(x))(1.5) == 9.0
    assert mod._scale_fn.targetoptions.get("inline") == "always"
    assert mod._scale_call.targetoptions.get("inline", "never") == "never"
    assert mod.sys_twice.targetoptions.get("inline", "never") == "never"
    for f in (mod._scale_call, mod.sys_twice):
        assert f.targetoptions.get("no_cpython_wrapper") and f.targetoptions.get("no_cfunc_wrapper")


def _callee_only_names() -> set[str]:
    """The functions of every system's generated modules compiled without wrappers."""
    from lgw.sim.eros import descent_kernel
    from lgw.sim.eros import kernel as eros_kernel
    from lgw.sim.lunar import kernel as lunar_kernel
    from lgw.sim.mars import kernel as mars_kernel
    from lgw.sim.mars.laws import LAWS

    mods = [mars_kernel.hooks_module(), *(mars_kernel.kernel_module(law) for law in LAWS),
            lunar_kernel.kernel_module(), eros_kernel.kernel_module(),
            descent_kernel.kernel_module()]
    return {name for mod in mods for name, f in vars(mod).items()
            if getattr(f, "targetoptions", {}).get("no_cpython_wrapper")}


def test_no_python_code_reaches_a_function_without_its_wrapper() -> None:
    """numba does not guard a function compiled with ``integrate.CALLEE_ONLY``: called from
    Python it crashes the interpreter.  Python reaches a generated module's function as an
    attribute (``module.name``) or an import: no source of the project does either for one."""
    names = _callee_only_names()
    # the hooks run once per case and the helpers compiled apart, of each system
    assert {"sys_init", "sys_start", "sys_finish", "_ground_fn"} <= names
    root = Path(__file__).resolve().parents[1]
    pattern = re.compile(r"(\.|\bimport\s+)(" + "|".join(map(re.escape, names)) + r")\b")
    hits = []
    for path in root.glob("*/**/*.py"):
        if path.parts[len(root.parts)] in {"theory", "sim", "tuning", "tests", "benchmarks"}:
            for k, line in enumerate(path.read_text().splitlines(), 1):
                if pattern.search(line.split("#")[0]) and "numba.njit" not in line:
                    hits.append(f"{path.relative_to(root)}:{k}: {line.strip()}")
    assert not hits, "\n".join(hits)


# --- hooks written into the integrator's source (lgw.sim.integrate.inline_source) ---------

TEMPLATE = '''
def kernel(a, n):
    out = 0.0
    for k in range(n):
        x = a + k
        hook_v(x, out, k)
        out, flag = hook_r(x, out)
        if flag:
            out = out + 1.0
    return out
'''

HOOKS = '''
LIMIT = 5.0


def hook_v(x, out, k):
    """no return: written in as is"""
    y = x * 2.0
    k = k + int(y)


def hook_r(x, out):
    """returns on several paths; its locals shadow none of the template's"""
    y = x * 0.5
    if y > LIMIT:
        return out - y, True
    for j in range(3):
        y = y + j
    return out + y, False
'''


def _run(src: str, *args):
    ns: dict = {}
    exec(compile(HOOKS + "\n" + src, "<test>", "exec"), ns)  # noqa: S102 (test text)
    return ns["kernel"](*args)


def test_inline_source_writes_hooks_in_with_the_same_results() -> None:
    from lgw.sim.integrate import inline_source

    src = inline_source(TEMPLATE, HOOKS, ["hook_v", "hook_r"])
    assert "hook_r(" not in src and "hook_v(" not in src  # both written in
    assert "_hook_r_y" in src and "LIMIT" in src  # locals renamed, globals kept
    for a, n in ((0.0, 0), (1.5, 4), (9.0, 7), (-3.0, 12)):
        assert _run(src, a, n) == _run(TEMPLATE, a, n)


def test_inline_source_returns_from_inside_a_hook_s_loops() -> None:
    from lgw.sim.integrate import inline_source

    looped = HOOKS.replace("        y = y + j\n", "        y = y + j\n"
                                                  "        while y > 4.0:\n"
                                                  "            if y > 5.5:\n"
                                                  "                return out + j, True\n"
                                                  "            y = y - 1.0\n")
    src = inline_source(TEMPLATE, looped, ["hook_r"])
    assert "hook_r(" not in src and "_hook_r_returned" in src
    for a, n in ((0.0, 0), (1.5, 4), (7.0, 5), (9.0, 7), (-3.0, 12)):
        assert _run_with(looped, src, a, n) == _run_with(looped, TEMPLATE, a, n)


def _run_with(hooks: str, src: str, *args):
    ns: dict = {}
    exec(compile(hooks + "\n" + src, "<test>", "exec"), ns)  # noqa: S102 (test text)
    return ns["kernel"](*args)


def test_inline_source_leaves_a_hook_it_cannot_write_in_as_a_call() -> None:
    from lgw.sim.integrate import inline_source

    nested = HOOKS.replace("    y = x * 0.5\n", "    y = (lambda z: z * 0.5)(x)\n")
    assert "hook_r(" in inline_source(TEMPLATE, nested, ["hook_r"])  # a lambda
    shadow = HOOKS.replace("LIMIT", "flag")  # a global the template binds as a local
    assert "hook_r(" in inline_source(TEMPLATE, shadow, ["hook_r"])


@pytest.mark.parametrize("system", ["mars", "eros"])
def test_kernel_text_has_its_per_step_hooks_written_in(system) -> None:
    """The vector field, the step and the sample hook are in the kernel's own source (not
    numba-inlined calls)."""
    import ast

    from lgw.sim import integrate
    if system == "mars":
        from lgw.sim.mars import kernel as K
        from lgw.sim.mars.laws import get_law
        text = K.kernel_text(get_law("corrected"))
    else:
        from lgw.sim.eros import kernel as K
        text = K.kernel_text()
    kfn = next(n for n in ast.parse(text).body
               if isinstance(n, ast.FunctionDef) and n.name == "kernel")
    called = {n.func.id for n in ast.walk(kfn)
              if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)}
    assert not called & set(integrate.INLINED_HOOKS), called
    assert {"sys_init", "sys_start", "sys_finish"} <= called
