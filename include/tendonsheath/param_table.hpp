// One parameter table per parameter struct: each field's name, unit, valid range, one-line doc
// and role (an identifiable parameter or a numerical option), declared once next to the struct
// (its default is the struct's own member initialiser). The bindings (a property per row, a
// keyword constructor, fields()), the constructors' checks of single-field bounds, the order in
// which assign_parameters() reads a flat vector, the Python models' names, signatures, defaults,
// docstrings and saved keys, and the docs page docs/parameters.md are derived from it.
//
//   template <> struct ParamTable<BacklashParams> {
//     static constexpr auto fields = std::make_tuple(
//         param("c_r", &BacklashParams::c_r, "", positive(), "slope of the rising branch"), ...);
//   };
//
// Header-only C++17: the table is a constexpr tuple of literal rows (no allocation); checking it
// (validate_fields) goes through validate.hpp, so it works built without exceptions too.
#pragma once

#include <limits>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

#include "validate.hpp"

namespace tendonsheath {

/// How a row's single-field bound is checked: the check_* kinds are checked by validate_fields()
/// with validate.hpp's message; documented is a bound the constructor checks by hand (its message
/// or its place among cross-field checks differs), unchecked a field with no bound of its own.
enum class Check : unsigned char {
  unchecked,     ///< any value (or a non-scalar row: a vector, an array, a nested struct, an enum)
  finite,        ///< "<name> must be finite (got v)"
  positive,      ///< "<name> must be > 0 (got v)": finite and > 0
  non_negative,  ///< "<name> must be >= 0 (got v)": finite and >= 0
  at_least,      ///< "<name> must be >= lo (got v)": finite and >= lo
  in_range,      ///< "<name> must be in [lo, hi] (got v)": finite and in [lo, hi]
  positive_or_inf,  ///< "<name> must be > 0 (got v)": > 0, +inf allowed (no limit)
  documented,    ///< the range [lo, hi] (inclusivity as given) is checked by the constructor by hand
};

/// What a row is to identification: a parameter is identified (in the flat vector of
/// assign_parameters(), a Python model's param_names, a saved file's "params"); an option is a
/// numerical setting that is not (a Python model's option_names, a saved file's "options").
enum class Role : unsigned char {
  parameter,  ///< identifiable
  option,     ///< a numerical setting (sub-steps, interpolation, ...), not identified
};

/// A row's valid range: its bounds, their inclusivity, and how it is checked.
struct Range {
  Check check = Check::unchecked;              ///< how the bound is checked
  double lo = -std::numeric_limits<double>::infinity();  ///< lower bound (-inf: none)
  bool lo_closed = false;                      ///< lo itself is valid
  double hi = std::numeric_limits<double>::infinity();   ///< upper bound (+inf: none)
  bool hi_closed = false;                      ///< hi itself is valid
};

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Any value, no check of its own (a cross-field rule may still apply).
constexpr Range any() { return Range{}; }
/// Finite.
constexpr Range finite() { return Range{Check::finite, -kInf, false, kInf, false}; }
/// Finite and > 0 (require_positive).
constexpr Range positive() { return Range{Check::positive, 0.0, false, kInf, false}; }
/// Finite and >= 0 (require_non_negative).
constexpr Range non_negative() { return Range{Check::non_negative, 0.0, true, kInf, false}; }
/// Finite and >= lo (require_at_least).
constexpr Range at_least(double lo) { return Range{Check::at_least, lo, true, kInf, false}; }
/// Finite and in [lo, hi] (require_in_range).
constexpr Range in_range(double lo, double hi) { return Range{Check::in_range, lo, true, hi, true}; }
/// > 0, +inf allowed: a limit that inf turns off.
constexpr Range positive_or_inf() { return Range{Check::positive_or_inf, 0.0, false, kInf, true}; }
/// A bound the constructor checks by hand: [lo or (lo, hi] or hi) as the flags say.
constexpr Range documented(double lo, bool lo_closed, double hi, bool hi_closed) {
  return Range{Check::documented, lo, lo_closed, hi, hi_closed};
}

/// One row of a parameter table: field `name` of struct P, of type T, at `member`.
template <class P, class T>
struct ParamField {
  using struct_type = P;  ///< the parameter struct
  using value_type = T;   ///< the field's type
  const char* name;       ///< the field's (and the Python argument's) name
  T P::*member;           ///< the field
  const char* unit;       ///< its unit ("" when dimensionless or in the input's units: see doc)
  Range range;            ///< its valid range and how it is checked
  const char* doc;        ///< one line
  /// the parameters the row applies to (nullptr: all), e.g. a position motor's: its bound is
  /// checked only where this holds
  bool (*applies)(const P&) = nullptr;
  const char* applies_to = nullptr;  ///< which those are, in words ("position"), for the docs
  Role role = Role::parameter;       ///< identifiable parameter or numerical option
};

/// A row: param("c_r", &BacklashParams::c_r, "", positive(), "slope of the rising branch").
template <class P, class T>
constexpr ParamField<P, T> param(const char* name, T P::*member, const char* unit, Range range,
                                 const char* doc) {
  return ParamField<P, T>{name, member, unit, range, doc};
}

/// An option's row (Role::option): option("max_substeps", &BoucWenParams::max_substeps, "", ...).
template <class P, class T>
constexpr ParamField<P, T> option(const char* name, T P::*member, const char* unit, Range range,
                                  const char* doc) {
  ParamField<P, T> row{name, member, unit, range, doc};
  row.role = Role::option;
  return row;
}

/// A row that applies only where applies(p) holds (`which`: those parameters in words):
/// only_if(param("viscous", ...), &is_torque, "torque").
template <class P, class T>
constexpr ParamField<P, T> only_if(ParamField<P, T> row, bool (*applies)(const P&),
                                   const char* which) {
  row.applies = applies;
  row.applies_to = which;
  return row;
}

/// Specialised next to each parameter struct P, with `static constexpr auto fields` (a tuple of
/// param() rows, in the order of the struct and of the constructor's checks),
/// `static constexpr const char* owner` (the class whose constructor takes P: its messages'
/// prefix) and `static constexpr bool checked_from_table` (true when that constructor checks the
/// rows' single-field bounds with validate_fields(); false when it keeps its own checks, for an
/// order of checks or a message of its own). Undefined for a struct without a table.
template <class P>
struct ParamTable;

/// Calls f(row) for each row of P's table, in order.
template <class P, class F>
constexpr void for_each_field(F&& f) {
  std::apply([&](const auto&... row) { (f(row), ...); }, ParamTable<P>::fields);
}

/// The number of rows of P's table.
template <class P>
constexpr std::size_t field_count() {
  return std::tuple_size_v<std::decay_t<decltype(ParamTable<P>::fields)>>;
}

/// The rows of a base struct B's table as rows of D, a struct derived from B (the inverse of a
/// model takes the model's parameters: its table starts with the model's rows, not a copy):
/// std::tuple_cat(rows_of<D, B>(), std::make_tuple(param("smoothing", &D::smoothing, ...))).
template <class D, class B>
constexpr auto rows_of() {
  static_assert(std::is_base_of_v<B, D>, "rows_of<D, B>: D must derive from B");
  return std::apply(
      [](const auto&... row) {
        return std::make_tuple([](const auto& r) {
          using T = typename std::decay_t<decltype(r)>::value_type;
          ParamField<D, T> out{r.name, static_cast<T D::*>(r.member), r.unit, r.range, r.doc};
          out.applies_to = r.applies_to;  // (a row that applies to some B only is not inherited)
          out.role = r.role;
          return out;
        }(row)...);
      },
      ParamTable<B>::fields);
}

/// The number of P's identifiable parameters (Role::parameter rows of type double): the length
/// of the flat vector assign_parameters() reads.
template <class P>
constexpr std::size_t parameter_count() {
  std::size_t n = 0;
  for_each_field<P>([&](const auto& row) {
    using T = typename std::decay_t<decltype(row)>::value_type;
    if (std::is_same_v<T, double> && row.role == Role::parameter) ++n;
  });
  return n;
}

/// Sets P's identifiable parameters (Role::parameter rows of type double) from
/// v[0..parameter_count<P>()), in table order (the Python param_names' order); options are kept.
template <class P>
void assign_parameters(P& p, const double* v) noexcept {
  std::size_t i = 0;
  for_each_field<P>([&](const auto& row) {
    using T = typename std::decay_t<decltype(row)>::value_type;
    if constexpr (std::is_same_v<T, double>) {
      if (row.role == Role::parameter) p.*row.member = v[i++];
    }
  });
}

/// Checks one row's single-field bound with validate.hpp's message (the documented and
/// unchecked kinds are left to the constructor).
template <class P, class T>
void validate_field(const P& p, const ParamField<P, T>& row, const char* where) {
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    if (row.applies != nullptr && !row.applies(p)) return;  // not these parameters' field
    const double v = static_cast<double>(p.*row.member);
    switch (row.range.check) {
      case Check::finite: require_finite(v, where, row.name); break;
      case Check::positive: require_positive(v, where, row.name); break;
      case Check::non_negative: require_non_negative(v, where, row.name); break;
      case Check::at_least: require_at_least(v, row.range.lo, where, row.name); break;
      case Check::in_range: require_in_range(v, row.range.lo, row.range.hi, where, row.name); break;
      case Check::positive_or_inf: require(v > 0.0, where, row.name, " must be > 0 (got ", v, ")"); break;
      default: break;
    }
  }
}

/// Checks every row's single-field bound of p in table order, naming the first one out of range
/// as "<where>: <name> must be ..."; the cross-field rules stay with the constructor.
template <class P>
void validate_fields(const P& p, const char* where) {
  for_each_field<P>([&](const auto& row) { validate_field(p, row, where); });
}

/// Checks the rows from `first` to `last` (names, both included) in table order, for a constructor
/// whose cross-field rules sit between the single-field checks.
template <class P>
void validate_fields(const P& p, const char* where, std::string_view first, std::string_view last) {
  bool inside = false;
  for_each_field<P>([&](const auto& row) {
    if (row.name == first) inside = true;
    if (inside) validate_field(p, row, where);
    if (row.name == last) inside = false;
  });
}

}  // namespace tendonsheath
