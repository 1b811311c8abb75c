"""Every public module of the package declares ``__all__``, and lists only its own API in it.

A public module is one whose dotted name has no part starting with ``_`` (``tendonsheath.io``,
``tendonsheath.identify.fit``, ``tendonsheath.report.build``; not ``tendonsheath._util.args``).
Its ``__all__`` names what ``from module import *`` brings and what the API reference
documents, so it must not carry the helpers the module imports: ``np``, ``re``, ``Path``, a
typing name, another library's function, or a private helper of the package
(``tendonsheath.io`` once exported ``atomic_path``, ``parse_cells``, ``np`` and ``re``).
"""

from __future__ import annotations

import ast
import importlib
import inspect
import pkgutil
import types
from pathlib import Path

import pytest

import tendonsheath as ts

PACKAGE = Path(ts.__file__).parent


def _is_public(modname: str) -> bool:
    return not any(part.startswith("_") for part in modname.split("."))


def public_modules() -> list[str]:
    """The public modules found by ``pkgutil.walk_packages``, plus those of ``report`` (a
    namespace package: no ``__init__.py``, so the walk does not enter it)."""
    names = {"tendonsheath"}
    for info in pkgutil.walk_packages(ts.__path__, "tendonsheath."):
        names.add(info.name)
    report = importlib.import_module("tendonsheath.report")
    for info in pkgutil.walk_packages(report.__path__, "tendonsheath.report."):
        names.add(info.name)
    return sorted(n for n in names if _is_public(n) and n != "tendonsheath.__main__")


def _files_as_modules() -> set[str]:
    """Every module of the package by its file (the check that the walk missed none)."""
    found = set()
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        found.add(".".join(("tendonsheath", *parts)))
    return {n for n in found if _is_public(n) and n != "tendonsheath.__main__"}


MODULES = public_modules()


def _source_file(module: types.ModuleType) -> Path:
    return Path(module.__file__)


def _imported_from(tree: ast.Module, modname: str, is_package: bool) -> dict[str, str]:
    """name -> the absolute module a top-level ``import`` / ``from ... import`` binds it from
    (in ``if``/``try`` blocks too)."""
    found: dict[str, str] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                found[alias.asname or alias.name.split(".")[0]] = alias.name
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = modname.split(".")
                if not is_package:
                    base = base[:-1]
                base = base[: len(base) - (node.level - 1)]
                source = ".".join([*base, *([node.module] if node.module else [])])
            else:
                source = node.module or ""
            for alias in node.names:
                found[alias.asname or alias.name] = f"{source}.{alias.name}"
    return found


def all_problems(module: types.ModuleType) -> list[str]:
    """What is wrong with a module's ``__all__`` (empty: nothing)."""
    modname = module.__name__
    names = getattr(module, "__all__", None)
    if names is None:
        return ["no __all__"]
    problems = []
    if len(set(names)) != len(names):
        problems.append("a name is listed twice")
    is_package = hasattr(module, "__path__")
    imported = _imported_from(ast.parse(_source_file(module).read_text()), modname, is_package)
    for name in names:
        if not hasattr(module, name):
            problems.append(f"{name}: listed but not defined")
            continue
        obj = getattr(module, name)
        if inspect.ismodule(obj):
            # a package may export its own subpackages (ts.models, ts.io) and modules of
            # its folders (ts.presets is tendonsheath.plant.presets), nothing else (np, re)
            if not obj.__name__.startswith(f"{modname}."):
                problems.append(f"{name}: the module {obj.__name__}")
            continue
        origin = imported.get(name)
        if origin is not None and not origin.startswith("tendonsheath."):
            problems.append(f"{name}: imported from {origin.rsplit('.', 1)[0]}")
            continue
        if origin is not None and any(p.startswith("_") for p in origin.split(".")[1:-1]):
            # a private module's helper: exported only when it is a class (a warning the
            # module's functions raise, e.g. route.UnitWarning) or a function of the package's
            # API that the private module merely holds
            if not inspect.isclass(obj):
                problems.append(f"{name}: a helper of {origin.rsplit('.', 1)[0]}")
                continue
        is_class = isinstance(obj, type) and not isinstance(obj, types.GenericAlias)
        if is_class or inspect.isfunction(obj) or inspect.isbuiltin(obj):
            owner = getattr(obj, "__module__", None) or ""
            if owner != "tendonsheath" and not owner.startswith("tendonsheath."):
                problems.append(f"{name}: defined in {owner}")
    return problems


def test_the_walk_finds_every_public_module():
    assert set(MODULES) == _files_as_modules()
    # the package, its subpackages and their modules, report's modules: not a handful
    assert len(MODULES) > 100 and "tendonsheath.report.build" in MODULES


@pytest.mark.parametrize("modname", MODULES)
def test_public_module_declares_its_own_names_in_all(modname):
    problems = all_problems(importlib.import_module(modname))
    assert not problems, f"{modname}.__all__: " + "; ".join(problems)


def test_star_import_of_io_brings_only_its_api():
    namespace: dict = {}
    exec("from tendonsheath.io import *", namespace)
    assert not {"np", "re", "atomic_path", "parse_cells", "Path", "annotations"} & set(namespace)
    assert {"read_log", "write_csv", "Log", "columns", "deg2rad", "rad2deg"} <= set(namespace)


def test_the_all_check_can_fail(tmp_path, monkeypatch):
    fake = tmp_path / "tendonsheath_fake_all.py"
    fake.write_text(
        "import re\n"
        "import numpy as np\n"
        "from pathlib import Path\n"
        "from tendonsheath._util.atomic import atomic_path\n"
        "from tendonsheath import models\n"
        "def own():\n"
        "    return 1\n"
        "__all__ = ['own', 're', 'np', 'Path', 'atomic_path', 'models', 'gone', 'own']\n"
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    module = importlib.import_module("tendonsheath_fake_all")
    # as if it were a module of the package (its own names are then the package's)
    module.own.__module__ = "tendonsheath.fake_all"
    module.__name__ = "tendonsheath.fake_all"
    problems = all_problems(module)
    assert problems == [
        "a name is listed twice",
        "re: the module re",
        "np: the module numpy",
        "Path: imported from pathlib",
        "atomic_path: a helper of tendonsheath._util.atomic",
        "models: the module tendonsheath.models",
        "gone: listed but not defined",
    ]
    del module.__all__
    assert all_problems(module) == ["no __all__"]
