// A parameter struct bound from its table (include/tendonsheath/param_table.hpp): a read/write
// property per row, a keyword constructor, and fields(), the rows as Python sees them.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/stl/array.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <string>
#include <type_traits>
#include <utility>

#include <tendonsheath/param_table.hpp>

namespace tsbind {

namespace nb = nanobind;

// The name Python shows for a Check kind.
inline const char* check_name(tendonsheath::Check c) {
  using tendonsheath::Check;
  switch (c) {
    case Check::finite: return "finite";
    case Check::positive: return "positive";
    case Check::non_negative: return "non_negative";
    case Check::at_least: return "at_least";
    case Check::in_range: return "in_range";
    case Check::positive_or_inf: return "positive_or_inf";
    case Check::documented: return "documented";
    default: return "unchecked";
  }
}

// One row as a dict: name, unit, default, lo, lo_closed, hi, hi_closed, check, doc, applies_to
// (None: every parameter set) and role ("parameter": identifiable, or "option").
template <class P, class T>
nb::dict field_row(const tendonsheath::ParamField<P, T>& row, const P& defaults) {
  nb::dict d;
  d["name"] = row.name;
  d["unit"] = row.unit;
  d["default"] = nb::cast(defaults.*row.member, nb::rv_policy::copy);
  d["lo"] = row.range.lo;
  d["lo_closed"] = row.range.lo_closed;
  d["hi"] = row.range.hi;
  d["hi_closed"] = row.range.hi_closed;
  d["check"] = check_name(row.range.check);
  d["doc"] = row.doc;
  d["applies_to"] = row.applies_to ? nb::cast(row.applies_to) : nb::none();
  d["role"] = row.role == tendonsheath::Role::option ? "option" : "parameter";
  return d;
}

// Sets field `key` of p from `value`; false when P's table has no such row.
template <class P>
bool set_field(P& p, const std::string& key, nb::handle value, const char* struct_name) {
  bool found = false;
  tendonsheath::for_each_field<P>([&](const auto& row) {
    using T = typename std::decay_t<decltype(row)>::value_type;
    if (found || key != row.name) return;
    found = true;
    T v{};
    if (!nb::try_cast<T>(value, v))
      throw nb::type_error((std::string(struct_name) + ": " + key + " cannot take a value of type " +
                            nb::type_name(value.type()).c_str())
                               .c_str());
    p.*row.member = std::move(v);
  });
  return found;
}

// The Python type a row's value takes, for the keyword constructor's signature (the stub).
template <class T>
std::string python_type() {
  if constexpr (std::is_same_v<T, bool>) {
    return "bool";
  } else if constexpr (std::is_floating_point_v<T>) {
    return "float";
  } else if constexpr (std::is_integral_v<T>) {
    return "int";
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    return "collections.abc.Sequence[float]";
  } else {
    nb::handle t = nb::type<T>();  // a nested struct or an enum, bound before P
    return t.is_valid() ? std::string(nb::type_name(t).c_str()) : std::string("object");
  }
}

// "def __init__(self, *, c_r: float = ..., ...) -> None": every row a keyword-only argument.
template <class P>
std::string init_signature() {
  std::string s = "def __init__(self";
  const char* sep = ", *, ";
  tendonsheath::for_each_field<P>([&](const auto& row) {
    using T = typename std::decay_t<decltype(row)>::value_type;
    s += sep;
    s += row.name;
    s += ": " + python_type<T>() + " = ...";
    sep = ", ";
  });
  return s + ") -> None";
}

// Binds P as `name`: a property per table row, P(**fields) (an unknown keyword: TypeError naming
// it), the static fields(), the rows as dicts, and the class attributes owner (the class that
// checks P) and checked_from_table. Returns the class for anything bound by hand.
template <class P>
nb::class_<P> bind_params(nb::module_& m, const char* name) {
  nb::class_<P> cls(m, name);
  cls.def(
      "__init__",
      [name](P* self, nb::kwargs kwargs) {
        P p{};
        for (auto [key, value] : kwargs) {
          const std::string k = nb::cast<std::string>(key);
          if (!set_field(p, k, value, name))
            throw nb::type_error((std::string(name) + ": unknown keyword '" + k + "'").c_str());
        }
        new (self) P(std::move(p));
      },
      nb::sig(init_signature<P>().c_str()),
      "Set any field by keyword; the others keep their defaults (fields() lists them).");
  tendonsheath::for_each_field<P>([&](const auto& row) { cls.def_rw(row.name, row.member); });
  cls.def_static(
      "fields",
      []() {
        const P defaults{};
        nb::list rows;
        tendonsheath::for_each_field<P>([&](const auto& row) { rows.append(field_row(row, defaults)); });
        return rows;
      },
      "The parameter table: a dict per field (name, unit, default, lo, lo_closed, hi, hi_closed, "
      "check, doc, applies_to, role: 'parameter' or 'option'), in the order of the struct.");
  cls.attr("owner") = tendonsheath::ParamTable<P>::owner;
  cls.attr("checked_from_table") = tendonsheath::ParamTable<P>::checked_from_table;
  return cls;
}

}  // namespace tsbind
