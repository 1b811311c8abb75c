"""Common behaviour of the hysteresis models: parameters, simulate, streaming, JSON."""

from __future__ import annotations

import inspect
import json
import math
import numbers
from contextlib import contextmanager
from pathlib import Path
from typing import Any, ClassVar, Self

import numpy as np

from .._util.args import core_errors_as, is_format_version, renamed
from .._util.arrays import as_time_and_signal, checked_dt
from .._util.atomic import write_text
from .._util.json_source import naming_the_file, read_json_source
from .._util.pyobject import PythonObject, bound_attribute
from .._util.typing import ArrayLike
from .._util.units import warn_unit_slips
from ..control_interop import _ControlBlock
from ..simulation_result import SimulationResult
from ..status import Status

FORMAT_NAME = "tendonsheath.model"
FORMAT_VERSION = 1

# the model classes a saved file may name, by class name: tendonsheath.models registers the
# ones it exports (register_models), a user's own model class is registered the same way
_REGISTRY: dict[str, type[HysteresisModel]] = {}


def register_models(*classes: Any) -> None:
    """Let saved files (:func:`load_model`), ``identify`` and ``compare`` name these model
    classes by their class names; anything that is not a model class is skipped.

    Parameters
    ----------
    *classes : type
        Model classes (subclasses of :class:`HysteresisModel`).

    Returns
    -------
    None
    """
    for cls in classes:
        if isinstance(cls, type) and issubclass(cls, HysteresisModel):
            _REGISTRY[cls.__name__] = cls


def _as_result(model: HysteresisModel, t: Any, x: Any, out: Any) -> SimulationResult:
    """A model's ``_simulate`` output as a :class:`SimulationResult`: the output with this
    model's own t and x (a wrapper's inner model saw transformed ones) and each sample's
    Status flags. ``out`` is the output, ``(output, flags)`` or a result with its flags."""
    y, flags = out if isinstance(out, tuple) else (out, None)
    if flags is None and isinstance(y, SimulationResult):
        flags = y.status
    if flags is None and model.reports_status:  # a model with a status but no flags: all OK
        flags = np.zeros(np.size(y), dtype=np.uint8)
    ts = None if t is None else np.asarray(t, dtype=float)
    return SimulationResult(y, t=ts, input=np.asarray(x, dtype=float), status=flags)


class HysteresisModel(PythonObject, _ControlBlock):
    """A single-input single-output model; most are a real-time C++ class.

    A model with a C++ core subclasses the bound class too (``class Backlash(HysteresisModel,
    core.Backlash)``): the model *is* the C++ object, so it goes to the core's functions as it
    is. Subclasses declare ``_core_params`` (the C++ parameter struct) and ``param_names`` (the
    identifiable parameters, in order), and may list ``option_names`` (numerical settings that
    are not identified). A model without one (a chain, a linear block) overrides ``_simulate``
    (the hook :meth:`simulate` calls), ``step`` and ``reset``; a model whose file holds other
    fields overrides ``_dict_fields`` (the hook :meth:`to_dict` calls).

    Parameters
    ----------
    *args
        The parameters in the order of the signature: taken by a model built from its table
        (``models/_param_table.py``), which names them; refused here.
    **values
        The subclass's parameters (``param_names``) and options (``option_names``) by name; a
        name left out or given as None keeps the C++ default.

    Raises
    ------
    ValueError
        An unknown name, a value of the wrong type, or a value the C++ core rejects (the
        message names the parameter).
    """

    _core_params: ClassVar[Any]
    param_names: ClassVar[tuple[str, ...]] = ()
    option_names: ClassVar[tuple[str, ...]] = ()
    rate_independent: bool = True  # per instance for Chain and Scaled (their parts decide)
    # status() and simulate(...).status report each step's Status (false: linear blocks, whose
    # result's status is None)
    reports_status: ClassVar[bool] = True
    # parameters whose default is derived from the others' (None in the signature; _core_values
    # derives it)
    derived_params: ClassVar[tuple[str, ...]] = ()
    # parameters a saved file may hold as null (all others must be present and not null)
    nullable_params: ClassVar[tuple[str, ...]] = ()
    # parameters added after files were saved: a file without one loads with the table's default
    added_params: ClassVar[tuple[str, ...]] = ()
    # parameters whose saved value is text (a name), not a number
    text_params: ClassVar[tuple[str, ...]] = ()
    # signal names of to_control()'s system
    control_inputs: tuple[str, ...] = ("x",)  # per instance for Scaled (its inner model's)
    control_output: ClassVar[str] = "y"
    # saved files' old parameter keys (old -> new): such files still load (data, not API: the
    # constructor and with_params take only the new names)
    renamed_params: ClassVar[dict[str, str]] = {}
    # the range (lo, hi) of the inputs the model was identified on (all recordings, data units),
    # set by identify; None when unknown. Saved by to_dict as "input_range": [lo, hi].
    input_range: tuple[float, float] | None = None

    def __init__(self, *args: Any, **values: Any) -> None:
        if args:  # a model built from its table maps them to names first (_param_table.py)
            raise TypeError(f"{type(self).__name__}: give the parameters by name")
        unknown = set(values) - set(self.param_names) - set(self.option_names)
        if unknown:  # an unknown keyword: TypeError, as Python says for any function
            raise TypeError(
                f"{type(self).__name__}: unknown parameter(s) {sorted(unknown)}; "
                f"expected {list(self.param_names + self.option_names)}"
            )
        struct = self._core_params()
        for key, value in self._core_values(values).items():
            if value is None:
                continue
            try:
                setattr(struct, key, value)
            except TypeError:
                raise _field_error(type(self).__name__, key, value) from None
        with core_errors_as(type(self).__name__):  # the core names the parameter as Python does
            self._bound_class.__init__(self, struct)
        warn_unit_slips(type(self).__name__, struct)

    @classmethod
    def _core_values(cls, values: dict[str, Any]) -> dict[str, Any]:
        """The values as the C++ parameter struct holds them, each under its Python name (a
        model whose struct holds a value otherwise, a code or a nested struct, converts it)."""
        return dict(values)

    @classmethod
    def _python_value(cls, name: str, value: Any) -> Any:
        """A value of the C++ struct's field ``name`` as Python shows it (in ``params``,
        ``options``, the signature's defaults): a model whose field holds a code overrides it."""
        return _plain(value)

    # -- parameters ------------------------------------------------------------------
    @property
    def params(self) -> dict[str, Any]:
        """The identifiable parameters, as a dict (a copy)."""
        s = self.params_struct()
        return {k: self._python_value(k, getattr(s, k)) for k in self.param_names}

    @property
    def options(self) -> dict[str, Any]:
        """The numerical options (not identified), as a dict (a copy)."""
        s = self.params_struct()
        return {k: self._python_value(k, getattr(s, k)) for k in self.option_names}

    def params_struct(self) -> Any:
        """The parameters and options as the C++ core holds them (its ``*Params`` struct, a
        copy), for the core's own functions.

        Returns
        -------
        object
            The bound parameter struct, e.g. :class:`~tendonsheath._core.BacklashParams`.

        Raises
        ------
        TypeError
            A model without a C++ core (a chain, a linear block).
        """
        if self._bound_class is None:
            raise TypeError(f"{type(self).__name__} has no C++ core and no parameter struct")
        return bound_attribute(self, "params")

    def with_params(self, **changes: Any) -> Self:
        """A new model with some parameters changed (options kept).

        Parameters
        ----------
        **changes
            Parameters or options by name, with their new values.

        Returns
        -------
        HysteresisModel
            A new model of the same class; this one is unchanged.
        """
        values = {**self.params, **self.options, **changes}
        return type(self)(**values)

    # -- simulation ------------------------------------------------------------------
    def simulate(
        self, t: ArrayLike | None, x: ArrayLike, *args: Any, **kwargs: Any
    ) -> SimulationResult:
        """Output for the input samples x at times t (t may be None when rate-independent).

        Starts from the model's initial state; does not disturb the streaming state. The
        model computes the output in :meth:`_simulate` (its own further inputs, such as a
        CurveAngleModel's ``curve_angle``, are documented there); this method returns it as a
        :class:`SimulationResult`.

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s), increasing; None for a rate-independent model.
        x : array_like of float, shape (n,)
            Input samples (the model's input unit, e.g. rad or m).
        *args
            The model's further inputs by position (see its ``_simulate``).
        **kwargs
            The model's further inputs by name (see its ``_simulate``).

        Returns
        -------
        SimulationResult, shape (n,)
            Output samples (an array), with ``t``, ``input``, ``success``, ``message`` and
            ``status`` (each sample's :class:`~tendonsheath.Status` bits, uint8; None for a
            model that reports no status).

        Raises
        ------
        ValueError
            t missing for a rate-dependent model, or t and x of different lengths, not finite
            or t not increasing.
        """
        return _as_result(self, t, x, self._simulate(t, x, *args, **kwargs))

    def _simulate(self, t: ArrayLike | None, x: ArrayLike) -> Any:
        """The output for :meth:`simulate` (the hook a model class overrides, with its own
        further inputs after ``t`` and ``x``): the output samples, ``(output, flags)`` or a
        :class:`SimulationResult` with its ``status``; :meth:`simulate` adds t and x.

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s), increasing; None for a rate-independent model.
        x : array_like of float, shape (n,)
            Input samples.

        Returns
        -------
        numpy.ndarray, tuple or SimulationResult
            The output samples (and each sample's Status flags).
        """
        if t is None and not self.rate_independent:
            raise ValueError(f"{type(self).__name__} is rate-dependent: t is required")
        ts, xs = as_time_and_signal(t, x)
        return self._bound_class.simulate(self, ts, xs, True)

    def reset(self) -> None:
        """Forget the streaming state; the next step() starts afresh.

        Returns
        -------
        None
        """
        self._bound_class.reset(self)

    def step(self, x: float, dt: float = 0.0) -> float:
        """Advance one sample (streaming).

        Parameters
        ----------
        x : float
            The input sample.
        dt : float, default 0.0
            Time since the previous sample (s); ignored by rate-independent models.

        Returns
        -------
        float
            The output sample.
        """
        dt = checked_dt(dt)
        return self._bound_class.step(self, float(x), float(dt))

    def status(self) -> Status:
        """The last step's :class:`~tendonsheath.Status` (held input, clamped, ...).

        Returns
        -------
        Status
            The flags of the last :meth:`step`.

        Raises
        ------
        TypeError
            The model has no real-time core and reports no status (linear blocks).
        """
        if not self.reports_status:
            raise TypeError(f"{type(self).__name__} has no real-time core and reports no status")
        return Status(self._bound_class.status(self))

    # -- persistence -----------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """The model as a JSON-ready dict (format, version, model, params, options; its
        ``input_range`` when it has one).

        Returns
        -------
        dict
            What :meth:`from_dict` and :func:`load_model` read back.
        """
        data = self._dict_fields()
        if self.input_range is not None and "input_range" not in data:
            data = {**data, "input_range": [float(v) for v in self.input_range]}
        return data

    def _dict_fields(self) -> dict[str, Any]:
        """The model's own fields of :meth:`to_dict` (the hook a model class whose file holds
        other fields overrides, e.g. a chain's parts): format, version, model, params and
        options; :meth:`to_dict` adds the input range.

        Returns
        -------
        dict
            The fields, JSON-ready.
        """
        return {
            "format": FORMAT_NAME,
            "version": FORMAT_VERSION,
            "model": type(self).__name__,
            "params": self.params,
            "options": self.options,
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> HysteresisModel:
        """The model saved in ``data`` (as written by :meth:`to_dict`).

        Parameters
        ----------
        data : dict
            A saved model: format, version, model, params and options.

        Returns
        -------
        HysteresisModel
            The saved model's class, with its parameters.

        Raises
        ------
        ValueError
            Not a model file, an unknown version or model, a model of another class than
            ``cls``, or a missing, null, unknown or boolean parameter.
        """
        model_cls = model_class_from_dict(data)
        if cls is not HysteresisModel and not issubclass(model_cls, cls):
            raise ValueError(f"file holds a {model_cls.__name__}, not a {cls.__name__}")
        input_range = saved_input_range(model_cls.__name__, data)
        if hasattr(model_cls, "_from_parts"):  # composite models (Chain, ...)
            with _file_error(model_cls.__name__):
                model = model_cls._from_parts(data)
        elif model_cls is not cls and "from_dict" in vars(model_cls):  # its own reader
            model = model_cls.from_dict(data)
        else:
            with _file_error(model_cls.__name__):
                model = _build_saved(model_cls, data)
        if input_range is not None:
            model.input_range = input_range
        _refuse_unknown_keys(model_cls.__name__, data, model.to_dict())
        return model

    def to_json(self, path: str | Path | None = None) -> str:
        """The model as JSON text; also written to `path` when one is given.

        Parameters
        ----------
        path : str or Path, optional
            A file to write the JSON to (atomically).

        Returns
        -------
        str
            The JSON text.
        """
        text = json.dumps(self.to_dict(), indent=2)
        if path is not None:
            write_text(path, text + "\n")
        return text

    def _configuration(self) -> dict[str, Any]:
        # get_params (tendonsheath._util.pyobject): the parameters and options; a composite
        # model's parts are its attributes
        return {**self.params, **self.options}

    def _recipe(self):
        # pickled as its saved file: an equal model at rest (tendonsheath._util.pyobject)
        return load_model, (self.to_dict(),)

    def __eq__(self, other) -> bool:
        return type(self) is type(other) and self.to_dict() == other.to_dict()

    # A model is a value: equal parameters and options make equal models, whatever the streaming
    # state (reset/step move only that, never the parameters), so the hash follows to_dict().
    def __hash__(self) -> int:
        return hash((type(self).__name__, _frozen(self.to_dict())))

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={_short(v)}" for k, v in self.params.items())
        return f"{type(self).__name__}({inner})"


def split_wrapped_changes(
    changes: dict[str, Any], prefix: str, own: dict[str, Any], owner: str
) -> tuple[dict[str, Any], dict[str, Any]]:
    """``with_params`` of a model around another (Scaled, Loaded): the changes named
    ``<prefix>.<name>`` for the wrapped model, and ``own`` updated with the others (TypeError
    naming an unknown one)."""
    inner, mine = {}, dict(own)
    for key, value in changes.items():
        if key.startswith(prefix + "."):
            inner[key.removeprefix(prefix + ".")] = value
        elif key in mine:
            mine[key] = value
        else:
            raise TypeError(f"{owner}: unknown parameter {key!r}; {prefix}.<name> or {tuple(own)}")
    return inner, mine


def saved_input_range(name: str, data: dict[str, Any]) -> tuple[float, float] | None:
    """The optional "input_range" of a saved model: [lo, hi] with finite lo <= hi, or absent
    (a file written before it: None)."""
    value = data.get("input_range")
    if value is None:
        return None
    ok = isinstance(value, list) and len(value) == 2
    ok = ok and all(isinstance(v, int | float) and not isinstance(v, bool) for v in value)
    if not ok or not (math.isfinite(value[0]) and math.isfinite(value[1]) and value[0] <= value[1]):
        raise ValueError(
            f"{name} file: 'input_range' must be [lo, hi] with finite lo <= hi (got {value!r})"
        )
    return (float(value[0]), float(value[1]))


# what `identify` and `compare` write beside a model in its file (read by `predict`)
_ANNOTATIONS = ("data", "fit", "validation", "input_range")


def _refuse_unknown_keys(name: str, data: dict[str, Any], written: dict[str, Any]) -> None:
    """A key the model does not write (a typo such as "option") would be ignored silently."""
    unknown = sorted(set(data) - set(written) - set(_ANNOTATIONS))
    if unknown:
        raise ValueError(
            f"{name} file: unknown key(s) {unknown}; expected {sorted(set(written))} "
            f"(and {list(_ANNOTATIONS)})"
        )


def _field_error(name: str, key: str, value) -> Exception:
    """What a value the C++ field refused is: an integer too large for it (ValueError) or a
    value of the wrong type (TypeError)."""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        digits = int(int(value).bit_length() * math.log10(2)) + 1
        shown = str(value) if digits <= 24 else f"an integer of about {digits} digits"
        return ValueError(f"{name}: {key} = {shown} is out of the range of its field")
    return TypeError(f"{name}: {key} has the wrong type (got {type(value).__name__} {value!r})")


def _build_saved(model_cls, data: dict[str, Any]) -> HysteresisModel:
    values = {**_saved_params(model_cls, data), **_saved_options(model_cls, data)}
    known = set(model_cls.param_names) | set(model_cls.option_names)
    unknown = sorted(set(values) - known)
    if unknown:
        raise ValueError(
            f"{model_cls.__name__}: unknown parameter(s) {unknown}; expected {sorted(known)}"
        )
    return model_cls(**values)


@contextmanager
def _file_error(name: str):
    """A value of the wrong type in a saved file is a bad file (ValueError), not a bad call;
    so is an integer too large for a float (OverflowError)."""
    try:
        yield
    except TypeError as err:
        raise ValueError(f"{name} file: {err}") from None
    except OverflowError as err:
        raise ValueError(f"{name} file: a number is too large ({err})") from None


def model_class_from_dict(data: dict[str, Any]) -> type[HysteresisModel]:
    if not isinstance(data, dict) or data.get("format") != FORMAT_NAME:
        raise ValueError(f"not a tendonsheath model file (missing format '{FORMAT_NAME}')")
    version = data.get("version")
    if not is_format_version(version, FORMAT_VERSION):
        raise ValueError(f"unsupported model file version {version!r} (expected {FORMAT_VERSION})")
    name = data.get("model")
    if not isinstance(name, str) or name not in _REGISTRY:
        raise ValueError(f"unknown model {name!r}; known: {sorted(_REGISTRY)}")
    return _REGISTRY[name]


def _saved_params(model_cls, data: dict[str, Any]) -> dict[str, Any]:
    """The saved parameters: every one present, none null (unless nullable), none boolean."""
    name = model_cls.__name__
    if "params" not in data:
        raise ValueError(f"{name} file: 'params' is missing")
    params = data["params"]
    if not isinstance(params, dict):
        raise ValueError(f"{name} file: 'params' must be an object (got {params!r})")
    try:
        params = renamed(name, params, model_cls.renamed_params)
    except TypeError as err:  # a parameter under its old and new names: a bad file
        raise ValueError(f"{name} file: {str(err).removeprefix(name + ': ')}") from None
    unknown = sorted(set(params) - set(model_cls.param_names) - set(model_cls.option_names))
    if unknown:
        raise ValueError(
            f"{name}: unknown parameter(s) {unknown}; expected {list(model_cls.param_names)}"
        )
    missing = [
        k for k in model_cls.param_names if k not in params and k not in model_cls.added_params
    ]
    if missing:
        raise ValueError(f"{name} file: parameter(s) {missing} missing from 'params'")
    for key, value in params.items():
        if value is None and key not in model_cls.nullable_params:
            raise ValueError(f"{name} file: parameter '{key}' is null")
        _check_not_bool(name, f"parameter '{key}'", value)
        if isinstance(value, str) and key not in model_cls.text_params:
            raise ValueError(f"{name} file: parameter '{key}' must be a number (got {value!r})")
    return params


def _saved_options(model_cls, data: dict[str, Any]) -> dict[str, Any]:
    """The saved options (each may be left out: its default); none null."""
    options = data.get("options", {})
    if not isinstance(options, dict):
        raise ValueError(f"{model_cls.__name__} file: 'options' must be an object")
    defaults = _option_defaults(model_cls)
    for key, value in options.items():
        if value is None:
            raise ValueError(f"{model_cls.__name__} file: option '{key}' is null")
        _check_option_type(model_cls.__name__, key, value, defaults.get(key))
    return options


def _option_defaults(model_cls) -> dict[str, Any]:
    """The constructor's default value of each keyword, where it has one."""
    try:
        signature = inspect.signature(model_cls.__init__)
    except (TypeError, ValueError):
        return {}
    return {k: p.default for k, p in signature.parameters.items() if p.default is not p.empty}


def _check_option_type(name: str, key: str, value, default) -> None:
    """A saved option of its default's kind: true/false for a flag (text "yes" would read as
    true), a number for a number, an integer a C++ field can hold."""
    if isinstance(default, bool) and not isinstance(value, bool):
        raise ValueError(f"{name} file: option '{key}' must be true or false (got {value!r})")
    number = isinstance(default, int | float) and not isinstance(default, bool)
    if number and (isinstance(value, bool) or not isinstance(value, int | float)):
        raise ValueError(f"{name} file: option '{key}' must be a number (got {value!r})")
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 2**63:
        raise _field_error(f"{name} file", f"option '{key}'", value)


def _check_not_bool(name: str, what: str, value) -> None:
    """true/false where a number belongs would silently become 1/0."""
    if isinstance(value, bool):
        raise ValueError(f"{name} file: {what} must be a number (got {json.dumps(value)})")
    if isinstance(value, list | tuple):
        for v in value:
            if isinstance(v, str):  # a list of numbers: "1.0" would read as 1.0
                raise ValueError(f"{name} file: {what} must hold numbers (got {v!r})")
            _check_not_bool(name, what, v)
    if isinstance(value, dict):
        for v in value.values():
            _check_not_bool(name, what, v)


def load_model(source: str | Path | dict) -> HysteresisModel:
    """Load a model saved with ``to_json``: a path, a JSON string or a dict.

    Parameters
    ----------
    source : str, Path or dict
        A path to a JSON file, JSON text, or the dict itself.

    Returns
    -------
    HysteresisModel
        The saved model.

    Raises
    ------
    ValueError
        An unreadable source or an invalid model file (the message says what is wrong).
    """
    data = read_json_source(source, "model")
    with naming_the_file(source):
        return HysteresisModel.from_dict(data)


def _frozen(value):
    """A hashable copy of a to_dict() value that compares (and hashes) like the original."""
    if isinstance(value, dict):
        return tuple(sorted((k, _frozen(v)) for k, v in value.items()))
    if isinstance(value, list | tuple):
        return tuple(_frozen(v) for v in value)
    return value


def _plain(value):
    if isinstance(value, list | tuple):
        return [float(v) for v in value]
    return value


def _short(value):
    if isinstance(value, list):
        return (
            "[" + ", ".join(f"{v:.4g}" for v in value[:4]) + (", ...]" if len(value) > 4 else "]")
        )
    if isinstance(value, float) and math.isfinite(value):
        return f"{value:.6g}"
    return repr(value)


__all__ = [
    "FORMAT_NAME",
    "FORMAT_VERSION",
    "HysteresisModel",
    "load_model",
    "model_class_from_dict",
    "register_models",
    "saved_input_range",
    "split_wrapped_changes",
]
