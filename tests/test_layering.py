"""The house rules, read from the source: floors import only downwards, a system never imports
another system, nothing imports the folders by their bare names, and every package folder is
installed (listed in pyproject.toml)."""

from __future__ import annotations

import ast
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FLOORS = {"theory": 1, "sim": 2, "tuning": 3}
SYSTEMS = ("mars", "lunar", "eros")


def _imports(path: Path, root: Path) -> list[tuple[int, str]]:
    """(line, absolute module name) of every import in a source file, relative ones resolved."""
    tree = ast.parse(path.read_text(), filename=str(path))
    rel = path.relative_to(root).with_suffix("")
    parts = ["lgw", *rel.parts]
    if parts[-1] == "__init__":
        parts = parts[:-1]
    pkg = parts if path.name == "__init__.py" else parts[:-1]
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg[: len(pkg) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            out.append((node.lineno, mod))
            out += [(node.lineno, f"{mod}.{a.name}") for a in node.names]
    return out


def violations(root: Path = ROOT) -> list[str]:
    """Every import that breaks a rule, as 'file:line: module (rule)'."""
    bad = []
    for floor, level in FLOORS.items():
        for path in sorted((root / floor).rglob("*.py")):
            rel = path.relative_to(root)
            system = rel.parts[1] if len(rel.parts) > 2 and rel.parts[1] in SYSTEMS else None
            for line, mod in _imports(path, root):
                head = mod.split(".")
                if head[0] in FLOORS:
                    bad.append(f"{rel}:{line}: {mod} (import lgw.{mod}, not the bare folder)")
                    continue
                if head[0] != "lgw" or len(head) < 2 or head[1] not in FLOORS:
                    continue
                if FLOORS[head[1]] > level:
                    bad.append(f"{rel}:{line}: {mod} (floor {floor} imports a floor above)")
                other = head[2] if len(head) > 2 and head[2] in SYSTEMS else None
                if other is not None and system is not None and other != system:
                    bad.append(f"{rel}:{line}: {mod} (system {system} imports system {other})")
                if other is not None and system is None and floor != "tuning":
                    # shared machinery below the CLI must not depend on one system
                    bad.append(f"{rel}:{line}: {mod} (shared {floor} imports system {other})")
    return bad


def test_no_forbidden_import():
    assert violations() == []


def test_the_checker_sees_a_forbidden_import(tmp_path):
    """The checker itself can fail: a copy of the tree with one forbidden import each."""
    for floor in FLOORS:
        (tmp_path / floor / "mars").mkdir(parents=True)
        (tmp_path / floor / "lunar").mkdir(parents=True)
    cases = {
        "theory/mars/a.py": "from lgw.sim.mars import batch\n",          # theory -> sim
        "sim/lunar/b.py": "import lgw.tuning.cli\n",                     # sim -> tuning
        "sim/mars/c.py": "from lgw.sim.lunar import plant\n",             # system -> system
        "theory/d.py": "from ..theory.mars import mss\n",                 # shared -> system
        "tuning/e.py": "from theory.mars import mss\n",                   # bare folder name
    }
    for rel, src in cases.items():
        (tmp_path / rel).write_text(src)
    found = {f.split(":")[0] for f in violations(tmp_path)}
    assert found == set(cases)


def test_every_package_folder_is_installed():
    cfg = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(cfg["packages"])
    # folder -> package through the package-dir mapping (the longest mapped folder wins)
    mapping = sorted(((Path(d).parts, pkg) for pkg, d in cfg["package-dir"].items()),
                     key=lambda m: -len(m[0]))

    def package(folder: Path) -> str:
        parts = folder.relative_to(ROOT).parts
        for prefix, pkg in mapping:
            if parts[:len(prefix)] == prefix:
                return ".".join([pkg, *parts[len(prefix):]])
        raise AssertionError(f"{folder} is under no mapped folder")

    dirs = {package(p.parent) for floor in FLOORS for p in (ROOT / floor).rglob("__init__.py")}
    assert dirs <= listed, sorted(dirs - listed)
    assert listed <= dirs, sorted(listed - dirs)
    assert cfg["package-dir"]["lgw"] == "tuning/_root"


@pytest.mark.parametrize("name", ["theory", "sim", "tuning"])
def test_bare_folder_names_do_not_import(name):
    import importlib
    import sys

    sys.modules.pop(name, None)
    with pytest.raises(ImportError):
        importlib.import_module(name)
    sys.modules.pop(name, None)
