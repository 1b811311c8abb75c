"""A model's parameters from its C++ parameter table, written once.

Each C++ parameter struct has a table (``include/tendonsheath/param_table.hpp``) that
``fields()`` gives Python row by row: name, unit, default, range, doc and role (an identifiable
``"parameter"`` or a numerical ``"option"``). :func:`from_table`, a class decorator, derives from
it what a model class would otherwise restate: ``param_names`` and ``option_names`` (so the
saved file's keys), the constructor's signature with the table's defaults (what
``inspect.signature`` and ``help()`` show), and the numpydoc Parameters section of the class
docstring. A class writes only what the table cannot say:

- a Python-only argument (Polynomial's ``degree``): its own ``__init__`` names it and takes the
  rows by ``**values``; its docstring's Parameters section documents only that argument;
- a value Python shows otherwise (a code by its name): ``_python_value``;
- a parameter whose default is derived from others: ``derived_params`` (None in the signature).
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Callable, Sequence
from typing import Any, TypeVar

from .._util.args import integer, number
from .._util.param_table import range_text, with_parameters
from .base import HysteresisModel

_T = TypeVar("_T", bound=type)


def table_rows(cls: type) -> list[dict[str, Any]]:
    """The rows of ``cls._core_params``'s table (``fields()``), as dicts.

    Parameters
    ----------
    cls : type
        A model class with ``_core_params``.

    Returns
    -------
    list of dict
        One per row: name, unit, default, lo, lo_closed, hi, hi_closed, check, doc, applies_to,
        role.
    """
    return list(cls._core_params.fields())  # type: ignore[attr-defined]


def table_default(cls: type, name: str) -> Any:
    """The table's default of row ``name``, as Python shows it (``cls._python_value``).

    Parameters
    ----------
    cls : type
        A model class with ``_core_params``.
    name : str
        A row's name.

    Returns
    -------
    object
        The default.
    """
    row = next(r for r in table_rows(cls) if r["name"] == name)
    return _python_default(cls, row)


def from_table(cls: _T) -> _T:
    """Class decorator: ``param_names``, ``option_names``, the constructor's signature and the
    docstring's Parameters section of a model class from its ``_core_params`` table.

    A class without its own ``__init__`` gets one that takes the table's rows (positionally
    too, in table order) and hands them to the base constructor; a class with its own keeps it
    (Python-only arguments first, the rows by ``**values``) and its signature is completed with
    the rows it does not name.

    Parameters
    ----------
    cls : type
        A HysteresisModel subclass with ``_core_params``.

    Returns
    -------
    type
        ``cls``, completed.
    """
    rows = table_rows(cls)
    if _declared(cls, "param_names") is None:
        cls.param_names = tuple(r["name"] for r in rows if r["role"] == "parameter")  # type: ignore[attr-defined]
    if _declared(cls, "option_names") is None:
        cls.option_names = tuple(r["name"] for r in rows if r["role"] == "option")  # type: ignore[attr-defined]
    own = _declared(cls, "__init__")
    if getattr(own, "from_table", False) or _takes_rows_only(own):
        own = None  # a decorated base's (this class's rows may differ), or a base's (**values)
    signature = _signature(cls, rows, own)
    if own is None:
        own = _init_taking(cls, signature)
        setattr(cls, "__init__", own)  # noqa: B010 - mypy refuses an assignment to __init__
    own.__signature__ = signature
    cls.__doc__ = with_parameters(
        cls.__name__,
        cls.__doc__ or "",
        signature,
        rows,
        cls._python_value,  # type: ignore[attr-defined]
        tuple(getattr(cls, "derived_params", ())),
    )
    return cls


def _declared(cls: type, name: str) -> Any:
    """``name`` as a class between ``cls`` and HysteresisModel declares it (None: none does)."""
    for klass in cls.__mro__:
        if klass is HysteresisModel:
            return None
        if name in vars(klass):
            return vars(klass)[name]
    return None


def _takes_rows_only(init: Any) -> bool:
    """A base's ``__init__(self, **values)``: it takes the rows by name; the class gets a
    constructor that names them (and takes them positionally)."""
    if init is None:
        return False
    kinds = [p.kind for p in inspect.signature(init).parameters.values()][1:]
    return kinds == [inspect.Parameter.VAR_KEYWORD]


def checked_values(
    owner: str, rows: list[dict[str, Any]], values: dict[str, Any]
) -> dict[str, Any]:
    """``values`` (one per numeric row) checked against the rows' bounds in table order, with
    the C++ core's messages (validate.hpp), for a model that runs in Python.

    Parameters
    ----------
    owner : str
        The class named in the messages.
    rows : list of dict
        The table's rows (``fields()``).
    values : dict
        A value per row name.

    Returns
    -------
    dict
        The values as float (int for an integer row).

    Raises
    ------
    TypeError
        A value that is not a number (an integer for an integer row).
    ValueError
        A value out of its row's range: "<owner>: <name> must be ... (got v)".
    """
    out = dict(values)
    for row in rows:
        name = row["name"]
        if isinstance(row["default"], int):
            out[name] = integer(owner, name, values[name])
        else:
            out[name] = number(owner, name, values[name])
        v = float(out[name])
        bound = range_text(row)
        lo_ok = v >= row["lo"] if row["lo_closed"] else v > row["lo"]
        hi_ok = v <= row["hi"] if row["hi_closed"] else v < row["hi"]
        finite = math.isfinite(v) or (row["check"] == "positive_or_inf" and v == math.inf)
        if not (finite and lo_ok and hi_ok):
            raise ValueError(f"{owner}: {name} must be {bound or 'finite'} (got {v:g})")
    return out


def _python_default(cls: type, row: dict[str, Any]) -> Any:
    value = cls._python_value(row["name"], row["default"])  # type: ignore[attr-defined]
    return tuple(value) if isinstance(value, list) else value


def _annotation(value: Any) -> Any:
    if isinstance(value, bool | int | float | str):
        return type(value)
    if isinstance(value, tuple):
        return Sequence[float]
    return Any


def _signature(cls: type, rows: list[dict[str, Any]], own: Callable | None) -> inspect.Signature:
    """(self, <own Python-only arguments>, <the rows>): positional-or-keyword rows for a class
    without its own ``__init__``, keyword-only after its own arguments otherwise."""
    derived = set(getattr(cls, "derived_params", ()))
    first = [inspect.Parameter("self", inspect.Parameter.POSITIONAL_OR_KEYWORD)]
    named: set[str] = set()
    if own is not None:
        first = []
        for p in inspect.signature(own).parameters.values():
            if p.kind is not p.VAR_KEYWORD or p.name != "values":  # **values: the rows
                first.append(p)
                named.add(p.name)
    kind = (
        inspect.Parameter.POSITIONAL_OR_KEYWORD if own is None else inspect.Parameter.KEYWORD_ONLY
    )
    rows_args = []
    for row in rows:
        if row["name"] in named:
            continue
        default = None if row["name"] in derived else _python_default(cls, row)
        annotation = _annotation(_python_default(cls, row))
        if default is None:
            annotation = annotation | None
        rows_args.append(
            inspect.Parameter(row["name"], kind, default=default, annotation=annotation)
        )
    starred = [p for p in first if p.kind is p.VAR_KEYWORD]
    plain = [p for p in first if p.kind is not p.VAR_KEYWORD]
    return inspect.Signature([*plain, *rows_args, *starred])


def _init_taking(cls: type, signature: inspect.Signature) -> Callable[..., None]:
    names = list(signature.parameters)[1:]

    def __init__(self, *args: Any, **values: Any) -> None:
        if len(args) > len(names):
            raise TypeError(
                f"{cls.__name__}() takes at most {len(names)} positional arguments "
                f"({len(args)} given)"
            )
        for name, value in zip(names, args, strict=False):
            if name in values:
                raise TypeError(f"{cls.__name__}() got multiple values for argument '{name}'")
            values[name] = value
        super(cls, self).__init__(**values)  # type: ignore[arg-type]

    __init__.from_table = True  # type: ignore[attr-defined]
    __init__.__qualname__ = f"{cls.__qualname__}.__init__"
    __init__.__module__ = cls.__module__
    __init__.__doc__ = f"Build a {cls.__name__} (see the class docstring)."
    return __init__


__all__ = ["checked_values", "from_table", "table_default", "table_rows"]
