"""Every option of every command matters (in the spirit of python-control's kwargs_test.py).

For every command of every registered system (iterating the registry), every option either
changes what is computed, or is refused with a named error (exit 2, one ``error:`` line, before
any work).  "Changes what is computed" is decided on the command's ``Job``: the inputs of the
computation, reduced to a canonical digest by ``lgw.tuning.spec.fingerprint``.  The job planned
with the option set to its probe value (``lgw.tuning.spec.probe_value``: declared, or derived
from the type) must differ from the job planned without it; planning is cheap (no kernel, no
solver, no campaign).  Execution options (``--json``, ``--out``, ``--plot``, ``--workers``, ...)
change where or how results go: they must either change the job or be handled by the shared
command (``--json``, ``--out``, ``--plot``, ``--database``), and ``test_execution_options_change_
the_outcome`` shows the outcome does differ.

Each option is probed against two bases: the command's minimal valid options with ``--json``,
and with ``--out`` (an option may matter only where something is written).  An option refused
alone is also probed in a context where it applies (``CONTEXTS``), so that "refused alone,
ignored where it applies" is caught too.  An accepted option whose job is unchanged is a
defect: the test names it.  ``test_checker_flags_an_ignored_option`` is the checker's own
self-test (a toy command with an ignored option).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import pytest
from lgw.theory.errors import ParameterError
from lgw.tuning.options import Number
from lgw.tuning.spec import NO_PROBE, Options, fingerprint, option, option_fields, probe_value
from lgw.tuning.system import VERBS, Job, NotApplicable, Verb, all_systems
from lgw.tuning.vocabulary import PROBE_GAINS

from tests.test_cli_conventions import assert_one_error, run_lgw

# Execution options the shared command itself acts on (lgw.tuning.commands.run): --json prints
# the document, the output locations are checked before the work and written as a set.
SHARED_EXECUTION = {"--json", "--out", "--plot", "--database"}


def _states_csv(columns: str, row: str) -> Callable[[Path], Path]:
    def write(folder: Path) -> Path:
        p = Path(folder) / "probe_states.csv"
        p.write_text(f"{columns}\n{row}\n")
        return p
    return write


def _envelope_toml(var: str, lo: float, hi: float) -> Callable[[Path], Path]:
    def write(folder: Path) -> Path:
        p = Path(folder) / "probe_envelope.toml"
        p.write_text(f'[envelope]\nname = "probe"\n{var} = [{lo}, {hi}]\n')
        return p
    return write


def _tuned_file(folder: Path) -> Path:
    from lgw.tuning.mars.cmd_compare import probe_tuned_file

    return probe_tuned_file(folder)


# Probes the options declare NO_PROBE for (they name a resource): made here.  --scheduler is
# probed with the scheduler check stubbed (the check itself: tests/mars/test_inputs.py).
RESOURCE_PROBES: dict[tuple[str, str, str], Any] = {
    ("simulate", "mars", "--initial-states"): _states_csv("rx,ry,rz,vx,vy,vz,m",
                                                          "-1900,1000,1500,100,-15,-75,1905"),
    ("simulate", "eros", "--initial-states"): _states_csv("ex,ey,ez,vx,vy,vz",
                                                          "5,-4,3,0.1,0.2,-0.1"),
    ("simulate", "mars", "--scheduler"): "tcp://127.0.0.1:8786",
    ("report", "mars", "--tuned"): _tuned_file,
    ("verify", "mars", "--envelope"): _envelope_toml("rx", -1000.0, -500.0),
    ("verify", "lunar", "--envelope"): _envelope_toml("x1", 10.0, 20.0),
    ("verify", "eros", "--envelope"): _envelope_toml("ex", 1.0, 2.0),
}

# Where an option refused alone applies: field -> value set together with it (and in the
# reference job), so that its effect is shown there as well.
CONTEXTS: dict[tuple[str, str, str], dict[str, Any]] = {
    ("simulate", "mars", "--cases"): {"dispersion": "table2"},
    ("simulate", "mars", "--seed"): {"dispersion": "table2", "cases": 3},
    ("simulate", "mars", "--dist-amplitude"): {"disturbance": "sin"},
    ("simulate", "mars", "--limit"): {"thrust_max": 40_000.0},
    ("simulate", "mars", "--rtol"): {"method": "dopri5"},
    ("simulate", "mars", "--atol"): {"method": "dopri5"},
    ("simulate", "mars", "--max-step"): {"method": "dopri5"},
    ("simulate", "mars", "--scheduler-timeout"): {"scheduler": "tcp://127.0.0.1:8786"},
    ("simulate", "lunar", "--seed"): {"cases": 2},
    ("simulate", "eros", "--seed"): {"cases": 2},
    ("tune", "mars", "--a-max"): {"neighborhood": 500.0},
    ("tune", "mars", "--neighborhood"): {"a_max": 0.5},
    ("tune", "mars", "--theta1"): {"a_max": 0.5, "neighborhood": 500.0},
    ("tune", "mars", "--theta2"): {"a_max": 0.5, "neighborhood": 500.0},
    ("report", "mars", "--figures"): {"out": "<out>"},
    ("report", "mars", "--tuned"): {"out": "<out>"},
}
# probes that replace a declared or derived one where the context needs another value
CONTEXT_PROBES: dict[tuple[str, str, str], Any] = {
    ("tune", "mars", "--a-max"): 0.5, ("tune", "mars", "--neighborhood"): 500.0,
    ("tune", "mars", "--theta1"): 0.4, ("tune", "mars", "--theta2"): 0.4,
}


# Execution options acted on while planning (a check before any work), not in the job: the
# option's value must reach that check.  --scheduler-timeout bounds the --scheduler handshake.
SCHEDULER_CALLS: list[tuple[Any, ...]] = []
PLAN_TIME = {("simulate", "mars", "--scheduler-timeout"):
             lambda val: any(c[1:] == (val,) for c in SCHEDULER_CALLS)}


@dataclass
class Finding:
    flag: str
    base: str  # "json" | "out" | "context"
    verdict: str  # changes | refused | shared-execution | IGNORED | not-probed
    detail: str = ""
    args: list[str] = dataclasses.field(default_factory=list)  # the CLI form, for refusals


def _out_value(cls: type[Options], folder: Path) -> Path | None:
    for _f, o in option_fields(cls):
        if o.flag == "--out":
            kind = getattr(o.type, "kind", "dir")
            return folder / ("out.toml" if kind == "file" else "out")
    return None


def _complete(cls: type[Options], kw: dict[str, Any], folder: Path, system: str,
              verb: str) -> dict[str, Any]:
    """``kw`` plus the required options (each set to its probe), until the object builds."""
    flags = {o.flag: (f, o) for f, o in option_fields(cls)}
    for _ in range(len(flags) + 1):
        try:
            cls(**kw)
            return kw
        except ParameterError as e:
            if "required" not in e.valid or e.name not in flags or \
                    flags[e.name][0].name in kw:
                raise
            f, o = flags[e.name]
            kw[f.name] = _out_value(cls, folder) if o.flag == "--out" else \
                _probe(f, o, folder, system, verb)
    raise AssertionError(f"{verb} {system}: cannot build default options")


def _probe(f: dataclasses.Field, o: Any, folder: Path, system: str, verb: str) -> Any:
    key = (verb, system, o.flag)
    if o.flag in ("--out", "--plot", "--database"):  # output locations: a new path
        kind = getattr(o.type, "kind", "dir")
        return folder / (o.flag.strip("-") + (".toml" if kind == "file" else ""))
    if key in RESOURCE_PROBES:
        val = RESOURCE_PROBES[key]
    elif o.probe is NO_PROBE:
        try:  # an option naming a resource may still be refused alone with a derived value
            val = probe_value(f, dataclasses.replace(o, probe=None))
        except LookupError:
            return NO_PROBE
    elif o.probe == PROBE_GAINS:
        val = folder / "probe_gains.toml"
        if not val.exists():
            from lgw.tuning.system import get_system

            val.write_text(get_system(system).gains_module().example())
    else:
        val = probe_value(f, o)
    if callable(val):
        val = val(folder)
    return (val,) if o.multiple and not isinstance(val, tuple) else val


def _cli_args(cls: type[Options], kw: dict[str, Any]) -> list[str]:
    """The command line that builds ``cls(**kw)``."""
    args: list[str] = []
    for f, o in option_fields(cls):
        if f.name not in kw:
            continue
        v = kw[f.name]
        if o.secondary is not None:
            args.append(o.flag if v else o.secondary)
        elif o.is_flag:
            if v:
                args.append(o.flag)
        elif o.multiple:
            for x in v:
                args += [o.flag, str(x)]
        elif v is not None:
            args += [o.flag, str(v)]
    return args


def _job(mod: Any, system: Any, kw: dict[str, Any]) -> Any:
    return mod.plan(mod.Options(**kw), system)


def check_options(mod: Any, system: Any, folder: Path, verb: str = "toy",
                  system_name: str = "toy") -> list[Finding]:
    """Probe every option of ``mod.Options`` (see the module docstring); one finding per
    option and base."""
    cls = mod.Options
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    names = {f.name for f, _ in option_fields(cls)}
    out_value = _out_value(cls, folder)
    bases = {"json": {"json": True}} if "json" in names else {"none": {}}
    if out_value is not None:
        bases["out"] = {"out": out_value}
    findings: list[Finding] = []
    for bname, base in bases.items():
        base = _complete(cls, dict(base), folder, system_name, verb)
        ref = fingerprint(_job(mod, system, base))
        assert ref == fingerprint(_job(mod, system, base)), \
            f"{verb} {system_name}: planning is not deterministic (fingerprint varies)"
        for f, o in option_fields(cls):
            if f.name in base:
                continue
            val = _probe(f, o, folder, system_name, verb)
            if val is NO_PROBE:
                findings.append(Finding(o.flag, bname, "not-probed", "names a resource"))
                continue
            findings.append(_probe_one(mod, system, base, ref, f, o, val, bname,
                                       (verb, system_name, o.flag)))
            ctx_key = (verb, system_name, o.flag)
            if findings[-1].verdict == "refused" and ctx_key in CONTEXTS and bname != "out":
                ctx = {k: (out_value if v == "<out>" else v)
                       for k, v in CONTEXTS[ctx_key].items()}
                cbase = {**base, **ctx}
                cval = CONTEXT_PROBES.get(ctx_key, val)
                cref_kw = {**cbase}
                if f.name in cbase:  # the context sets the option itself: compare with none
                    cref_kw.pop(f.name)
                try:
                    cref = fingerprint(_job(mod, system, _complete(cls, cref_kw, folder,
                                                                   system_name, verb)))
                except ParameterError:  # options that go together: against the base job
                    cref = ref
                fc = _probe_one(mod, system, cbase, cref, f, o, cval, "context", ctx_key)
                if fc.verdict == "refused":
                    fc = dataclasses.replace(fc, verdict="IGNORED", detail="refused even in "
                                             f"its context {ctx}: {fc.detail}")
                findings.append(fc)
    return findings


def _probe_one(mod: Any, system: Any, base: dict[str, Any], ref: str,
               f: dataclasses.Field, o: Any, val: Any, bname: str,
               key: tuple[str, str, str] = ("", "", "")) -> Finding:
    kw = {**base, f.name: val}
    SCHEDULER_CALLS.clear()
    try:
        job = _job(mod, system, kw)
    except ParameterError as e:
        return Finding(o.flag, bname, "refused", str(e), _cli_args(mod.Options, kw))
    if fingerprint(job) != ref:
        return Finding(o.flag, bname, "changes", f"{o.flag} {val!r}")
    if o.execution and o.flag in SHARED_EXECUTION:
        return Finding(o.flag, bname, "shared-execution", "acted on by lgw.tuning.commands")
    if o.execution and key in PLAN_TIME and PLAN_TIME[key](val):
        return Finding(o.flag, bname, "plan-time", "reaches the check made while planning")
    return Finding(o.flag, bname, "IGNORED", f"{o.flag} {val!r} accepted; the job is the "
                   "same as without it")


# --- every command of every system -----------------------------------------------------------

def _commands() -> list[Any]:
    params = []
    for s in all_systems():
        for verb in VERBS:
            v = s.verbs.get(verb)
            if v is None or isinstance(v, NotApplicable):
                continue
            params.append(pytest.param(verb, s.name, id=f"{verb}-{s.name}"))
    return params


COMMANDS = _commands()
SUMMARY: dict[str, dict[str, int]] = {}


@pytest.fixture
def stub_scheduler(monkeypatch):
    import lgw.tuning.options as topt

    def check(*a, **k):
        SCHEDULER_CALLS.append(a + tuple(k.values()))
        return {"type": "Scheduler"}

    monkeypatch.setattr(topt, "check_scheduler", check)


@pytest.mark.parametrize("verb, system", COMMANDS)
def test_every_option_changes_the_job_or_is_refused(verb, system, tmp_path, stub_scheduler):
    from lgw.tuning.system import get_system

    s = get_system(system)
    v = s.verbs[verb]
    assert isinstance(v, Verb)
    mod = v.load()
    findings = check_options(mod, s, tmp_path, verb, system)
    counts: dict[str, int] = {}
    for fd in findings:
        counts[fd.verdict] = counts.get(fd.verdict, 0) + 1
    SUMMARY[f"{verb} {system}"] = counts
    print(f"\n{verb} {system}: {len(list(option_fields(mod.Options)))} options, "
          + ", ".join(f"{k} {n}" for k, n in sorted(counts.items())))
    ignored = [f"{fd.flag} [{fd.base}]: {fd.detail}" for fd in findings
               if fd.verdict == "IGNORED"]
    assert not ignored, f"lgw {verb} {system}: accepted and ignored:\n" + "\n".join(ignored)
    unprobed = [fd.flag for fd in findings if fd.verdict == "not-probed"]
    assert not unprobed, f"lgw {verb} {system}: options never probed: {unprobed} (declare a " \
        "probe or add one to RESOURCE_PROBES)"
    # a refusal is a named error through the real command line: exit 2, one line, before work
    seen = set()
    for fd in findings:
        if fd.verdict != "refused" or fd.flag in seen:
            continue
        seen.add(fd.flag)
        r = run_lgw([verb, system, *fd.args])
        assert_one_error(r)
        assert "internal error" not in r.stderr


@pytest.mark.parametrize("system", ["mars", "lunar", "eros"])
def test_execution_options_change_the_outcome(system, tmp_path):
    """--json prints the document instead of the table; --out writes it (bounds: cheap)."""
    import json

    as_json = run_lgw(["bounds", system, "--json"])
    out = tmp_path / "o"
    written = run_lgw(["bounds", system, "--out", str(out)])  # the table, and the file
    assert as_json.code == written.code == 0, (as_json.stderr, written.stderr)
    assert written.stdout != as_json.stdout and not written.stdout.lstrip().startswith("{")
    doc = json.loads(as_json.stdout)
    assert doc["command"] == f"bounds {system}"
    assert not (tmp_path / "x").exists() and (out / "bounds.json").is_file()
    assert json.loads((out / "bounds.json").read_text()) == doc


def test_every_verb_is_probed():
    """The registry's Verbs are all in COMMANDS."""
    ids = {p.id for p in COMMANDS}
    for s in all_systems():
        for verb, v in s.verbs.items():
            if isinstance(v, Verb):
                assert f"{verb}-{s.name}" in ids


# --- the checker's own self-test ---------------------------------------------------------------

@dataclass(frozen=True)
class ToyOptions(Options):
    used: float = option("--used", Number(0, 10), 1.0, "goes into the job")
    ignored: float = option("--ignored", Number(0, 10), 1.0, "accepted, never used")
    refused: bool = option("--refused", None, False, "never applies here", is_flag=True)
    shown: bool = option("--json", None, False, "print JSON", is_flag=True, execution=True)

    def check(self) -> None:
        super().check()
        self.refuse_unless(False, "refused", "does not apply to the toy")


@dataclass(frozen=True)
class ToyJob(Job):
    used: float


def test_checker_flags_an_ignored_option(tmp_path):
    toy = SimpleNamespace(Options=ToyOptions, plan=lambda opts, system: ToyJob(opts.used))
    found = {(f.flag, f.base): f.verdict for f in check_options(toy, None, tmp_path)}
    assert found == {("--used", "none"): "changes", ("--ignored", "none"): "IGNORED",
                     ("--refused", "none"): "refused", ("--json", "none"): "shared-execution"}


def test_checker_sees_an_option_ignored_where_it_applies(tmp_path):
    """An option refused alone but ignored in its context is flagged too."""

    @dataclass(frozen=True)
    class Opts(Options):
        mode: str = option("--mode", None, "a", "a or b", probe="b")
        level: float = option("--level", Number(0, 10), 1.0, "only with --mode b")

        def check(self) -> None:
            super().check()
            self.refuse_unless(self.mode == "b", "level", "needs --mode b")

    @dataclass(frozen=True)
    class J(Job):
        mode: str

    toy = SimpleNamespace(Options=Opts, plan=lambda opts, system: J(opts.mode))
    CONTEXTS[("toy", "toy", "--level")] = {"mode": "b"}
    try:
        found = {(f.flag, f.base): f.verdict for f in check_options(toy, None, tmp_path)}
    finally:
        CONTEXTS.pop(("toy", "toy", "--level"))
    assert found[("--level", "none")] == "refused"
    assert found[("--level", "context")] == "IGNORED"
    assert found[("--mode", "none")] == "changes"
