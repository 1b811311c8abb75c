"""A feedforward whose constructor takes exactly its C++ parameter table's rows: the signature,
the saved file's keys and the docstring's Parameters section from the table, written nowhere
else (a model's counterpart is ``models/_param_table.py``'s ``from_table``)."""

from __future__ import annotations

import inspect
from typing import Any, TypeVar

from .._util.args import core_errors_as, number
from .._util.param_table import python_default, rows_of, with_parameters
from .._util.units import warn_unit_slips

_T = TypeVar("_T", bound=type)


def feedforward_from_table(cls: _T) -> _T:
    """Class decorator: the constructor of a feedforward built on a bound C++ compensator from
    its ``_core_params`` table: it takes the rows (by name or in table order, each a number,
    the table's default when left out), keeps them as the settings ``to_json`` saves and
    ``params`` returns, and builds the C++ compensator from them.

    Parameters
    ----------
    cls : type
        A :class:`~tendonsheath.compensate.base.Feedforward` subclass of a bound C++
        compensator, with ``_core_params`` its parameter struct.

    Returns
    -------
    type
        ``cls``, completed: ``__init__``, ``_saved_settings`` and its docstring.
    """
    struct = cls._core_params  # type: ignore[attr-defined]
    rows = rows_of(struct)
    keyword = inspect.Parameter.POSITIONAL_OR_KEYWORD
    signature = inspect.Signature(
        [inspect.Parameter("self", keyword)]
        + [
            inspect.Parameter(r["name"], keyword, default=d, annotation=type(d))
            for r, d in ((r, python_default(r)) for r in rows)
        ]
    )

    def __init__(self: Any, *args: Any, **values: Any) -> None:
        who = type(self).__name__
        try:
            bound = signature.bind(self, *args, **values)
        except TypeError as e:
            raise TypeError(f"{who}: {e}") from None
        bound.apply_defaults()
        settings = dict(list(bound.arguments.items())[1:])
        self._settings = {k: number(who, k, v) for k, v in settings.items()}
        params = struct(**self._settings)
        with core_errors_as(who):
            self._bound_class.__init__(self, params)
        warn_unit_slips(who, params)

    __init__.__signature__ = signature  # type: ignore[attr-defined]
    __init__.from_table = True  # type: ignore[attr-defined]
    __init__.__qualname__ = f"{cls.__qualname__}.__init__"
    __init__.__module__ = cls.__module__
    __init__.__doc__ = f"Build a {cls.__name__} (see the class docstring)."
    setattr(cls, "__init__", __init__)  # noqa: B010 - mypy refuses an assignment to __init__
    cls._saved_settings = tuple(r["name"] for r in rows)  # type: ignore[attr-defined]
    cls._table_struct = struct  # type: ignore[attr-defined]
    cls.__doc__ = with_parameters(cls.__name__, cls.__doc__ or "", signature, rows)
    return cls


__all__ = ["feedforward_from_table"]
