"""The ``System`` interface: what one paper contributes to the workbench, and the registry.

Each system registers one ``System`` (``lgw.tuning.<name>.system.SYSTEM``).  Its parts come
from every floor of that system: the gain set (``lgw.theory.<name>``: the loader, the default,
the claims and bounds), the simulator (``lgw.sim.<name>``), and on this floor the verify spec,
the tuner, the comparison scenario, the figures and the report sections.  The verbs
(``lgw.tuning.commands``) are written once over this interface: a system supplies, per verb, an
options class (``lgw.tuning.spec.Options``) and a ``plan`` function that turns validated
options into a ``Job``, whose ``run`` returns an ``Outcome``.  The shared command does the rest
for every system alike: the click options, checking outputs before the work, progress,
warnings, JSON, tables, files written as one atomic set, exit codes.

A verb that cannot apply to a system is a ``NotApplicable`` with the reason, shown in
``--help`` and given with exit 2.  Parts are named by import path and loaded on use, so
``lgw --help`` and option errors answer before SymPy, numba or cvxpy load.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cache
from typing import Any

from lgw.theory.errors import NotApplicableError, ParameterError
from lgw.theory.sections import Figure  # noqa: F401  (one figure record for every layer)

# exit codes of every verb (documented in tuning/cli.py and docs/cli.md)
EXIT_OK = 0
EXIT_VIOLATED = 1  # verify: a claim is violated
EXIT_USAGE = 2  # bad input: nothing computed, nothing written
EXIT_INFEASIBLE = 3  # tune: no gain set meets the target
EXIT_INCONCLUSIVE = 4  # verify: not enough informative evidence
EXIT_INTERRUPTED = 130  # Ctrl-C (128 + SIGINT)
VERIFY_EXIT = {"holds": EXIT_OK, "violated": EXIT_VIOLATED, "inconclusive": EXIT_INCONCLUSIVE,
               "not-applicable": EXIT_OK}

VERBS = {
    "bounds": "Settling-time, neighbourhood and landing-time bounds for a gain set.",
    "simulate": "Fly the closed loop: one case, a Monte Carlo campaign or a states file.",
    "verify": "Property campaign: observed behaviour against every proven bound.",
    "tune": "Design gains for a target and an actuator limit, with a certificate.",
    "report": "Derive and judge every claim of the paper; write the report.",
    "compare": "The paper's own comparison of laws on its own scenario.",
    "optimal": "Offline fuel-optimal baseline (lossless convexification).",
    "warmup": "Build and cache every compiled kernel of a system in one step.",
}
# verbs that, given no SYSTEM, run for every system in turn (lgw.tuning.commands)
EVERY_SYSTEM_VERBS = ("warmup",)


@dataclass
class Outcome:
    """What a job computed, in the forms the shared command emits.

    ``document``: the JSON payload (the command adds ``lgw_version``, ``command``, ``gains``
    first); a value that is a ``Stream`` is written item by item (flat memory).
    ``render(console)``: the terminal output (tables and lines).  ``files``: name -> text,
    bytes or a ``Stream`` writer, written as one atomic set into ``--out``.  ``figures``:
    written into ``--plot`` (or beside the files).  ``exit_code``: 0, or 1/3/4 as documented.
    ``flags``: warnings the command prints after the output (unconverged numbers, ...).
    ``stderr``: lines for stderr whatever the output mode (why a target is infeasible, ...)."""

    document: dict[str, Any]
    render: Callable[[Any], None] | None = None
    files: dict[str, Any] = field(default_factory=dict)
    figures: list[Figure] = field(default_factory=list)
    exit_code: int = EXIT_OK
    flags: list[str] = field(default_factory=list)
    stderr: list[str] = field(default_factory=list)


class Job:
    """The inputs of one computation (a frozen dataclass in practice) and ``run``.

    ``run(progress)`` computes and returns an ``Outcome``; ``progress`` is a
    ``lgw.tuning.progress.Progress`` (``progress.stage(text)``, ``progress.advance(n, total)``).
    A ``gains`` attribute, when present, is the gain set used (the document's ``gains``)."""

    def run(self, progress: Any) -> Outcome:  # pragma: no cover - every job overrides it
        raise NotImplementedError


@dataclass(frozen=True)
class Verb:
    """One verb of one system: ``module`` (import path) defines ``Options`` (an
    ``lgw.tuning.spec.Options`` subclass) and ``plan(options) -> Job``; ``help`` is the
    one-line text of ``lgw VERB --help``.  ``inputs(options)`` (optional, in the module) lists
    the files a run reads, so that no output may replace one."""

    module: str
    help: str

    def load(self) -> Any:
        return importlib.import_module(self.module)


@dataclass(frozen=True)
class NotApplicable:
    """A verb that does not apply to a system, and why (shown in --help, exit 2)."""

    reason: str


@dataclass(frozen=True)
class System:
    """One paper's contribution.  ``verbs``: verb -> ``Verb`` or ``NotApplicable``.
    ``gains``: import path of a module with ``load(path) -> Gains`` and ``default() ->
    Gains``; ``claims``: import path of ``all_claims(gains)``; ``interop``: of the
    python-control blocks (``plant()``, ``law(gains)``); ``kernels``: of
    ``warmup_kernels() -> [(name, build)]``, the system's compiled kernels (``lgw warmup``)."""

    name: str
    seed: str
    title: str
    summary: str
    gains: str
    verbs: Mapping[str, Verb | NotApplicable]
    claims: str = ""
    interop: str = ""
    kernels: str = ""

    def verb(self, verb: str) -> Verb:
        v = self.verbs.get(verb)
        if v is None:
            raise ParameterError("VERB", verb, f"one of {', '.join(VERBS)}")
        if isinstance(v, NotApplicable):
            raise NotApplicableError(verb, self.name, v.reason)
        return v

    def gains_module(self) -> Any:
        return importlib.import_module(self.gains)


def system_names() -> tuple[str, ...]:
    from lgw import SYSTEMS

    return tuple(SYSTEMS)


@cache
def get_system(name: str) -> System:
    """The registered system ``name`` (its ``lgw.tuning.<name>.system.SYSTEM``)."""
    if name not in system_names():
        raise ParameterError("SYSTEM", name, f"one of {', '.join(system_names())}")
    return importlib.import_module(f"lgw.tuning.{name}.system").SYSTEM


def all_systems() -> list[System]:
    return [get_system(n) for n in system_names()]


def resolve(path: str) -> Any:
    """``"pkg.module:attr"`` -> the attribute (parts named by path load on use)."""
    mod, _, attr = path.partition(":")
    obj = importlib.import_module(mod)
    return getattr(obj, attr) if attr else obj


def check_consistent(systems: Iterable[System] | None = None) -> list[str]:
    """Problems of the registry (for the tests): every system names every verb, every module
    loads and defines ``Options`` and ``plan``."""
    problems = []
    for s in systems or all_systems():
        for verb in VERBS:
            v = s.verbs.get(verb)
            if v is None:
                problems.append(f"{s.name}: verb {verb} neither implemented nor not-applicable")
            elif isinstance(v, Verb):
                m = v.load()
                for attr in ("Options", "plan"):
                    if not hasattr(m, attr):
                        problems.append(f"{s.name} {verb}: {v.module} has no {attr}")
    return problems


def names(items: Sequence[Any]) -> str:
    return ", ".join(str(i) for i in items)


WARMUP = Verb("lgw.tuning.cmd_warmup", "build and cache every compiled kernel in one step")


def laid_out_system(name: str, seed: str, title: str, summary: str,
                    **verbs: str | NotApplicable) -> System:
    """The ``System`` of a system laid out as the workbench lays out every system: its parts
    at their standard paths (``lgw.tuning.<name>.gainset``, ``lgw.theory.<name>.claims:
    all_claims``, ``lgw.sim.<name>.interop``, ``lgw.sim.<name>.batch:warmup_kernels``), each
    verb in ``lgw.tuning.<name>.cmd_<verb>``.  ``verbs``: verb -> its one-line help, or a
    ``NotApplicable`` with the reason; ``warmup`` is the shared one unless given."""
    unknown = set(verbs) - set(VERBS)
    if unknown:
        raise ParameterError("verbs", ", ".join(sorted(unknown)), f"one of {', '.join(VERBS)}")
    table: dict[str, Verb | NotApplicable] = {"warmup": WARMUP}
    for verb, v in verbs.items():
        table[verb] = v if isinstance(v, NotApplicable) else Verb(
            f"lgw.tuning.{name}.cmd_{verb}", v)
    return System(name=name, seed=seed, title=title, summary=summary,
                  gains=f"lgw.tuning.{name}.gainset",
                  verbs={verb: table[verb] for verb in VERBS if verb in table},
                  claims=f"lgw.theory.{name}.claims:all_claims",
                  interop=f"lgw.sim.{name}.interop",
                  kernels=f"lgw.sim.{name}.batch:warmup_kernels")


@dataclass(frozen=True)
class Call(Job):
    """A job that is one call of a system's function: ``fn`` (import path of
    ``fn(gains, progress, **args) -> Outcome``) with the gain set and the keyword
    arguments that, beside the gains, decide what is computed."""

    fn: str
    gains: Any
    args: Mapping[str, Any] = field(default_factory=dict)

    def run(self, progress: Any) -> Outcome:
        return resolve(self.fn)(self.gains, progress, **self.args)


CARD_KEYS = ("seed", "title", "summary", "verbs", "not_applicable")


def carded_system(name: str) -> System:
    """The ``System`` of ``name`` from its card, ``lgw/tuning/<name>/data/system.toml``: what
    ``lgw`` shows of the system (``seed``, ``title``, ``summary``, ``[verbs]``: verb -> the
    one-line help, ``[not_applicable]``: verb -> why), its parts at the standard paths
    (``laid_out_system``).  The card is prose, read without importing any part."""
    import tomllib
    from importlib import resources

    path = resources.files(f"lgw.tuning.{name}").joinpath("data", "system.toml")
    return system_of_card(name, tomllib.loads(path.read_text("utf-8")),
                          f"lgw.tuning.{name} data/system.toml")


def system_of_card(name: str, card: Mapping[str, Any], where: str) -> System:
    """The ``System`` a card describes (``carded_system``); ``where`` names the card in the
    errors: an unknown key, a verb both applicable and not, an unknown verb."""
    unknown = sorted(set(card) - set(CARD_KEYS))
    if unknown:
        raise ParameterError(where, ", ".join(unknown), f"keys are {', '.join(CARD_KEYS)}")
    verbs: dict[str, str | NotApplicable] = dict(card.get("verbs", {}))
    for verb, reason in card.get("not_applicable", {}).items():
        if verb in verbs:
            raise ParameterError(where, verb, "a verb is either in [verbs] or in "
                                 "[not_applicable], not both")
        verbs[verb] = NotApplicable(reason)
    return laid_out_system(name, card["seed"], card["title"], card["summary"], **verbs)
