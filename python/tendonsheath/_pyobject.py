"""Models, compensators and plants behave like Python objects: copies, pickles, attributes.

Most of them *are* a bound C++ class (a Python subclass of it, see :func:`bound_base`), whose
streaming state copies exactly but does not serialise. So:

* ``copy.deepcopy`` and ``copy.copy`` give an independent object with the exact streaming
  state of the original (each engine is a C++ copy): stepping the copy continues as the
  original would, and leaves the original unchanged. ``copy.copy`` is a deep copy, since a
  shallow one would share the C++ engine with the original.
* ``pickle`` (and with it multiprocessing, joblib, caches) saves the configuration, the same
  as the object's saved file (``to_dict``) or its constructor's arguments, and loads an equal
  object *at rest*, as after ``reset()``: the streaming state of a running engine is not
  pickled. Outputs of ``simulate``/``command`` (which start at rest) and any ``step`` sequence
  from rest are identical to the original's.
* Setting an attribute the class does not declare (``model.B_r = 0.5``) raises
  AttributeError naming the parameters, instead of adding an attribute nothing reads.
"""

from __future__ import annotations

import copy
import functools
import sys
from collections.abc import Callable
from typing import Any, ClassVar

_OPEN = "_initialising"  # set on an instance while its outermost __init__ runs


def _opening(init: Callable) -> Callable:
    """``init`` during which the instance takes new public attributes (its own settings)."""

    @functools.wraps(init)
    def wrapper(self, *args, **kwargs):
        if _OPEN in vars(self):  # a subclass's __init__ calling its parent's
            return init(self, *args, **kwargs)
        object.__setattr__(self, _OPEN, True)
        try:
            return init(self, *args, **kwargs)
        finally:
            object.__delattr__(self, _OPEN)

    return wrapper


def bound_base(cls: type) -> type | None:
    """The C++ class bound by nanobind that ``cls`` is built on (the first one in its method
    resolution order defined in a compiled extension), or None for a pure Python class."""
    for base in cls.__mro__:
        module = sys.modules.get(base.__module__)
        if type(base).__name__ == "nb_type" and getattr(module, "__file__", "").endswith(
            (".so", ".pyd")
        ):
            return base
    return None


def bound_attribute(obj: Any, name: str) -> Any:
    """``obj``'s attribute ``name`` as its bound C++ class defines it (a property such as
    ``params`` that the Python class redefines in its own shape)."""
    base = getattr(type(obj), "_bound_class", None) or bound_base(type(obj))
    if base is None:
        raise TypeError(f"{type(obj).__name__} is not built on a bound C++ class")
    return getattr(base, name).__get__(obj, type(obj))


def from_state(cls: type[Any], state: dict[str, Any]) -> Any:
    """An instance of ``cls`` with the attributes ``state`` (its pickled ``__dict__``).

    Parameters
    ----------
    cls : type
        The class.
    state : dict
        The attributes.

    Returns
    -------
    object
        The instance (its ``__init__`` not run).
    """
    obj = object.__new__(cls)
    vars(obj).update(state)
    return obj


class PythonObject:
    """Copies that do not share the C++ engine, pickling through the configuration, and no
    silent attribute for a misspelt or unknown name (see :mod:`tendonsheath._pyobject`).

    A subclass whose state holds C++ engines defines ``_recipe()``: a picklable
    ``(callable, args)`` that builds an equal object at rest. Without one, the instance's
    attributes are pickled as they are (each must pickle).

    ``_bound_class`` is the bound C++ class a subclass is built on (None: pure Python), for the
    calls that must reach it past a Python method of the same name
    (``self._bound_class.step(self, ...)``)."""

    _bound_class: ClassVar[Any] = None

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        cls._bound_class = bound_base(cls)
        if "__init__" in vars(cls):
            cls.__init__ = _opening(cls.__init__)

    def _recipe(self) -> tuple[Callable, tuple]:
        return from_state, (type(self), dict(vars(self)))

    def __reduce__(self):
        return self._recipe()

    def __deepcopy__(self, memo: dict) -> Any:
        new = type(self).__new__(type(self))
        if self._bound_class is not None:  # the C++ part: an exact copy, its state included
            self._bound_class.__init__(new, self)
        memo[id(self)] = new
        vars(new).update(copy.deepcopy(vars(self), memo))  # engines: exact C++ copies
        return new

    def __copy__(self) -> Any:
        return copy.deepcopy(self)

    def __setattr__(self, name: str, value: Any) -> None:
        known = name.startswith("_") or name in vars(self) or hasattr(type(self), name)
        if not (known or _OPEN in vars(self)):
            names = self._parameter_names()
            if name in names:  # a parameter, read through params: not an attribute to set
                how = (
                    f"with_params({name}=...) makes a copy with the new value"
                    if hasattr(self, "with_params")
                    else "it is set at construction"
                )
                raise AttributeError(
                    f"{type(self).__name__}: parameter {name!r} cannot be set on the object "
                    f"(it is read as .params[{name!r}]); {how}"
                )
            raise AttributeError(
                f"{type(self).__name__} has no attribute {name!r} to set; its parameters are "
                f"{names}" + self._how_to_change()
            )
        object.__setattr__(self, name, value)

    def _parameter_names(self) -> list[str]:
        try:
            return list(self.params)  # type: ignore[attr-defined]
        except AttributeError:
            return sorted(k for k in vars(self) if not k.startswith("_"))

    def _how_to_change(self) -> str:
        if hasattr(self, "with_params"):
            return " (with_params(...) makes a copy with new values)"
        return " (set at construction)"
