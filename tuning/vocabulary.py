"""One vocabulary for every verb of every system: the same concept, the same flag, unit and
meaning.  Each function returns an options field (``lgw.tuning.spec.option``) with the flag,
type, unit and help fixed here; a system chooses only its default (and, where physics bounds
it, the range).  ``tests/test_options.py`` checks that a flag means the same field and unit in
every system.

    --gains FILE        the gain set (TOML)            --json        one JSON document on stdout
    --out DIR|FILE      where the output set goes      --plot DIR    figures (PNG)
    --t-max S           horizon (s)                    --dt S        RK4 step / sampling (s)
    --method M          rk4 | dopri5                   --rtol/--atol dopri5 tolerances
    --cases N           Monte Carlo cases              --seed S      numpy SeedSequence seed
    --initial-states F  CSV of initial states          --workers N / --scheduler ADDR   dask
    --thrust-max N      actuator limit (N)             --scale CLAIM=FACTOR   bound scaling
    --sim/--no-sim      fly the paper's scenario (report)
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lgw.tuning.options import (
    DIR,
    FILE,
    SCHEDULER_TIMEOUT,
    SEED,
    Integer,
    Number,
    ScaleItem,
    choice,
)
from lgw.tuning.spec import NO_PROBE, Options, option

METHODS = ("rk4", "dopri5")
PROFILES = ("ci", "thorough")
MAX_CASES = 10**7  # campaigns stream in chunks; memory is estimated before the run
PROBE_GAINS = "<probe gains>"  # the options test writes the system's example gain set here


def gains(help_extra: str = "") -> Any:
    return option("--gains", FILE, None,
                  "gains TOML file (UTF-8; the system's keys, see its docs) [default: the "
                  f"system's built-in gain set]{help_extra}", probe=PROBE_GAINS)


def json_flag() -> Any:
    return option("--json", None, False, "print one JSON document (strict JSON; schema: "
                  "docs/json.md)", is_flag=True, execution=True)


def out_dir(files: str) -> Any:
    return option("--out", DIR, None, f"output folder for {files}: a new or empty folder, or "
                  "one lgw wrote before (replaced as a whole); checked before any work, "
                  "written atomically", execution=True)


def out_file(what: str, required: bool = False) -> Any:
    return option("--out", FILE, None, f"the file to write ({what}); checked before any "
                  "work, written atomically" + ("" if not required else " [required]"),
                  execution=True)


def plot_dir(what: str) -> Any:
    return option("--plot", DIR, None, f"write figures (PNG) to DIR: {what}", execution=True)


def t_max(default: float | None, what: str = "simulation horizon", hi: float = 1e7) -> Any:
    return option("--t-max", Number(0, hi, lo_open=True, unit="s"), default,
                  f"{what}, s" + ("" if default is not None else " [default: the scenario's]"))


def dt(default: float | None, hi: float = 1.0, what: str = "RK4 step; dopri5: first step",
       probe: Any = None) -> Any:
    """``probe``: a value for the options test when the derived one (the middle of the range)
    could be the default the system chooses."""
    return option("--dt", Number(0, hi, lo_open=True, unit="s"), default, f"{what}, s",
                  probe=probe)


def method(default: str = "rk4") -> Any:
    return option("--method", choice(METHODS), default,
                  "integrator: rk4 (fixed step) or dopri5 (adaptive Dormand-Prince 5(4))")


def rtol(default: float) -> Any:
    return option("--rtol", Number(1e-13, 1e-1), default, "dopri5 relative tolerance "
                  "(only with --method dopri5)")


def atol(default: float, unit: str) -> Any:
    return option("--atol", Number(0, lo_open=True, unit=unit), default,
                  f"dopri5 absolute tolerance ({unit}; only with --method dopri5)")


def cases(default: int | None, what: str = "Monte Carlo cases") -> Any:
    return option("--cases", Integer(1, MAX_CASES, "cases"), default,
                  f"{what} (memory is estimated before the run)", probe=3)


def seed(default: int = 0, what: str = "seed of the campaign") -> Any:
    return option("--seed", SEED, default, f"{what} (numpy SeedSequence); integer in "
                  "[0, 2^64 - 1]")


def initial_states(columns: str) -> Any:
    return option("--initial-states", FILE, None, f"CSV of initial states, header {columns} "
                  "(UTF-8, one case per row)", probe=NO_PROBE)


def thrust_max(default: float | None, what: str) -> Any:
    return option("--thrust-max", Number(0, 1e9, lo_open=True, unit="N"), default,
                  f"actuator limit, N: {what}")


# specific impulse, s: 1 s is far below any engine (cold gas ~60 s) and keeps the mass flow
# T/(Isp g0) and the SOCP's 1/(Isp g0) finite; 1e5 s is above any (ion thrusters ~1e4 s)
ISP_RANGE = (1.0, 1e5)


def isp(default: float | None, what: str = "specific impulse, s") -> Any:
    return option("--isp", Number(*ISP_RANGE, unit="s"), default, what)


def scale() -> Any:
    return option("--scale", ScaleItem(), (), "CLAIM=FACTOR: multiply a claim's bound (the "
                  "checker's self-test; repeatable)", multiple=True, probe=NO_PROBE)


def sim_toggle(default: bool, what: str) -> Any:
    return option("--sim", None, default, f"fly the paper's scenario: {what}",
                  secondary="--no-sim")


@dataclass(frozen=True)
class Dask(Options):
    """Where a campaign runs: in-process (default), a local dask cluster, or a scheduler."""

    workers: int | None = option("--workers", Integer(1, 1024, "dask workers"), None,
                                 "run on a dask LocalCluster with N single-threaded workers "
                                 "[default: in-process]; not with --scheduler", execution=True,
                                 probe=2)
    scheduler: str | None = option("--scheduler", None, None, "address of a running dask "
                                   "scheduler (tcp://host:port), checked before any work",
                                   execution=True, probe=NO_PROBE)
    scheduler_timeout: float = option("--scheduler-timeout", Number(0, 600, lo_open=True,
                                                                     unit="s"),
                                      SCHEDULER_TIMEOUT, "seconds to wait for --scheduler",
                                      execution=True, probe=NO_PROBE)

    def check(self) -> None:
        super().check()
        self.refuse_unless(self.workers is None or self.scheduler is None, "workers",
                           "cannot be combined with --scheduler (the scheduler's cluster "
                           "decides the workers); give one of them")
        self.refuse_unless(self.scheduler is not None, "scheduler_timeout",
                           "only applies with --scheduler")


@dataclass(frozen=True)
class VerifyRun(Options):
    """The run options of every ``lgw verify SYSTEM`` (Hypothesis campaign)."""

    profile: str = option("--profile", choice(PROFILES), "ci",
                          "ci: the CI budget; thorough: a longer campaign (examples per "
                          "profile in the system's docs)")
    seed: int = seed(0, "derandomised run with this seed (Hypothesis)")
    random: bool = option("--random", None, False, "a random run (not with --seed)",
                          is_flag=True)
    examples: int | None = option("--examples", Integer(1, 100_000, "examples"), None,
                                  "Hypothesis examples per claim group [default: the "
                                  "profile's]", probe=2)
    min_cases: int = option("--min-cases", Integer(1, 10**7, "cases"), 30,
                            "informative checked cases a claim needs for 'holds'")
    database: Path | None = option("--database", DIR, None,
                                   "Hypothesis example database folder: replays earlier "
                                   "failures first and saves new ones; makes the run random",
                                   probe=NO_PROBE)
    scale: tuple = scale()

    def check(self) -> None:
        super().check()
        self.refuse_unless(not self.random, "seed", "cannot be combined with --random")
        self.refuse_unless(self.database is None, "seed", "cannot be combined with "
                           "--database (a database makes the run random: Hypothesis uses "
                           "no database in a seeded run)")

    @property
    def run_seed(self) -> int | None:
        return None if self.random or self.database is not None else self.seed

    def scale_map(self) -> dict[str, float]:
        return dict(self.scale)


def declare(cls: type, name: str, annotation: str, value: Any, *, first: bool = False) -> None:
    """Declare option field ``name`` in the class body of ``cls`` (before ``@dataclass``
    runs): a field already declared by a base keeps its place; a new one goes last, or first
    of the class's own fields with ``first``."""
    own = dict(cls.__dict__.get("__annotations__", {}))
    own.pop(name, None)
    cls.__annotations__ = {name: annotation, **own} if first else {**own, name: annotation}
    setattr(cls, name, value)


@dataclass(frozen=True)
class Outputs(Options):
    """--gains, --json and --out, declared once for every verb that computes for a gain set
    and writes what it computed, and --plot where the verb draws.  What differs between verbs
    and systems is only text, given as keywords of the class statement::

        @dataclass(frozen=True)
        class Options(V.Outputs, out="bounds.json (the --json document)"): ...

    ``out``: the files --out holds (declares --out); ``plot``: the figures (declares
    --plot); ``gains``: the end of --gains' help."""

    gains: Path | None = gains()
    json: bool = json_flag()

    def __init_subclass__(cls, *, out: str | None = None, plot: str | None = None,
                          gains: str | None = None, **kw: Any) -> None:
        super().__init_subclass__(**kw)
        if gains is not None:
            declare(cls, "gains", "Path | None", _gains(gains))
        if out is not None:
            declare(cls, "out", "Path | None", out_dir(out))
        if plot is not None:
            declare(cls, "plot", "Path | None", plot_dir(plot))


_gains = gains


@dataclass(frozen=True)
class BoundsOptions(Outputs, out="bounds.json (the --json document)"):
    """The options every ``lgw bounds SYSTEM`` takes (a system adds its own)."""
