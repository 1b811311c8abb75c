"""A C++ parameter table (``include/tendonsheath/param_table.hpp``, ``fields()``) read by the
Python classes that take its rows, so that a row's default, range and doc are written once.

Every layer uses it: the models (``models/_param_table.py``, which also derives their names and
whole signatures), and the plants, motors, sensors and compensators, whose hand-written
constructors interleave the rows with Python-only arguments (a route, a motor, a model):

- :data:`TABLE`, a row's default in such a constructor's ``def``: :func:`table_defaults` (a
  function) or :func:`table_constructor` (a class's ``__init__``) replaces it with the table's
  default, so ``inspect.signature``, ``help()``, ``locals()`` and ``get_params`` see the real
  value;
- both complete the docstring's Parameters section: an entry for each row the signature
  names, from the table (doc, unit, range, default), the hand-written entries for the rest.

A row's Python default that differs from the table's on purpose (a torque motor's inertia) is
written as a literal and documented by hand; tests/test_param_single_copy.py lists each such
exception with its reason.
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Callable
from typing import Any, TypeVar

_F = TypeVar("_F", bound=Callable[..., Any])
_T = TypeVar("_T", bound=type)


class _FromTable:
    """The sentinel :data:`TABLE`."""

    def __repr__(self) -> str:
        return "TABLE"


TABLE: Any = _FromTable()
"""A row's default in a constructor's ``def``: the table's, filled in by :func:`table_defaults`
or :func:`table_constructor`."""

# numpydoc's section headers that follow Parameters, in order
_LATER_SECTIONS = (
    "Returns",
    "Yields",
    "Receives",
    "Other Parameters",
    "Raises",
    "Warns",
    "Warnings",
    "See Also",
    "Notes",
    "References",
    "Examples",
)


def rows_of(struct: Any) -> list[dict[str, Any]]:
    """The rows of a bound C++ parameter struct's table (``fields()``), as dicts.

    Parameters
    ----------
    struct : type
        A bound ``...Params`` struct.

    Returns
    -------
    list of dict
        One per row: name, unit, default, lo, lo_closed, hi, hi_closed, check, doc, applies_to,
        role.
    """
    return list(struct.fields())


def number_rows(struct: Any) -> tuple[str, ...]:
    """The names of the rows that hold a number (float or int, not bool), in table order:
    those a constructor checks with ``number`` and sets on the struct one by one (a nested
    struct, a flag or a code is set on its own).

    Parameters
    ----------
    struct : type
        A bound ``...Params`` struct.

    Returns
    -------
    tuple of str
        The names.
    """
    return tuple(
        r["name"]
        for r in rows_of(struct)
        if isinstance(r["default"], float | int) and not isinstance(r["default"], bool)
    )


def table_defaults(
    struct: Any, shown: Callable[[str, Any], Any] | None = None
) -> Callable[[_F], _F]:
    """Decorator: the function's :data:`TABLE` defaults become ``struct``'s table defaults and
    its docstring's Parameters section documents each row it takes from the table; the struct
    is kept as ``func._table_struct``.

    Parameters
    ----------
    struct : type
        The bound C++ parameter struct whose rows the function takes.
    shown : callable, optional
        (name, table default) -> the default as Python shows it (a code by its name); default:
        the table's value.

    Returns
    -------
    callable
        The decorator (it returns the function, completed).
    """

    def complete(func: _F) -> _F:
        _take_rows(func, func, func.__qualname__, struct, shown)
        return func

    return complete


def table_constructor(
    struct: Any, shown: Callable[[str, Any], Any] | None = None
) -> Callable[[_T], _T]:
    """Class decorator: :func:`table_defaults` for the class's own ``__init__``, its Parameters
    entries written into the class docstring (where numpydoc reads a class's); the struct is
    kept as ``cls._table_struct``.

    Parameters
    ----------
    struct : type
        The bound C++ parameter struct whose rows the constructor takes.
    shown : callable, optional
        As for :func:`table_defaults`.

    Returns
    -------
    callable
        The decorator (it returns the class, completed).
    """

    def complete(cls: _T) -> _T:
        _take_rows(cls, vars(cls)["__init__"], cls.__name__, struct, shown)
        return cls

    return complete


def _take_rows(
    documented: Any,
    func: Callable[..., Any],
    owner: str,
    struct: Any,
    shown: Callable[[str, Any], Any] | None,
) -> None:
    """``func``'s :data:`TABLE` defaults filled from ``struct``'s rows, the struct kept as
    ``documented._table_struct`` and the rows' Parameters entries written into
    ``documented``'s docstring (the function itself, or the class of a constructor)."""
    rows = rows_of(struct)
    _fill_defaults(func, rows, shown)
    documented._table_struct = struct
    documented.__doc__ = with_parameters(
        owner, documented.__doc__ or "", inspect.signature(func), rows, shown
    )


def _fill_defaults(
    func: Callable[..., Any],
    rows: list[dict[str, Any]],
    shown: Callable[[str, Any], Any] | None,
) -> None:
    """Replace each :data:`TABLE` default of ``func`` by its row's default (in place)."""
    by_name = {r["name"]: r for r in rows}
    owner = func.__qualname__

    def value(name: str, default: Any) -> Any:
        if default is not TABLE:
            return default
        if name not in by_name:
            raise TypeError(f"{owner}: argument {name!r} defaults to TABLE but is in no row")
        return python_default(by_name[name], shown)

    code = func.__code__
    positional = code.co_varnames[: code.co_posonlyargcount + code.co_argcount]
    defaults = func.__defaults__ or ()
    named = positional[len(positional) - len(defaults) :]
    func.__defaults__ = tuple(value(n, d) for n, d in zip(named, defaults, strict=True)) or None
    if func.__kwdefaults__:
        func.__kwdefaults__ = {n: value(n, d) for n, d in func.__kwdefaults__.items()}


def python_default(row: dict[str, Any], shown: Callable[[str, Any], Any] | None = None) -> Any:
    """A row's default as Python shows it (``shown``, else an enum by its name; a list as a
    tuple).

    Parameters
    ----------
    row : dict
        The row.
    shown : callable, optional
        (name, table default) -> the value Python shows.

    Returns
    -------
    object
        The default.
    """
    value = row["default"] if shown is None else shown(row["name"], row["default"])
    if shown is None and hasattr(type(value), "__members__"):
        value = value.name  # a C++ enum (ContinuumMode.exact) by its name, as Python takes it
    return tuple(value) if isinstance(value, list) else value


def row_default(struct: Any, name: str) -> Any:
    """Row ``name``'s default as Python shows it (an enum by its name).

    Parameters
    ----------
    struct : type
        A bound ``...Params`` struct.
    name : str
        A row's name.

    Returns
    -------
    object
        The default.
    """
    return python_default(next(r for r in rows_of(struct) if r["name"] == name))


# -- the docstring's Parameters section --------------------------------------------------------


def _number(value: float) -> str:
    return f"{value:g}"


def range_text(row: dict[str, Any]) -> str:
    """The row's valid range in words ("> 0", "in [0, 1]"), "" when it has none.

    Parameters
    ----------
    row : dict
        The row.

    Returns
    -------
    str
        The range.
    """
    lo, hi = row["lo"], row["hi"]
    check = row["check"]
    if check in ("unchecked",) or (math.isinf(lo) and math.isinf(hi) and check != "finite"):
        return ""
    if check == "finite":
        return "finite"
    if check == "positive_or_inf":
        return "> 0 (inf: no limit)"
    low = f"{'>=' if row['lo_closed'] else '>'} {_number(lo)}" if not math.isinf(lo) else ""
    high = f"{'<=' if row['hi_closed'] else '<'} {_number(hi)}" if not math.isinf(hi) else ""
    if low and high:
        return (
            f"in {'[' if row['lo_closed'] else '('}{_number(lo)}, {_number(hi)}"
            f"{']' if row['hi_closed'] else ')'}"
        )
    return low or high


def _type_text(value: Any) -> str:
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, int):
        return "int"
    if isinstance(value, float):
        return "float"
    if isinstance(value, str):
        return "str"
    if isinstance(value, tuple):
        return "sequence of float"
    return type(value).__name__


def row_entry(
    row: dict[str, Any], param: inspect.Parameter, shown: Any, derived: bool = False
) -> list[str]:
    """A row's numpydoc entry: ``name : type, default value`` and the row's doc, unit and
    range (a None default: "optional", and what None gives unless the value is ``derived``).

    Parameters
    ----------
    row : dict
        The row.
    param : inspect.Parameter
        The argument that takes it.
    shown : object
        The row's default as Python shows it.
    derived : bool, default False
        Whether None derives the value from other arguments.

    Returns
    -------
    list of str
        The entry's lines.
    """
    kind = _type_text(shown)
    if param.default is param.empty:  # a required argument
        head = f"{row['name']} : {kind}"
    elif param.default is None:
        head = f"{row['name']} : {kind}, optional"
    else:
        head = f"{row['name']} : {kind}, default {shown!r}"
    doc = row["doc"]  # as written (a symbol such as mu or c_v keeps its case)
    unit = row["unit"] + (" unit" if row["unit"] in ("input", "output", "command") else "")
    unit = f" ({unit})" if unit else ""
    bound = range_text(row) if type(shown) is type(row["default"]) else ""  # not of a code
    text = f"{doc}{unit}" + (f"; {bound}" if bound else "") + "."
    if param.default is None and shown is not None and not derived:
        text += f" None gives the default, {shown!r}."
    return [head, *_wrapped(text)]


def _wrapped(text: str, width: int = 88) -> list[str]:
    lines, line = [], "   "
    for word in text.split():
        if len(line) + 1 + len(word) > width:
            lines.append(line)
            line = "   "
        line += " " + word
    return [*lines, line]


def _sections(doc: str) -> tuple[list[str], dict[str, list[str]], list[str]]:
    """The docstring's lines before its first section, its sections by header, and their
    order."""
    lines = inspect.cleandoc(doc).splitlines()
    head: list[str] = []
    sections: dict[str, list[str]] = {}
    order: list[str] = []
    current = None
    i = 0
    while i < len(lines):
        nxt = lines[i + 1] if i + 1 < len(lines) else ""
        if lines[i].strip() and nxt.strip() and set(nxt.strip()) == {"-"}:
            current = lines[i].strip()
            sections[current] = []
            order.append(current)
            i += 2
            continue
        (head if current is None else sections[current]).append(lines[i])
        i += 1
    return head, sections, order


def _own_entries(lines: list[str]) -> dict[str, list[str]]:
    """A hand-written Parameters section's entries, under each name they document."""
    entries: dict[str, list[str]] = {}
    current: list[str] | None = None
    for line in lines:
        if line and not line[0].isspace():
            current = [line]
            for name in line.split(" : ")[0].split(","):
                entries[name.strip()] = current
        elif current is not None:
            current.append(line)
    return entries


def with_parameters(
    owner: str,
    doc: str,
    signature: inspect.Signature,
    rows: list[dict[str, Any]],
    shown: Callable[[str, Any], Any] | None = None,
    derived: tuple[str, ...] = (),
) -> str:
    """The docstring with a Parameters section in the signature's order (``self`` or ``cls``
    aside): a hand-written entry where the docstring has one, else the row's from the table.

    Parameters
    ----------
    owner : str
        The class or function named in an error.
    doc : str
        The docstring as written.
    signature : inspect.Signature
        The signature documented (its first argument aside).
    rows : list of dict
        The table's rows.
    shown : callable, optional
        (name, table default) -> the value Python shows.
    derived : tuple of str, default ()
        The rows whose None default is derived from other arguments.

    Returns
    -------
    str
        The docstring, completed.

    Raises
    ------
    TypeError
        An argument in no row and not documented by hand.
    """
    head, sections, order = _sections(doc)
    own = _own_entries(sections.pop("Parameters", []))
    by_name = {r["name"]: r for r in rows}
    entries: list[str] = []
    done: set[int] = set()
    for param in list(signature.parameters.values())[1:]:  # self or cls aside
        star = {"VAR_KEYWORD": "**", "VAR_POSITIONAL": "*"}.get(param.kind.name, "")
        key = star + param.name
        if key in own:
            if id(own[key]) not in done:  # "a, b : float" documents both
                entries += [line.rstrip() for line in own[key] if line.strip()]
                done.add(id(own[key]))
        elif param.name in by_name:
            row = by_name[param.name]
            entries += row_entry(row, param, python_default(row, shown), param.name in derived)
        else:
            raise TypeError(f"{owner}: argument {key!r} is in no table row and not documented")
    order = [s for s in order if s != "Parameters"]
    later = [i for i, s in enumerate(order) if s in _LATER_SECTIONS]
    at = later[0] if later else len(order)
    order.insert(at, "Parameters")
    sections["Parameters"] = entries
    while head and not head[-1].strip():
        head.pop()
    out = [*head]
    for name in order:
        body = sections[name]
        while body and not body[-1].strip():
            body = body[:-1]
        out += ["", name, "-" * len(name), *body]
    return "\n".join(out) + "\n"


__all__ = [
    "TABLE",
    "number_rows",
    "python_default",
    "range_text",
    "row_default",
    "row_entry",
    "rows_of",
    "table_constructor",
    "table_defaults",
    "with_parameters",
]
