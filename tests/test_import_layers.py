"""The package's layers as folders: no module imports a name from the package's ``__init__``,
and one module per layer (``_bound.py``) imports the C++ extension, which import-linter's graph
cannot see (`make lint` runs .importlinter's layer and no-cycle contracts)."""

import ast
import importlib
from pathlib import Path

import tendonsheath as ts

PACKAGE = Path(ts.__file__).resolve().parent


def _resolved(module_path: Path, node: ast.ImportFrom) -> str:
    parts = list(module_path.relative_to(PACKAGE.parent).with_suffix("").parts)
    here = parts[:-1] if parts[-1] == "__init__" else parts[:-1]
    if parts[-1] == "__init__":
        here = parts[:-1]
    if not node.level:
        return node.module or ""
    base = here[: len(here) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _imports_from_the_root(module_path: Path) -> list[str]:
    """`from tendonsheath import X` / `from .. import X` where X is not a module (or _core),
    and `import tendonsheath`, in one module of the package."""
    found = []
    for node in ast.walk(ast.parse(module_path.read_text())):
        if isinstance(node, ast.Import):
            found += [f"import {a.name}" for a in node.names if a.name == "tendonsheath"]
        elif isinstance(node, ast.ImportFrom) and _resolved(module_path, node) == "tendonsheath":
            for alias in node.names:
                is_module = (PACKAGE / f"{alias.name}.py").exists() or (
                    PACKAGE / alias.name
                ).is_dir()
                if alias.name != "_core" and not is_module:
                    found.append(f"line {node.lineno}: from tendonsheath import {alias.name}")
    return found


def test_no_module_imports_a_name_from_the_package_init():
    modules = [m for m in sorted(PACKAGE.rglob("*.py")) if m != PACKAGE / "__init__.py"]
    assert len(modules) > 100
    offenders = {str(m.relative_to(PACKAGE)): _imports_from_the_root(m) for m in modules}
    assert {k: v for k, v in offenders.items() if v} == {}


def test_the_resolver_sees_an_import_from_the_root(tmp_path):
    # the check above can fail: a module importing a name from the package's __init__
    probe = PACKAGE / "bench" / "run.py"
    node = ast.parse("from .. import Motor").body[0]
    assert _resolved(probe, node) == "tendonsheath"
    node = ast.parse("from ..plant import Motor").body[0]
    assert _resolved(probe, node) == "tendonsheath.plant"


def test_the_public_names_stay_where_they_were():
    assert ts.PullPullPlant is importlib.import_module("tendonsheath.plant").PullPullPlant
    assert ts.presets is importlib.import_module("tendonsheath.plant.presets")
    assert ts.physics is importlib.import_module("tendonsheath.plant.physics")
    assert ts.loads is importlib.import_module("tendonsheath.plant.loads")
    assert ts.io.read_log is importlib.import_module("tendonsheath.io.log").read_log


def _imports_the_extension(module_path: Path) -> bool:
    for node in ast.walk(ast.parse(module_path.read_text())):
        if isinstance(node, ast.ImportFrom):
            target = _resolved(module_path, node)
            if target == "tendonsheath._core" or (
                target == "tendonsheath" and any(a.name == "_core" for a in node.names)
            ):
                return True
        elif isinstance(node, ast.Import) and any(
            a.name == "tendonsheath._core" for a in node.names
        ):
            return True
    return False


def test_one_module_per_layer_imports_the_extension():
    # <layer>/_bound.py lists the C++ names its folder uses; no other module imports _core
    importers = sorted(
        str(m.relative_to(PACKAGE)) for m in PACKAGE.rglob("*.py") if _imports_the_extension(m)
    )
    assert importers == [f"{layer}/_bound.py" for layer in sorted(LAYERS_WITH_CORE)]


def test_the_extension_check_can_fail(tmp_path):
    probe = PACKAGE / "plant" / "motor.py"
    for text in ("from .. import _core as core", "from .._core import Motor"):
        assert _resolved(probe, ast.parse(text).body[0]) in ("tendonsheath", "tendonsheath._core")
    assert _imports_the_extension(PACKAGE / "plant" / "_bound.py")
    assert not _imports_the_extension(PACKAGE / "plant" / "motor.py")


LAYERS_WITH_CORE = ("bench", "compensate", "identify", "models", "plant")
