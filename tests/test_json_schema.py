"""Every verb's JSON document against its JSON Schema (lgw.tuning.schemas), and docs/json.md
generated from the schemas.

Each applicable verb of each system (iterating the registry) runs for real on a cheap
configuration with --json (and --out where the document is also a file there); the document on
stdout and its copy under --out are validated.  The cases that take more than ~20 s warm
(every report, tune mars, compare mars) are marked slow.  A schema that accepts anything
would pass too, so ``test_schemas_reject_broken_documents`` breaks valid documents in the ways
that matter (a head key missing, a wrong type, an unknown key, an impossible value) and
requires a violation for each.
"""

from __future__ import annotations

import copy
import json
from pathlib import Path

import pytest
from lgw.tuning import schemas as S
from lgw.tuning.system import NotApplicable, Verb, all_systems

from tests.test_cli_conventions import run_lgw

ROOT = Path(__file__).resolve().parents[1]
SLOW = pytest.mark.slow

# (verb, system) -> runs: (arguments after `lgw VERB SYSTEM`, expected exit code, the file
# under --out that holds the same document or None, marks)
RUNS = {
    ("bounds", "mars"): [([], 0, "bounds.json", ())],
    ("bounds", "lunar"): [(["--eq0-min", "0.9"], 0, "bounds.json", ())],
    ("bounds", "eros"): [(["--dbar", "0.5"], 0, "bounds.json", ())],
    ("simulate", "mars"): [([], 0, None, ()), (["--fig6", "--t-max", "40"], 0, "fig6.json", ())],
    ("simulate", "lunar"): [(["--t-max", "2"], 0, "summary.json", ())],
    ("simulate", "eros"): [(["--law", "fuzzy-sign", "--t-max", "2"], 0, "simulate.json", ())],
    ("optimal", "mars"): [(["--n", "20"], 0, "optimal.json", ()),
                          (["--n", "20", "--min-tf", "--no-replay"], 0, "optimal.json", ())],
    ("tune", "eros"): [(["--ts", "10", "--thrust-max", "30", "--fresh-cases", "5"], 3, None,
                        ()),
                       (["--ts", "30", "--thrust-max", "400", "--fresh-cases", "5"], 0, None,
                        ())],
    ("tune", "mars"): [(["--law", "bounded", "--tf", "5", "--thrust-max", "50000",
                         "--no-suggest"], 3, None, (SLOW,)),
                       (["--law", "bounded", "--tf", "120", "--thrust-max", "50000"], 0, None,
                        (SLOW,))],
    ("report", "lunar"): [(["--no-sim"], 0, None, (SLOW,))],
    ("report", "mars"): [([], 0, None, (SLOW,))],
    ("report", "eros"): [(["--no-sim"], 0, None, (SLOW,))],
    ("verify", "lunar"): [(["--examples", "3", "--min-cases", "1"], 0, None, ())],
    ("verify", "eros"): [(["--examples", "3", "--min-cases", "1"], 0, None, ())],
    ("verify", "mars"): [(["--examples", "2", "--min-cases", "1", "--claim", "reaching-16"],
                          0, None, (SLOW,))],
    ("compare", "mars"): [(["--law", "bounded", "--dist-amplitude", "1", "--n", "20"], 0,
                           "compare.json", (SLOW,))],
    # the session's warm-up (tests/conftest.py) built every kernel: these only load them
    ("warmup", "mars"): [([], 0, None, ())],
    ("warmup", "lunar"): [([], 0, None, ())],
    ("warmup", "eros"): [([], 0, None, ())],
}


def _verbs() -> list[tuple[str, str, object]]:
    return [(verb, s.name, v) for s in all_systems() for verb, v in s.verbs.items()
            if not isinstance(v, NotApplicable)]


def _cases() -> list[object]:
    out = []
    for verb, system, _v in _verbs():
        for i, (args, code, file, marks) in enumerate(RUNS.get((verb, system), [])):
            out.append(pytest.param(verb, system, args, code, file,
                                    id=f"{verb}-{system}-{i}", marks=list(marks)))
    return out


def _strict(text: str):
    def no(name: str):
        raise AssertionError(f"non-strict JSON token {name}")
    return json.loads(text, parse_constant=no)


def test_schemas_are_valid_draft_2020_12():
    assert S.check_schemas() == []


def test_every_verb_has_a_schema_and_runs_here():
    """Each Verb of the registry has its schema file and at least one run above; each schema
    belongs to a Verb."""
    verbs = {(verb, system) for verb, system, v in _verbs() if isinstance(v, Verb)}
    names = set(S.names())
    missing = sorted(f"{v}.{s}" for v, s in verbs if f"{v}.{s}" not in names)
    assert not missing, f"no schema in tuning/schemas/ for {missing}"
    orphans = sorted(n for n in names if tuple(n.split(".")) not in verbs)
    assert not orphans, f"schemas of no Verb: {orphans}"
    untested = sorted(f"{v} {s}" for v, s in verbs if not RUNS.get((v, s)))
    assert not untested, f"add a run to RUNS for {untested}"


@pytest.mark.parametrize("verb, system, args, code, file", _cases())
def test_document_validates_against_its_schema(verb, system, args, code, file, tmp_path):
    out_args: list[str] = []
    out = None
    if file is not None:
        out = tmp_path / "out"
        out_args = ["--out", str(out)]
    elif verb == "tune":
        out_args = ["--out", str(tmp_path / "gains.toml")]
    r = run_lgw([verb, system, *args, "--json", *out_args])
    assert r.exception is None and r.code == code, (r.code, r.stderr[-800:])
    doc = _strict(r.stdout)
    assert list(doc)[:3] == ["lgw_version", "command", "gains"]
    assert doc["command"] == f"{verb} {system}"
    S.validate(doc)
    if file is not None:
        on_disk = _strict((out / file).read_text())
        S.validate(on_disk)
        assert on_disk == doc


def _valid(name: str) -> dict:
    """A small valid document of ``name`` for the negative test (checked valid first)."""
    gains = {"beta1": [2.8] * 3, "beta2": [4e-4] * 3, "alpha1": [0.5] * 3,
             "alpha2": [2e-5] * 3, "q1": 0.6, "q2": 1.5, "g1": 0.7, "g2": 1.9}
    stats = {"min": 1.0, "median": 2.0, "max": 3.0}
    docs = {
        "optimal.mars": {
            "lgw_version": "0.1.0", "command": "optimal mars", "gains": None,
            "plant": "mars", "solution": {
                "status": "optimal", "tf": 30.0, "n": 1, "dt": 30.0, "fuel_kg": 10.0,
                "final_mass_kg": 1895.0, "settings": {"m0_kg": 1905.0, "m_dry_kg": 1505.0},
                "t": [0.0, 30.0], "r": [[1.0, 2.0, 3.0], [0.0, 0.0, 0.0]],
                "v": [[1.0, 2.0, 3.0], [0.0, 0.0, 0.0]], "m": [1905.0, 1895.0],
                "F": [[1.0, 2.0, 3.0]]},
            "sources": [], "replays": [], "paper_fuel_optimal_kg": 212.9},
        "simulate.mars": {
            "lgw_version": "0.1.0", "command": "simulate mars", "gains": gains,
            "summary": {"cases": 1, "landed": 1, "nonfinite": 0,
                        "outcomes": {k: 0 for k in ("landed", "propellant_exhausted",
                                                    "nonfinite", "step_limit", "horizon",
                                                    "command_blown_up")},
                        "fuel_kg": stats, "landing_time_s": stats,
                        "settings": {"law": "corrected", "disturbance": "none", "cases": 1,
                                     "method": "rk4"}},
            "cases": [{"case": 0, "r0": [1.0, 2.0, 3.0], "v0": [0.0, 0.0, 0.0], "m0": 1905.0,
                       "landed": True, "fuel": 200.0, "nonfinite": False,
                       "outcome": "landed"}]},
    }
    d = docs[name]
    S.validate(d)
    return d


@pytest.mark.parametrize("name, path, value", [
    ("simulate.mars", ("lgw_version",), None),  # a head key missing
    ("simulate.mars", ("gains",), None),
    ("simulate.mars", ("gains", "q1"), "0.6"),  # a wrong type
    ("simulate.mars", ("gains", "beta1"), [1.0, 2.0]),  # a per-axis list of two
    ("simulate.mars", ("gains", "zeta"), 1.0),  # an unknown gain
    ("simulate.mars", ("surprise",), 1),  # an unknown top-level key
    ("simulate.mars", ("command",), "simulate lunar"),
    ("simulate.mars", ("cases", 0, "fuel"), "lots"),
    ("simulate.mars", ("nonfinite_replaced",), False),
    ("optimal.mars", ("solution", "fuel_kg"), -4e-12),  # impossible: negative fuel
    ("optimal.mars", ("gains",), {"q1": 1.0}),  # the optimum flies no gain set
    ("optimal.mars", ("solution", "r", 0), [1.0, 2.0]),
])
def test_schemas_reject_broken_documents(name, path, value):
    d = copy.deepcopy(_valid(name))
    target = d
    for key in path[:-1]:
        target = target[key]
    if value is None:
        del target[path[-1]]
    else:
        target[path[-1]] = value
    assert S.errors(d), f"{name}: {path} = {value!r} accepted"


def test_docs_json_md_is_generated_from_the_schemas():
    """docs/json.md is ``python -m lgw.tuning.schemas --write docs/json.md``'s output."""
    text = (ROOT / "docs" / "json.md").read_text(encoding="utf-8")
    assert text == S.markdown(), "docs/json.md is stale: python -m lgw.tuning.schemas " \
        "--write docs/json.md"
    for n in S.names():
        assert f"lgw {n.replace('.', ' ')}" in text


def test_schemas_are_shipped_as_package_data():
    import tomllib

    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text())
    assert "lgw.tuning.schemas" in pyproject["tool"]["setuptools"]["packages"]
    assert "*.json" in pyproject["tool"]["setuptools"]["package-data"]["lgw.tuning.schemas"]
    shipped = {p.name for p in (ROOT / "tuning" / "schemas").glob("*.json")}
    assert shipped == {f"{n}.json" for n in S.names()} | {"common.json"}
