"""The headers of the compensators whose step takes more than (y_d, dt), for ``tendonsheath
export FILE --cpp OUT.hpp``: a LoadCompensated (``step(y_d, dt, load)``) and a
CoupledFeedforward (``step(y_d[J], u[J], dt)``), built from constants into the core's own
classes, as tendonsheath/io/json_multi_input.hpp builds them from the JSON file.

Each inverse (the base's, or each joint's) is written as the description Python's
InverseFeedforward hands the core (``InverseModel``: the model's parts, their parameter
structs field by field, the Chain's order and a Scaled model's map) and its settings
(``InverseSettings``), then built by ``make_model_inverse``: the one function that built
Python's inverse, so every model class it inverts exports (an AngleDependent excepted: its
laws are not fields). Numbers are Python's shortest round-trip repr: the C++ doubles are
Python's bit for bit.
"""

from __future__ import annotations

from collections.abc import Callable

from .._util.cpp_literal import cpp_number as _number

_MULTI_INPUT = "tendonsheath/io/json_multi_input.hpp"


def _fields(obj) -> list[str]:
    """The read-write fields of a bound parameter struct (its properties), in name order."""
    names: set[str] = set()
    for cls in type(obj).__mro__:
        names.update(k for k, v in vars(cls).items() if isinstance(v, property))
    return sorted(names)


def _assignments(target: str, obj, refuse: Callable[[str], ValueError]) -> str:
    """C++ statements setting every field of the bound struct ``obj`` on ``target``."""
    lines = []
    for name in _fields(obj):
        value, lhs = getattr(obj, name), f"{target}.{name}"
        if isinstance(value, bool):
            lines.append(f"  {lhs} = {'true' if value else 'false'};\n")
        elif isinstance(value, int):
            lines.append(f"  {lhs} = {value};\n")
        elif isinstance(value, float):
            lines.append(f"  {lhs} = {_number(value)};\n")
        elif isinstance(value, list) and all(isinstance(v, float | int) for v in value):
            lines.append(f"  {lhs} = {{{', '.join(_number(v) for v in value)}}};\n")
        elif _fields(value):
            lines.append(_assignments(lhs, value, refuse))
        else:
            raise refuse(f"its field {lhs} ({type(value).__name__})")
    return "".join(lines)


def _refusal(kind: str, what: str) -> Callable[[str], ValueError]:
    def refuse(detail: str) -> ValueError:
        return ValueError(
            f"export --cpp cannot write the inverse of a {what} as constants ({detail}): "
            f"load the {kind} JSON with {_MULTI_INPUT} instead"
        )

    return refuse


def _inverse_function(name: str, inverse, kind: str) -> str:
    """An inline function ``name()`` building the ModelInverse of the InverseFeedforward
    ``inverse`` (its model's description and settings) with make_model_inverse."""
    from ..compensate.inverse_model import PART_MEMBERS, describe

    desc = describe(inverse.model)
    body = f"  m.parts.resize({len(desc.parts)});\n"
    for i, part in enumerate(desc.parts):
        members = PART_MEMBERS.get(part.kind)
        refuse = _refusal(kind, f"{part.kind} model")
        if members is None:
            raise refuse("its parameters are not plain fields")
        body += f'  m.parts[{i}].kind = "{part.kind}";\n'
        for member in members:
            body += _assignments(f"m.parts[{i}].{member}", getattr(part, member), refuse)
    body += "".join(
        f"  m.map.{k} = {_number(getattr(desc.map, k))};\n"
        for k in ("input_offset", "input_scale", "output_offset", "output_gain")
    )
    lo, hi = inverse.command_range
    lim = inverse.limits
    settings = {
        "smoothing": inverse.smoothing,
        "limits.min": lim.min,
        "limits.max": lim.max,
        "limits.max_rate": lim.max_rate,
        "range.lo": lo,  # the identified range widened by its margin, as Python's
        "range.hi": hi,
        "filter_hz": 0.0 if inverse.filter_hz is None else inverse.filter_hz,
    }
    body += "".join(f"  s.{k} = {_number(v)};\n" for k, v in settings.items())
    return (
        f"inline tendonsheath::ModelInverse {name}() {{\n"
        "  tendonsheath::InverseModel m;\n  tendonsheath::InverseSettings s;\n"
        f"{body}  return tendonsheath::make_model_inverse(m, s);\n}}\n"
    )


# what the header says of its inverses' construction (make_model_inverse is no constructor:
# its checks are not collected by make())
_INVERSE_NOTE = (
    "// The inverse of a model, as Python's InverseFeedforward builds it: its description\n"
    "// (parts, parameters, Scaled map) and settings, given to make_model_inverse. Python's\n"
    "// inverse passed the same checks on the same numbers; a constant edited out of range\n"
    "// goes to the error handler (tendonsheath/error_handler.hpp), not to make_compensator().\n"
)


def _builder(cpp_class: str, args: str, step: str) -> str:
    return (
        "\n// The class to build: Compensator, that is\n"
        f"//   tendonsheath::{cpp_class}\n// its step:\n//   {step}\n"
        "// make_compensator() builds it with or without C++ exceptions (g++ -fno-exceptions):\n"
        "//   auto built = make_compensator();\n"
        '//   if (!built.ok()) { /* built.error(): "<class>: <what>" */ }\n'
        "//   Compensator& c = built.value();\n"
        f"using Compensator = tendonsheath::{cpp_class};\n"
        "inline tendonsheath::Result<Compensator> make_compensator() {\n"
        f"  return tendonsheath::make<Compensator>({args});\n}}\n"
    )


def load_compensated_body(ff) -> tuple[str, str]:
    """(header to include, declarations) of a LoadCompensated: the base's inverse, the load
    terms as a constexpr LoadTerms, and LoadCompensated<ModelInverse> built from both."""
    terms = {**ff.model.terms, "switch_travel": ff.switch}
    fields = "".join(f"  p.{k} = {_number(v)};\n" for k, v in terms.items())
    body = (
        _INVERSE_NOTE
        + _inverse_function("base_inverse", ff.inverse, "LoadCompensated")
        + "\n// the load terms of the Loaded model and the play inverse's switch travel\n"
        "inline constexpr tendonsheath::LoadTerms terms = [] {\n"
        f"  tendonsheath::LoadTerms p{{}};\n{fields}  return p;\n}}();\n"
    )
    build = _builder(
        "LoadCompensated<tendonsheath::ModelInverse>",
        "base_inverse(), terms",
        "double u = c.step(y_d, dt, load);  // a non-finite load holds the last one",
    )
    return "compensators/load_compensated.hpp", body + build


def coupled_feedforward_body(ff) -> tuple[str, str]:
    """(header to include, declarations) of a CoupledFeedforward: each joint's inverse, the
    row-major coupling as a constexpr array, and the CoupledFeedforward built from them."""
    joints = len(ff.joints)
    body = _INVERSE_NOTE + "".join(
        _inverse_function(f"joint_{i}_inverse", j, "CoupledFeedforward") + "\n"
        for i, j in enumerate(ff.joints)
    )
    coupling = ", ".join(_number(v) for v in ff.model.coupling.ravel())
    calls = ", ".join(f"joint_{i}_inverse()" for i in range(joints))
    body += (
        f"inline constexpr std::size_t joints = {joints};\n"
        "// C, row-major joints x joints: joint i's angle per radian of joint j\n"
        f"inline constexpr double coupling[] = {{{coupling}}};\n"
        "inline std::vector<tendonsheath::ModelInverse> joint_inverses() {\n"
        f"  return {{{calls}}};\n}}\n"
    )
    build = _builder(
        "CoupledFeedforward",
        "joint_inverses(), std::vector<double>(std::begin(coupling), std::end(coupling))",
        "c.step(y_d, u, dt);  // y_d, u: `joints` doubles each; a non-finite angle holds",
    )
    return "compensators/coupled_feedforward.hpp", body + build


__all__ = ["coupled_feedforward_body", "load_compensated_body"]
