"""Run options (lgw.sim.options) and the simulator entry points: a misspelled keyword is
rejected (never silently ignored), a value out of range names its parameter, and the objects
cannot be changed once built."""

from __future__ import annotations

import dataclasses
import inspect

import numpy as np
import pytest
from lgw.sim.options import IntegrationOptions, LimitOptions, StoppingOptions
from lgw.theory.errors import ParameterError

GOOD = {
    IntegrationOptions: {"dt": 0.05, "rtol": 1e-5, "atol": 1e-5, "max_step": 1.0,
                         "max_steps": 1000},
    StoppingOptions: {"t_max": 120.0, "land_tol": (0.1, 0.1), "m_dry": 1505.0},
    LimitOptions: {},
}


def _misspell(name: str) -> str:
    return name[:-1] + ("x" if name[-1] != "x" else "y")


@pytest.mark.parametrize("cls", list(GOOD))
def test_options_reject_a_misspelled_keyword(cls):
    for f in dataclasses.fields(cls):
        kw = dict(GOOD[cls])
        kw[_misspell(f.name)] = kw.pop(f.name, None) or 1.0
        with pytest.raises(TypeError, match="unexpected keyword"):
            cls(**kw)
    obj = cls(**GOOD[cls])
    with pytest.raises(dataclasses.FrozenInstanceError):
        obj.__setattr__(dataclasses.fields(cls)[0].name, None)


def test_every_public_options_object_is_covered():
    from lgw.sim import options
    public = {o for _, o in inspect.getmembers(options, inspect.isclass)
              if dataclasses.is_dataclass(o) and o.__module__ == options.__name__}
    assert public == set(GOOD)


@pytest.mark.parametrize("cls, name, bad", [
    (IntegrationOptions, "method", "rk45"),
    (IntegrationOptions, "dt", 0.0),
    (IntegrationOptions, "dt", float("nan")),
    (IntegrationOptions, "dt", "0.05"),
    (StoppingOptions, "stop", "ground"),
    (StoppingOptions, "t_max", -1.0),
    (StoppingOptions, "land_tol", (0.1,)),
    (StoppingOptions, "m_dry", float("inf")),
    (LimitOptions, "thrust_limit", 0.0),
    (LimitOptions, "kind", "box"),
])
def test_options_name_the_bad_parameter(cls, name, bad):
    with pytest.raises(ParameterError) as e:
        cls(**{**GOOD[cls], name: bad})
    assert e.value.name.startswith({"kind": "limit"}.get(name, name))


@pytest.mark.parametrize("name, bad", [("rtol", 1e-14), ("atol", 0.0), ("max_step", -1.0),
                                       ("max_steps", 0), ("max_steps", 2.5)])
def test_dopri5_tolerances_checked(name, bad):
    kw = {**GOOD[IntegrationOptions], "method": "dopri5", name: bad}
    with pytest.raises(ParameterError) as e:
        IntegrationOptions(**kw)
    assert e.value.name == name
    kw["method"] = "rk4"  # not used by RK4: not checked
    IntegrationOptions(**kw)


def test_simulators_reject_a_misspelled_keyword():
    """Before any compilation: the keyword front and the option-object entry point."""
    from lgw.sim.mars.batch import simulate, simulate_batch
    from lgw.sim.mars.campaign import run_campaign
    from lgw.theory.mars.gains import default_gains

    r0, v0, m0 = np.zeros((1, 3)), np.zeros((1, 3)), np.array([1900.0])
    for fn in (simulate_batch, simulate, run_campaign):
        names = [p for p, v in inspect.signature(fn).parameters.items()
                 if v.kind is inspect.Parameter.KEYWORD_ONLY]
        assert names
        for name in names:
            with pytest.raises(TypeError, match="unexpected keyword|got an unexpected"):
                fn(r0, v0, m0, default_gains(), **{_misspell(name): 1})
