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
  AttributeError naming the parameters, instead of adding an attribute nothing reads. A class
  declares the public attributes its ``__init__`` sets with class-level annotations
  (``limits: CommandLimits``); private ones (``_name``) need no declaration.
"""

from __future__ import annotations

import copy
import inspect
import sys
from collections.abc import Callable
from typing import Any, ClassVar, Self


def bound_base(cls: type) -> type | None:
    """The C++ class bound by nanobind that ``cls`` is built on (the first one in its method
    resolution order defined in a compiled extension), or None for a pure Python class."""
    if cls not in _BOUND_BASES:
        _BOUND_BASES[cls] = _first_bound(cls)
    return _BOUND_BASES[cls]


_BOUND_BASES: dict[type, type | None] = {}  # bound_base of each class asked about


def _first_bound(cls: type) -> type | None:
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


def constructor_arguments(cls: type, values: dict[str, Any]) -> dict[str, Any]:
    """The arguments of ``cls``'s constructor, in its signature's order, from ``values`` (the
    constructor's ``locals()`` before it assigns anything); a ``**kwargs`` catch-all is
    spread into its keys.

    Parameters
    ----------
    cls : type
        The class whose ``__init__`` signature names the arguments.
    values : dict
        The constructor's local variables.

    Returns
    -------
    dict
        Each argument's value, by name.
    """
    out: dict[str, Any] = {}
    init = cls.__init__  # type: ignore[misc]  # the class's own constructor
    for name, p in list(inspect.signature(init).parameters.items())[1:]:
        if p.kind is p.VAR_KEYWORD:
            out.update(values[name])
        elif p.kind is not p.VAR_POSITIONAL:
            out[name] = values[name]
    return out


def _constructor_parameters(cls: type) -> list[tuple[str, inspect.Parameter]]:
    """The parameters of ``cls``'s constructor after ``self``, but a ``*args``."""
    init = cls.__init__  # type: ignore[misc]  # the class's own constructor
    items = list(inspect.signature(init).parameters.items())[1:]
    return [(name, p) for name, p in items if p.kind is not p.VAR_POSITIONAL]


def _plain_attribute(cls: type, name: str) -> bool:
    """Whether ``name`` is declared on ``cls`` as data (an annotation or a property), not a
    method."""
    if _declared(cls, name):
        return True
    return isinstance(getattr(cls, name, None), property)


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


class _BoundClass:
    """``cls._bound_class``: :func:`bound_base` of the class it is read on."""

    def __get__(self, obj: Any, owner: type) -> type | None:
        return bound_base(owner)


def _declared(cls: type, name: str) -> bool:
    """Whether ``cls`` or a base annotates ``name`` at class level (an attribute its
    ``__init__`` sets)."""
    return any(name in vars(base).get("__annotations__", {}) for base in cls.__mro__)


class PythonObject:
    """Copies that do not share the C++ engine, pickling through the configuration, and no
    silent attribute for a misspelt or unknown name (see :mod:`tendonsheath._util.pyobject`).

    A subclass whose state holds C++ engines defines ``_recipe()``: a picklable
    ``(callable, args)`` that builds an equal object at rest. Without one, the instance's
    attributes are pickled as they are (each must pickle).

    ``_bound_class`` is the bound C++ class a subclass is built on (None: pure Python), for the
    calls that must reach it past a Python method of the same name
    (``self._bound_class.step(self, ...)``).

    A public attribute can be set only where the class declares it: a class attribute, a
    class-level annotation (for those its ``__init__`` sets), or one the instance already
    has."""

    _bound_class: ClassVar[Any] = _BoundClass()

    def _recipe(self) -> tuple[Callable, tuple]:
        return from_state, (type(self), dict(vars(self)))

    # -- configuration (scikit-learn's idiom) ----------------------------------------------
    def _configuration(self) -> dict[str, Any]:
        """The values the object was configured with, by constructor argument name (the hook
        :meth:`get_params` reads; a model gives its parameters and options, a plant its
        constructor's arguments, a compensator its settings). An argument missing here is
        read as the attribute of its name, where the object has one."""
        return {}

    def get_params(self, deep: bool = False) -> dict[str, Any]:
        """The constructor's arguments, by the names of its signature (scikit-learn's
        ``get_params``): ``type(obj)(**obj.get_params())`` builds an equal object.

        Parameters
        ----------
        deep : bool, default False
            Accepted for scikit-learn's ``clone``; a nested model or compensator is returned
            as the object it is.

        Returns
        -------
        dict
            Each argument's value (a copy of the dict; the values are not copied).
        """
        values = self._configuration()
        out: dict[str, Any] = {}
        takes_more = False
        for name, p in _constructor_parameters(type(self)):
            if p.kind is p.VAR_KEYWORD:
                takes_more = True
            elif name in values:
                out[name] = values[name]
            elif name in vars(self) or _plain_attribute(type(self), name):
                out[name] = getattr(self, name)
        if takes_more:  # the rest of the configuration goes through **kwargs
            out.update({k: v for k, v in values.items() if k not in out})
        return out

    def set_params(self, **changes: Any) -> Self:
        """A new object with some constructor arguments changed (scikit-learn's
        ``set_params``, except that this object is left unchanged: its C++ core is fixed at
        construction, so the change makes a new one; use the returned object, as
        ``clone(est).set_params(...)`` does).

        Parameters
        ----------
        **changes
            Constructor arguments by name, with their new values.

        Returns
        -------
        object
            A new object of the same class.

        Raises
        ------
        TypeError
            A name the constructor does not take.
        """
        parameters = dict(_constructor_parameters(type(self)))
        if not any(p.kind is p.VAR_KEYWORD for p in parameters.values()):
            unknown = sorted(set(changes) - set(parameters))
            if unknown:
                raise TypeError(
                    f"{type(self).__name__}.set_params: unknown argument(s) {unknown}; "
                    f"expected {list(parameters)}"
                )
        return type(self)(**{**self.get_params(), **changes})

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
        if not (known or _declared(type(self), name)):
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
