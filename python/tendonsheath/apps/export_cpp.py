"""A saved model or compensator as a C++ header of constexpr parameters, for targets with no
file system (``tendonsheath export FILE --cpp OUT.hpp``).

Fixed-size parameters become a ``constexpr`` params struct of the real-time core (filled by a
constexpr lambda: C++17 has no designated initialisers); a Prandtl-Ishlinskii operator's
thresholds and weights become constexpr arrays, from which the user fills the params struct (its
vectors allocate, once, at construction). Numbers are written with Python's shortest round-trip
repr, so the C++ doubles equal Python's bit for bit.

The header names the class to build (``Model`` or ``Compensator``, an alias of the core's class)
and builds it with ``make_model()`` or ``make_compensator()``: a ``tendonsheath::Result`` holding
the object or the message of a bad parameter, with or without C++ exceptions (``-fno-exceptions``,
docs/cpp-without-exceptions.md). The compensators whose step takes more than (y_d, dt)
(LoadCompensated, CoupledFeedforward) are written by export_cpp_multi.py.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

from .._util.cpp_literal import cpp_number as _number

# C++ keywords and alternative tokens (C++20's too: a header outlives its standard), and the
# namespaces a header must not open
_CPP_RESERVED = frozenset(
    """alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t
    char16_t char32_t class compl concept const consteval constexpr constinit const_cast
    continue co_await co_return co_yield decltype default delete do double dynamic_cast else
    enum explicit export extern false float for friend goto if inline int long mutable
    namespace new noexcept not not_eq nullptr operator or or_eq private protected public
    register reinterpret_cast requires return short signed sizeof static static_assert
    static_cast struct switch template this thread_local throw true try typedef typeid
    typename union unsigned using virtual void volatile wchar_t while xor xor_eq std
    tendonsheath""".split()
)
_EXPORTED_COMPENSATORS = ("InverseFeedforward", "CurveAngleFeedforward", "ContinuumFeedforward")
# those whose step takes more than (y_d, dt): export_cpp_multi.py writes them
_MULTI_INPUT_COMPENSATORS = ("LoadCompensated", "CoupledFeedforward")


def _literal(value) -> str:
    if isinstance(value, str):  # an enum value, already C++
        return value
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int) and not isinstance(value, bool):
        return str(value)
    return _number(value)


def _struct(cpp_type: str, fields: dict) -> str:
    body = "".join(f"  p.{k} = {_literal(v)};\n" for k, v in fields.items())
    return (
        f"inline constexpr tendonsheath::{cpp_type} params = [] {{\n"
        f"  tendonsheath::{cpp_type} p{{}};\n{body}  return p;\n}}();\n"
    )


def _limits_fields(limits) -> dict:
    return {f"limits.{k}": getattr(limits, k) for k in ("min", "max", "max_rate")}


def _array(name: str, values) -> str:
    return f"inline constexpr double {name}[] = {{{', '.join(_number(v) for v in values)}}};\n"


# the PrandtlIshlinskiiParams the exported arrays hold (vectors: they allocate, once)
_PI_PARAMS = (
    "  tendonsheath::PrandtlIshlinskiiParams p{{std::begin(thresholds), std::end(thresholds)},\n"
    "                                         {std::begin(weights), std::end(weights)}};\n"
)


def _builder(role: str, cpp_class: str, args: str, setup: str = "") -> str:
    """The class to build (``role``: Model or Compensator, an alias of ``cpp_class``) and the
    function that builds it with or without exceptions from the constants above it: ``setup``
    then ``make<role>(args)``."""
    make = f"make_{role.lower()}"
    return (
        f"\n// The class to build: {role}, that is tendonsheath::{cpp_class}.\n"
        f"// {make}() builds it with or without C++ exceptions (g++ -fno-exceptions): a bad\n"
        "// parameter comes back as an error value, not a throw (tendonsheath/result.hpp):\n"
        f"//   auto built = {make}();\n"
        '//   if (!built.ok()) { /* built.error(): "<class>: <what>" */ }\n'
        f"//   {role}& obj = built.value();\n"
        f"using {role} = tendonsheath::{cpp_class};\n"
        f"inline tendonsheath::Result<{role}> {make}() {{\n"
        f"{setup}  return tendonsheath::make<{role}>({args});\n}}\n"
    )


def _pi_arrays(model) -> str:
    p = model.params
    return (
        "// tendonsheath::PrandtlIshlinskiiParams{{std::begin(thresholds), std::end(thresholds)},\n"
        "//                                       {std::begin(weights), std::end(weights)}}\n"
        + _array("thresholds", p["thresholds"])
        + _array("weights", p["weights"])
    )


def _scalar_model_body(model) -> tuple[str, str] | None:
    """A model of the core's list whose every table row is a number: its params
    struct filled row by row from Python's values; None for any other model."""
    struct = getattr(type(model), "_core_params", None)
    if struct is None or not hasattr(model, "params_struct"):
        return None
    values = model.params_struct()
    fields = {r["name"]: getattr(values, r["name"]) for r in struct.fields()}
    if not all(isinstance(v, int | float) for v in fields.values()):
        return None
    kind = type(model).__name__
    body = _struct(struct.__name__, fields) + _builder("Model", kind, "params")
    return "models/model_list.hpp", body


def _model_body(model) -> tuple[str, str]:
    """(header to include, declarations) for a model."""
    kind = type(model).__name__
    if kind == "Backlash":
        body = _struct("BacklashParams", model.params)
        return "models/backlash.hpp", body + _builder("Model", "Backlash", "params")
    if kind == "BoucWenBacklash":
        options = {"max_step": model.options["max_step"]}
        options["max_substeps"] = int(model.options["max_substeps"])
        body = _struct("BoucWenBacklashParams", {**model.params, **options})
        return "models/bouc_wen_backlash.hpp", body + _builder("Model", "BoucWenBacklash", "params")
    if kind == "PrandtlIshlinskii":
        body = _pi_arrays(model) + _builder("Model", "PrandtlIshlinskii", "p", _PI_PARAMS)
        return "models/prandtl_ishlinskii.hpp", body
    scalar = _scalar_model_body(model)
    if scalar is not None:
        return scalar
    raise ValueError(
        "export --cpp writes Backlash, BoucWenBacklash and PrandtlIshlinskii models, any model "
        "of the core's list whose parameters are numbers, and the "
        "InverseFeedforward, CurveAngleFeedforward, ContinuumFeedforward, LoadCompensated and "
        f"CoupledFeedforward compensators (got {kind})" + _MODEL_NOTE.get(kind, "")
    )


def _inverse_body(ff) -> tuple[str, str]:
    """The direct D.2 and exact PI inverses (and a Scaled map around them) as constexpr params;
    the input range as two constants. The other inverses: load their JSON with io/json.hpp."""
    model = ff.model
    map_values = None
    if type(model).__name__ == "Scaled":
        map_values, model = tuple(model.map.values()), model.inner
    kind = type(model).__name__
    exact_pi = kind == "PrandtlIshlinskii" and model.params["thresholds"][0] == 0.0
    if kind not in ("Backlash", "BoucWenBacklash") and not exact_pi:
        raise ValueError(
            f"export --cpp writes the InverseFeedforward of a Backlash, BoucWenBacklash or "
            f"PrandtlIshlinskii (thresholds[0] = 0), or a Scaled one of them (got one of a "
            f"{kind}): load its JSON with tendonsheath/io/json.hpp instead"
        )
    if kind in ("Backlash", "BoucWenBacklash"):
        include, body = _direct_inverse(ff, model, map_values)
        build = _builder("Compensator", "BacklashInverseFeedforward", "params")
    else:
        include, body = _pi_inverse(ff, model, map_values)
        build = _builder("Compensator", "PrandtlIshlinskiiFeedforward", "p, limits", _PI_PARAMS)
    return include, body + _range_constants(ff) + _map_constants(map_values) + build


def _inner_limits(ff, map_values):
    lim = ff.limits
    if map_values is None:
        return {k: getattr(lim, k) for k in ("min", "max", "max_rate")}
    x_c, x_s = map_values[0], map_values[1]
    return {
        "min": (lim.min - x_c) / x_s,
        "max": (lim.max - x_c) / x_s,
        "max_rate": lim.max_rate / x_s,
    }


def _direct_inverse(ff, model, map_values) -> tuple[str, str]:
    from ..models import Backlash  # its rows begin BacklashInverseParams' table (rows_of)

    fields = {k: model.params[k] for k in Backlash.param_names}
    smoothing = ff.smoothing if map_values is None else ff.smoothing / abs(map_values[3])
    limits = {f"limits.{k}": v for k, v in _inner_limits(ff, map_values).items()}
    fields = {**fields, "smoothing": smoothing, **limits}
    return "compensators/inverse_feedforward.hpp", _struct("BacklashInverseParams", fields)


def _pi_inverse(ff, model, map_values) -> tuple[str, str]:
    limits = _struct("CommandLimits", _inner_limits(ff, map_values))
    return "compensators/inverse_feedforward.hpp", _pi_arrays(model) + limits.replace(
        " params =", " limits ="
    )


def _range_constants(ff) -> str:
    lo, hi = ff.command_range
    return (
        "// the commands allowed (the identified input range and its margin; +-inf: none):\n"
        "// hold the command inside [input_min, input_max]; a PrandtlIshlinskiiFeedforward\n"
        "// takes it before stepping: c.set_range({lo, hi}), in its own (inner) units\n"
        "// ((input_min - input_offset) / input_scale ... of a Scaled model)\n"
        f"inline constexpr double input_min = {_number(lo)};\n"
        f"inline constexpr double input_max = {_number(hi)};\n"
    )


def _map_constants(map_values) -> str:
    if map_values is None:
        return ""
    names = ("input_offset", "input_scale", "output_offset", "output_gain")
    consts = "".join(
        f"inline constexpr double {n} = {_number(v)};\n"
        for n, v in zip(names, map_values, strict=True)
    )
    note = (
        "// command = input_offset\n"
        "//   + input_scale * inverse.step((y_d - output_offset) / output_gain, dt)\n"
    )
    return note + consts


# the compensators tendonsheath/io/json.hpp reads from their JSON file instead
_JSON_LOADER_NOTE = {
    k: ": load its JSON with tendonsheath/io/json.hpp instead"
    for k in ("EncoderLoop", "TipLoop", "LearnedFeedforward")
}
# the models whose inverse steps more than (y_d, dt): save that compensator, export it
_MODEL_NOTE = {
    "Loaded": ": its inverse takes the measured load each cycle; save "
    "ts.compensate.LoadCompensated(model).to_json(...) and export that file",
    "Coupled": ": its inverse steps all joints together; save "
    "ts.compensate.CoupledFeedforward(model).to_json(...) and export that file",
}


def _compensator_body(ff) -> tuple[str | tuple[str, ...], str]:
    kind = type(ff).__name__
    if kind in _MULTI_INPUT_COMPENSATORS:
        from .export_cpp_multi import coupled_feedforward_body, load_compensated_body

        made = (load_compensated_body if kind == "LoadCompensated" else coupled_feedforward_body)(
            ff
        )
        return (made[0], "compensators/make_model_inverse.hpp"), made[1]
    if kind not in _EXPORTED_COMPENSATORS:
        raise ValueError(
            "export --cpp writes the InverseFeedforward, CurveAngleFeedforward, "
            "ContinuumFeedforward, LoadCompensated and CoupledFeedforward compensators "
            f"(got {kind})" + _JSON_LOADER_NOTE.get(kind, "")
        )
    if kind == "InverseFeedforward":
        return _inverse_body(ff)
    s = ff.params
    limits = _limits_fields(s.pop("limits"))
    if kind == "CurveAngleFeedforward":  # the C++ fields are the Python names
        body = _struct("CurveAngleFeedforwardParams", {**s, **limits})
        build = _builder("Compensator", "CurveAngleFeedforward", "params")
        return "compensators/curve_angle_feedforward.hpp", body + build
    s["mode"] = "tendonsheath::ContinuumMode::" + s["mode"].capitalize()
    body = _struct("ContinuumFeedforwardParams", {**s, **limits})
    build = _builder("Compensator", "ContinuumFeedforward", "params")
    return "compensators/continuum_feedforward.hpp", body + build


def _check_namespace(given: str | None, path: Path) -> None:
    """A C++ namespace name: an identifier, not a keyword nor a reserved one ("__", "_X");
    without ``given``, the one made of the file's stem."""
    name = given or re.sub(r"\W", "_", path.stem)
    how = "" if given else f" (made of the file name {path.name}: give --namespace NAME)"
    if not re.fullmatch(r"[A-Za-z_]\w*", name):
        raise ValueError(f"export --cpp: {name!r} is not a C++ namespace name{how}")
    if name in _CPP_RESERVED:
        raise ValueError(
            f"export --cpp: {name!r} is a C++ keyword or a reserved namespace, not a free "
            f"namespace name{how}"
        )
    if "__" in name or re.match(r"_[A-Z]", name):
        raise ValueError(
            f"export --cpp: {name!r} is reserved to the C++ implementation (a double "
            f"underscore, or an underscore and a capital letter at the start){how}"
        )


def cpp_header(source: str | Path, namespace: str | None = None) -> str:
    """The header text for a model or compensator JSON file, its declarations in `namespace`
    (default: the file's stem).

    Parameters
    ----------
    source : str or Path
        A model or compensator saved with ``to_json``.
    namespace : str, optional
        A C++ namespace name (default the file's stem, non-word characters as "_").

    Returns
    -------
    str
        The header's text.

    Raises
    ------
    ValueError
        An invalid namespace name, or a file that is not a model or compensator.
    """
    from ..compensate import load_compensator
    from ..models import load_model

    path = Path(source)
    _check_namespace(namespace, path)
    namespace = namespace or re.sub(r"\W", "_", path.stem)
    try:
        fmt = json.loads(path.read_text(encoding="utf-8-sig")).get("format")
    except (OSError, ValueError, AttributeError) as exc:
        raise ValueError(f"{path}: not a model or compensator JSON file ({exc})") from None
    obj: object  # a compensator or a model
    include: str | tuple[str, ...]  # the core's header(s) it builds from
    if fmt == "tendonsheath.compensator":
        obj = load_compensator(path)
        include, body = _compensator_body(obj)
    elif fmt == "tendonsheath.coupled_model":
        raise ValueError(
            f"export --cpp: {path.name} holds a Coupled model" + _MODEL_NOTE["Coupled"]
        )
    else:
        obj = load_model(path)
        include, body = _model_body(obj)
    kind = type(obj).__name__
    ours = include if isinstance(include, tuple) else (include,)
    # the multi-input compensators (two core headers) also size vectors
    std = ("cstddef", "iterator", "limits", "vector") if len(ours) > 1 else ("iterator", "limits")
    return (
        f"// Generated by `tendonsheath export {path.name} --cpp`: {kind}. Do not edit.\n"
        "#pragma once\n\n"
        + "".join(f"#include <{h}>\n" for h in std)
        + "".join(f"#include <tendonsheath/{h}>\n" for h in ours)
        + "#include <tendonsheath/result.hpp>\n\n"
        f"namespace {namespace} {{\n\n{body}\n}}  // namespace {namespace}\n"
    )


__all__ = ["cpp_header"]
