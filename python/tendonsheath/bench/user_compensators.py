"""A user's own compensators in a ``tendonsheath bench`` scenario (``[[compare.user]]``).

    [[compare.user]]
    class = "my_package.control:MyCompensator"   # module:Class (importable), or
    # file = "my_compensator.py"                 #   a Python file (relative to the scenario)
    # class = "MyCompensator"                    #   and the class in it
    name = "my compensator"                      # optional: its label (default: the class name)
    kwargs = { gain = 1.0, kp = 0.5 }            # optional: the constructor's keyword arguments

The class must meet :class:`tendonsheath.protocols.StreamingCompensator` (``reset()`` and
``step(<step_inputs>, dt)``); a compiled one bound with ``tendonsheath_bind/compensator.hpp``
runs in the C++ loop. A ``control_output`` of "torque" is run on the plant with the
``[torque_motor]``, any other on the plant with the position servo ``[motor]``. Its
constructor's keyword arguments are what it was told, declared by the user.
"""

from __future__ import annotations

import importlib
import importlib.util
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..protocols import StreamingCompensator, missing_members, step_signals

_ENTRY_KEYS = {"class", "file", "name", "kwargs"}


@dataclass
class UserCompensator:
    """One ``[[compare.user]]`` entry, its class resolved."""

    name: str
    cls: type
    kwargs: dict[str, Any] = field(default_factory=dict)
    origin: str = ""

    def build(self):
        return self.cls(**self.kwargs)


def parse_user_compensators(entries, where: str, base: Path, taken) -> list[UserCompensator]:
    """The ``[[compare.user]]`` entries of a scenario, each class imported and built once to
    check it; ``base``: the scenario's folder; ``taken``: labels already used."""
    if not isinstance(entries, list):
        raise ValueError(f"{where}: 'user' must be an array of tables ([[compare.user]])")
    out: list[UserCompensator] = []
    names = set(taken)
    for i, entry in enumerate(entries):
        here = f"{where} [[compare.user]] #{i + 1}"
        user = _entry(entry, here, base)
        if user.name in names:
            raise ValueError(f"{here}: the name '{user.name}' is already used; give it a 'name'")
        names.add(user.name)
        out.append(user)
    return out


def _entry(entry, here: str, base: Path) -> UserCompensator:
    if not isinstance(entry, dict):
        raise ValueError(f"{here}: each entry must be a table")
    unknown = sorted(set(entry) - _ENTRY_KEYS)
    if unknown:
        raise ValueError(f"{here}: unknown key '{unknown[0]}' (known: {sorted(_ENTRY_KEYS)})")
    cls, origin, kwargs = class_and_kwargs(entry, here, base)
    name = entry.get("name", cls.__name__)
    if not isinstance(name, str) or not name:
        raise ValueError(f"{here}: 'name' must be a non-empty string")
    user = UserCompensator(name, cls, dict(kwargs), origin)
    _check_builds(user, here)
    return user


def class_and_kwargs(table: dict, here: str, base: Path) -> tuple[type, str, dict]:
    """The class a table's 'class' (and 'file') names, its origin "module:Class" and the
    table's 'kwargs'; ValueError starting with ``here`` when one is missing or malformed."""
    spec, kwargs = table.get("class"), table.get("kwargs", {})
    if not isinstance(spec, str) or not spec:
        raise ValueError(
            f"{here}: 'class' (\"module:Class\", or a class name with 'file') is needed"
        )
    if not isinstance(kwargs, dict):
        raise ValueError(f"{here}: 'kwargs' must be a table of keyword arguments")
    cls, origin = resolve_class(spec, table.get("file"), here, base)
    return cls, origin, kwargs


def resolve_class(spec: str, file, here: str, base: Path) -> tuple[type, str]:
    """The class ``spec`` names ("module:Class", or "Class" in the Python ``file``, relative
    to ``base``) and its origin "module:Class"; ValueError starting with ``here`` otherwise."""
    if file is not None:
        if not isinstance(file, str):
            raise ValueError(f"{here}: 'file' must be a path (string)")
        module, origin = _module_from_file((base / file).resolve(), here), file
        class_name = spec
    else:
        if ":" not in spec:
            raise ValueError(f"{here}: 'class' must be \"module:Class\" (or give 'file')")
        module_name, class_name = spec.split(":", 1)
        try:
            module = importlib.import_module(module_name)
        except Exception as exc:  # the user's module: any import error is theirs to see
            raise ValueError(f"{here}: cannot import '{module_name}' ({exc})") from None
        origin = module_name
    cls = getattr(module, class_name, None)
    if not isinstance(cls, type):
        raise ValueError(f"{here}: '{origin}' has no class '{class_name}'")
    return cls, f"{origin}:{class_name}"


def _module_from_file(path: Path, here: str):
    if not path.is_file():
        raise ValueError(f"{here}: file not found: {path}")
    spec = importlib.util.spec_from_file_location(f"_tendonsheath_user_{path.stem}", path)
    if spec is None or spec.loader is None:
        raise ValueError(f"{here}: {path} is not a Python file")
    module = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(module)
    except Exception as exc:
        raise ValueError(f"{here}: cannot run {path.name} ({type(exc).__name__}: {exc})") from None
    return module


def _check_builds(user: UserCompensator, here: str) -> None:
    try:
        instance = user.build()
    except Exception as exc:
        raise ValueError(f"{here}: {user.origin}(**kwargs) failed ({exc})") from None
    missing = missing_members(instance, StreamingCompensator)
    if missing:
        raise ValueError(
            f"{here}: {user.origin} is not a compensator: it has no {' and no '.join(missing)}"
        )
    _check_step(instance, here, user.origin)


def _check_step(instance, here: str, origin: str) -> None:
    """``step`` takes the signals its ``step_inputs`` names, then dt (checked by
    :func:`~tendonsheath.protocols.step_signals`), named by the entry."""
    try:
        step_signals(instance)
    except TypeError as exc:
        raise ValueError(f"{here}: {origin}: {exc}") from None


def told_by_user(user: UserCompensator) -> dict[str, tuple[Any, str]]:
    """What a user's compensator was told: its keyword arguments, declared by the user."""
    told = {"class": (user.origin, "named by the user ([[compare.user]])")}
    for key, value in user.kwargs.items():
        told[key] = (value, "declared by the user ([[compare.user]] kwargs)")
    return told


__all__ = [
    "UserCompensator",
    "class_and_kwargs",
    "parse_user_compensators",
    "resolve_class",
    "told_by_user",
]
