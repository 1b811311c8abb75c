// Model files ("tendonsheath.model", as Python's `HysteresisModel.to_json` writes them) read
// into the description a ModelInverse is built from (InverseModel): every model class the
// identification returns, a Chain of two, a Scaled model around either; a Loaded model (a base
// and its load terms, LoadedModel) and a Coupled model file ("tendonsheath.coupled_model",
// CoupledModel). Part of the optional tendonsheath/io/json.hpp (needs nlohmann/json); outside the
// real-time path.
//
// With or without C++ exceptions: a bad key is reported through detail::fail(), which throws
// std::invalid_argument with exceptions; without them (-fno-exceptions) the message is collected
// by the Result being built (result.hpp, detail::result_of) and each function returns at its
// next guard (failed()) before it reads what the check refused. No nlohmann call here can throw:
// every value's type (and size, and range before narrowing) is checked before it is read, and
// values are shown with shown() (never a throwing dump()).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "../compensators/load_compensated.hpp"
#include "../compensators/make_model_inverse.hpp"
#include "../result.hpp"

namespace tendonsheath::io {

/// The JSON value type of nlohmann/json.
using json = nlohmann::json;

namespace detail {

// A bad file: "<where>: <what>" thrown as std::invalid_argument with exceptions; without them
// collected by the Result being built (or, outside one, the error handler, then std::abort()).
// Without exceptions it returns: the caller returns at its next guard.
inline void fail(const std::string& where, const std::string& what) {
  tendonsheath::detail::report_error(where + ": " + what);
}

// True once a check has failed (only ever without exceptions: with them the check has thrown).
inline bool failed() noexcept { return tendonsheath::detail::failed(); }

// A value as JSON text, for a message (never throws: a string that is not UTF-8, possible only in
// a json built in code, is shown with U+FFFD where a parsed file could not have it).
inline std::string shown(const json& v) {
  return v.dump(-1, ' ', false, json::error_handler_t::replace);
}

// the null a failed member() returns (without exceptions): every check on it fails quietly
inline const json& absent() {
  static const json none;
  return none;
}

inline const json& member(const json& obj, const std::string& key, const std::string& where) {
  if (!obj.is_object()) return fail(where, "must be a JSON object"), absent();
  const auto it = obj.find(key);
  if (it == obj.end()) return fail(where, "key '" + key + "' is missing"), absent();
  return *it;
}

// every key of obj is one of `allowed` and every one of `required` is there
inline void check_keys(const json& obj, const std::set<std::string>& allowed,
                       const std::set<std::string>& required, const std::string& where) {
  if (!obj.is_object()) return fail(where, "must be a JSON object");
  for (const auto& item : obj.items())
    if (!allowed.count(item.key())) return fail(where, "unknown key '" + item.key() + "'");
  for (const auto& key : required) member(obj, key, where);
}

// a number; null means `unbounded` when that is not NaN, else it is an error (NaN once failed)
inline double number(const json& obj, const std::string& key, const std::string& where,
                     double unbounded = std::numeric_limits<double>::quiet_NaN()) {
  const json& v = member(obj, key, where);
  if (failed()) return std::numeric_limits<double>::quiet_NaN();
  if (v.is_null() && !std::isnan(unbounded)) return unbounded;
  if (!v.is_number()) {
    fail(where, "key '" + key + "' must be a number (got " + shown(v) + ")");
    return std::numeric_limits<double>::quiet_NaN();
  }
  return v.get<double>();
}

// an integer within an int's range (0 once failed)
inline int integer(const json& obj, const std::string& key, const std::string& where) {
  const json& v = member(obj, key, where);
  if (failed()) return 0;
  if (!v.is_number_integer())
    return fail(where, "key '" + key + "' must be an integer (got " + shown(v) + ")"), 0;
  // get<int> would wrap a larger integer round silently
  const bool fits = v.is_number_unsigned()
                        ? v.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<int>::max())
                        : v.get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                              v.get<std::int64_t>() <= std::numeric_limits<int>::max();
  if (!fits) {
    fail(where, "key '" + key + "' is out of the range of an int (got " + shown(v) + ")");
    return 0;
  }
  return v.get<int>();
}

// an array of numbers (empty once failed)
inline std::vector<double> numbers(const json& obj, const std::string& key,
                                   const std::string& where) {
  const json& v = member(obj, key, where);
  if (failed()) return {};
  if (!v.is_array()) {
    fail(where, "key '" + key + "' must be an array of numbers");
    return {};
  }
  std::vector<double> out;
  for (const json& e : v) {
    if (!e.is_number()) {
      fail(where, "key '" + key + "' must hold only numbers (got " + shown(e) + ")");
      return {};
    }
    out.push_back(e.get<double>());
  }
  return out;
}

inline void check_format(const json& file, const char* format, const std::string& where) {
  const json& f = member(file, "format", where);
  if (failed()) return;
  if (f != format)
    return fail(where,
                std::string("key 'format' must be \"") + format + "\" (got " + shown(f) + ")");
  const json& v = member(file, "version", where);
  if (failed()) return;
  // the integer 1: neither true nor 1.0 (Python's loaders refuse them too)
  if (!v.is_number_integer() || v != 1)
    fail(where, "unsupported 'version' " + shown(v) + " (expected 1)");
}

// The models of the list (model_list.hpp) whose file's params are their parameter vector's
// scalars by name (param_names) and whose options model_options() reads: those with a parameter
// vector, but CurveAngleModel (its reader takes the old key names and an optional play).
template <class M>
struct scalar_model : has_param_vector<M> {};
template <>
struct scalar_model<CurveAngleModel> : std::false_type {};
using ScalarModels = filter_list_t<Models, scalar_model>;

// the names of parameter vector P (the first P::vector_size rows of its table: its assign()
// order, Python's param_names)
template <class P>
std::vector<std::string> vector_names() {
  std::vector<std::string> out;
  for_each_field<P>([&](const auto& row) {
    if (out.size() < P::vector_size) out.emplace_back(row.name);
  });
  return out;
}

// the parameters of a model class, in its Python param_names order (what AngleLaws index): a
// model of ScalarModels, PlantModel or a lag
inline std::vector<std::string> param_names(const std::string& kind) {
  std::vector<std::string> out;
  if (any_type(ScalarModels{}, [&](auto tag) {
        using M = typename decltype(tag)::type;
        if (kind != model_kind<M>()) return false;
        out = vector_names<typename M::Params>();
        return true;
      }))
    return out;
  if (kind == "PlantModel") return {"friction_angle", "backlash", "viscous_time", "gain", "offset"};
  if (kind == "FirstOrderLag") return {"time_constant"};
  if (kind == "SecondOrderLag") return {"frequency", "damping"};
  return {};
}

inline std::set<std::string> set_of(const std::vector<std::string>& v) {
  return std::set<std::string>(v.begin(), v.end());
}

// scalar params of `kind` (every one a number), in param_names order
inline std::vector<double> scalars(const json& p, const std::string& kind, const std::string& w) {
  const auto names = param_names(kind);
  check_keys(p, set_of(names), set_of(names), w);
  std::vector<double> out;
  for (const auto& k : names) out.push_back(number(p, k, w));
  return out;
}

// the options object (absent: {}), its keys among `allowed`
inline json options(const json& m, const std::set<std::string>& allowed, const std::string& where) {
  if (!m.contains("options")) return json::object();
  const json& o = member(m, "options", where);
  check_keys(o, allowed, {}, where + ": options");
  return o;
}

inline void bouc_wen_options(const json& o, double& max_step, int& max_substeps,
                             const std::string& w) {
  if (o.contains("max_step")) max_step = number(o, "max_step", w);
  if (o.contains("max_substeps")) max_substeps = integer(o, "max_substeps", w);
}

inline void oscillator_options(const json& o, HystereticOscillatorParams& h, const std::string& w) {
  if (o.contains("substeps")) h.substeps = integer(o, "substeps", w);
  if (o.contains("max_substeps")) h.max_substeps = integer(o, "max_substeps", w);
  if (o.contains("lookahead")) h.lookahead = integer(o, "lookahead", w);
  if (!o.contains("input_interpolation")) return;
  const json& v = member(o, "input_interpolation", w);
  if (v == "hold") h.input_interpolation = kInputHold;
  else if (v == "linear") h.input_interpolation = kInputLinear;
  else if (v == "bandlimited") h.input_interpolation = kInputBandlimited;
  else fail(w, "key 'input_interpolation' must be \"linear\", \"hold\" or \"bandlimited\" (got " + shown(v) + ")");
}

// the base parameters of `kind` (a model of ScalarModels) from scalars v
// (its param_names order), into part's member
inline void assign_base(ModelPart& part, const std::string& kind, const std::vector<double>& v) {
  any_type(ScalarModels{}, [&](auto tag) {
    using M = typename decltype(tag)::type;
    if (kind != model_kind<M>()) return false;
    part_params<M>(part).assign(v.data());
    return true;
  });
}

// The options of a scalar model M (its file's "options") into its parameters: none unless an
// overload below reads some.
template <class M>
void model_options(TypeTag<M>, typename M::Params&, const json& o, const std::string& w) {
  check_keys(o, {}, {}, w);
}
inline void model_options(TypeTag<BoucWenBacklash>, BoucWenBacklashParams& p, const json& o,
                          const std::string& w) {
  check_keys(o, {"max_step", "max_substeps"}, {}, w);
  bouc_wen_options(o, p.max_step, p.max_substeps, w);
}
inline void model_options(TypeTag<BoucWen>, BoucWenParams& p, const json& o,
                          const std::string& w) {
  check_keys(o, {"max_step", "max_substeps"}, {}, w);
  bouc_wen_options(o, p.max_step, p.max_substeps, w);
}
inline void model_options(TypeTag<HystereticOscillator>, HystereticOscillatorParams& p,
                          const json& o, const std::string& w) {
  check_keys(o, {"substeps", "max_substeps", "input_interpolation", "lookahead"}, {}, w);
  oscillator_options(o, p, w);
}

// the options of a base model (a model of ScalarModels) into part
inline void base_options(ModelPart& part, const std::string& kind, const json& o,
                         const std::string& w) {
  if (!any_type(ScalarModels{}, [&](auto tag) {
        using M = typename decltype(tag)::type;
        if (kind != model_kind<M>()) return false;
        model_options(tag, part_params<M>(part), o, w);
        return true;
      }))
    check_keys(o, {}, {}, w);
}

inline AngleLaw law_of(const json& v, const std::string& key, const std::string& w) {
  if (v == "constant") return AngleLaw::constant;
  if (v == "linear") return AngleLaw::linear;
  if (v == "tanh") return AngleLaw::tanh;
  fail(w, "law of '" + key + "' must be \"constant\", \"linear\" or \"tanh\" (got " + shown(v) + ")");
  return AngleLaw::constant;  // (without exceptions: never used, the check has failed)
}

// AngleDependent: base, laws, coefficients, angle_friction; options base_options
inline void angle_dependent_part(ModelPart& part, const json& m, const std::string& where) {
  const std::string w = where + ": params";
  const json& p = member(m, "params", where);
  check_keys(p, {"base", "laws", "coefficients", "angle_friction"},
             {"base", "laws", "coefficients", "angle_friction"}, w);
  if (failed()) return;
  const json& base = member(p, "base", w);
  if (!base.is_string())
    return fail(w, "key 'base' must be a model class name (got " + shown(base) + ")");
  part.base = base.get<std::string>();
  bool base_ok = false;  // a model of the list that make_model_inverse takes as a base
  visit_model_kind(part.base, [&](auto tag) {
    base_ok = angle_dependent_base<typename decltype(tag)::type>;
  });
  const auto names = param_names(part.base);
  if (!base_ok || names.empty())
    return fail(w, "key 'base': the inverse of an AngleDependent model takes a Backlash, "
                   "BoucWenBacklash, BoucWen or HystereticOscillator base (got " +
                       shown(base) + ")");
  const json& laws = member(p, "laws", w);
  const json& coefs = member(p, "coefficients", w);
  check_keys(laws, set_of(names), {}, w + ": laws");
  check_keys(coefs, set_of(names), set_of(names), w + ": coefficients");
  if (failed()) return;
  AngleLaws out;
  out.count = names.size();
  for (std::size_t i = 0; i < names.size(); ++i) {
    out.law[i] = laws.contains(names[i]) ? law_of(member(laws, names[i], w), names[i], w)
                                         : AngleLaw::constant;
    const auto c = numbers(coefs, names[i], w + ": coefficients");
    if (failed()) return;
    const std::size_t want = out.law[i] == AngleLaw::constant ? 1 : 2;
    if (c.size() != want)
      return fail(w, "coefficients of '" + names[i] + "' must be " + std::to_string(want) +
                         " number(s)");
    out.c0[i] = c[0];
    out.c1[i] = want == 2 ? c[1] : 0.0;
  }
  out.angle_friction = number(p, "angle_friction", w, 0.0);
  part.laws = out;
  const json o = options(m, {"base_options"}, where);
  if (o.contains("base_options"))
    base_options(part, part.base, member(o, "base_options", where),
                 where + ": options: base_options");
  if (failed()) return;
  std::vector<double> v(names.size());
  out.at_angle(0.0, v.data());
  assign_base(part, part.base, v);
}

inline void envelope(Envelope& e, const json& p, const std::string& side, const std::string& w) {
  e.a = number(p, side + "_a", w);
  e.b = number(p, side + "_b", w);
  e.c = number(p, side + "_c", w);
  e.d = number(p, side + "_d", w);
}

// options.envelope_range: null (the tanh everywhere) or [lo, hi], both envelopes' tanh input range
inline void envelope_range(GeneralizedPrandtlIshlinskiiParams& g, const json& o, const std::string& w) {
  if (!o.contains("envelope_range") || member(o, "envelope_range", w).is_null()) return;
  const std::vector<double> r = numbers(o, "envelope_range", w);
  if (failed()) return;
  if (r.size() != 2 || !std::isfinite(r[0]) || !std::isfinite(r[1]) || !(r[0] < r[1]))
    return fail(w, "'envelope_range' must be null or [lo, hi] with finite lo < hi (got " +
                       shown(member(o, "envelope_range", w)) + ")");
  for (Envelope* e : {&g.rising, &g.falling}) {
    e->lo = r[0];
    e->hi = r[1];
  }
}

inline void plays_part(ModelPart& part, const json& m, const std::string& where) {
  const std::string w = where + ": params";
  const json& p = member(m, "params", where);
  if (part.kind == "PrandtlIshlinskii") {
    options(m, {}, where);
    check_keys(p, {"thresholds", "weights"}, {"thresholds", "weights"}, w);
    part.prandtl_ishlinskii.thresholds = numbers(p, "thresholds", w);
    part.prandtl_ishlinskii.weights = numbers(p, "weights", w);
    return;
  }
  std::set<std::string> keys{"thresholds", "weights"};
  for (const char* side : {"rising", "falling"})
    for (const char* k : {"_a", "_b", "_c", "_d"}) keys.insert(std::string(side) + k);
  check_keys(p, keys, keys, w);
  auto& g = part.generalized_prandtl_ishlinskii;
  envelope(g.rising, p, "rising", w);
  envelope(g.falling, p, "falling", w);
  g.thresholds = numbers(p, "thresholds", w);
  g.weights = numbers(p, "weights", w);
  envelope_range(g, options(m, {"envelope_range"}, where), where + ": options");
}

inline void polynomial_part(ModelPart& part, const json& m, const std::string& where) {
  const std::string w = where + ": params";
  const json& p = member(m, "params", where);
  check_keys(p, {"coefficients"}, {"coefficients"}, w);
  part.polynomial.coefficients = numbers(p, "coefficients", w);
  const json o = options(m, {"odd"}, where);
  if (o.contains("odd")) {
    const json& odd = member(o, "odd", where + ": options");
    if (!odd.is_boolean()) return fail(where + ": options", "key 'odd' must be true or false");
    part.polynomial.odd = odd.get<bool>();
  }
}

// CurveAngleModel (load_force / load_stiffness, or the old names load / spring)
inline void curve_angle_part(ModelPart& part, const json& m, const std::string& where) {
  const std::string w = where + ": params";
  const json& p = member(m, "params", where);
  options(m, {}, where);
  std::set<std::string> keys{"friction", "stiffness", "pretension", "length", "proximal_radius",
                             "distal_radius"};
  const std::string load = p.is_object() && p.contains("load") ? "load" : "load_force";
  const std::string spring = p.is_object() && p.contains("spring") ? "spring" : "load_stiffness";
  keys.insert({load, spring});
  std::set<std::string> allowed = keys;
  allowed.insert("play");  // optional: model files written before it was a parameter lack it
  check_keys(p, allowed, keys, w);
  CurveAngleParams& c = part.curve_angle_model;
  c.friction = number(p, "friction", w);
  c.stiffness = number(p, "stiffness", w);
  c.pretension = number(p, "pretension", w);
  c.length = number(p, "length", w);
  c.load_force = number(p, load, w);
  c.load_stiffness = number(p, spring, w);
  c.proximal_radius = number(p, "proximal_radius", w);
  c.distal_radius = number(p, "distal_radius", w);
  if (p.contains("play")) c.play = number(p, "play", w);
}

// the models whose params are scalars in param_names order
inline void scalar_part(ModelPart& part, const json& m, const std::string& where) {
  const std::string w = where + ": params";
  const auto v = scalars(member(m, "params", where), part.kind, w);
  if (part.kind == "PlantModel") {
    const json o = options(m, {"elements"}, where);
    PlantModelParams& q = part.plant_model;
    q.friction_angle = v[0], q.backlash = v[1], q.viscous_time = v[2], q.gain = v[3], q.offset = v[4];
    if (o.contains("elements")) q.elements = integer(o, "elements", where + ": options");
  } else if (part.kind == "FirstOrderLag" || part.kind == "SecondOrderLag") {
    options(m, {}, where);
    part.lag.order = part.kind == "FirstOrderLag" ? 1 : 2;
    if (part.lag.order == 1) part.lag.time_constant = v[0];
    else part.lag.frequency = v[0], part.lag.damping = v[1];
  } else {
    assign_base(part, part.kind, v);
    const json none = json::object();
    base_options(part, part.kind, m.contains("options") ? member(m, "options", where) : none,
                 where + ": options");
  }
}

// The params (and options) of a model M of the list (model_list.hpp) into part: a model of
// ScalarModels by default, else an overload below.
template <class M>
void model_part(TypeTag<M>, ModelPart& part, const json& m, const std::string& where) {
  static_assert(scalar_model<M>::value, "a model outside ScalarModels needs its own model_part()");
  scalar_part(part, m, where);
}
inline void model_part(TypeTag<PlantModel>, ModelPart& part, const json& m,
                       const std::string& where) {
  scalar_part(part, m, where);
}
inline void model_part(TypeTag<PrandtlIshlinskii>, ModelPart& part, const json& m,
                       const std::string& where) {
  plays_part(part, m, where);
}
inline void model_part(TypeTag<GeneralizedPrandtlIshlinskii>, ModelPart& part, const json& m,
                       const std::string& where) {
  plays_part(part, m, where);
}
inline void model_part(TypeTag<Polynomial>, ModelPart& part, const json& m,
                       const std::string& where) {
  polynomial_part(part, m, where);
}
inline void model_part(TypeTag<CurveAngleModel>, ModelPart& part, const json& m,
                       const std::string& where) {
  curve_angle_part(part, m, where);
}

// the model kinds the loader inverts, for its message: the list's, then the others
inline std::string loader_kinds() {
  std::string out;
  for_each_type(Models{}, [&](auto tag) {
    out += model_kind<typename decltype(tag)::type>();
    out += ", ";
  });
  return out + "AngleDependent, FirstOrderLag, SecondOrderLag, a Chain of two and a Scaled model "
               "around them";
}

inline const std::set<std::string> kPlainKeys{"format", "version", "model", "params", "options",
                                              "input_range"};

// one plain model
inline ModelPart part_from_json(const json& m, const std::string& where) {
  check_format(m, "tendonsheath.model", where);
  const json& name = member(m, "model", where);
  ModelPart part;
  part.kind = name.is_string() ? name.get<std::string>() : shown(name);
  check_keys(m, kPlainKeys, {"params"}, where);
  if (failed()) return part;
  if (visit_model_kind(part.kind, [&](auto tag) { model_part(tag, part, m, where); })) {
  } else if (part.kind == "AngleDependent") {
    angle_dependent_part(part, m, where);
  } else if (!param_names(part.kind).empty()) {  // a lag
    scalar_part(part, m, where);
  } else if (part.kind == "Loaded") {
    fail(where, "key 'model': a Loaded model's inverse takes the measured load each cycle: save a "
                "LoadCompensated and load it with io::load_load_compensated_json "
                "(tendonsheath/io/json_multi_input.hpp)");
  } else {
    fail(where, "key 'model': the C++ loader inverts " + loader_kinds() + " (got " + shown(name) +
                    ")");
  }
  return part;
}

inline ScaledMap scaled_map(const json& mp, const std::string& w) {
  check_keys(mp, {"input_offset", "input_scale", "output_offset", "output_gain"},
             {"input_offset", "input_scale", "output_offset", "output_gain"}, w);
  const ScaledMap map{number(mp, "input_offset", w), number(mp, "input_scale", w),
                      number(mp, "output_offset", w), number(mp, "output_gain", w)};
  map.validate(w.c_str());
  return map;
}

// a plain model or a Chain of two
inline std::vector<ModelPart> parts_from_json(const json& m, const std::string& where) {
  check_format(m, "tendonsheath.model", where);
  if (failed()) return {};
  if (member(m, "model", where) != "Chain") return {part_from_json(m, where)};
  check_keys(m, {"format", "version", "model", "first", "second", "input_range"},
             {"first", "second"}, where);
  if (failed()) return {};
  std::vector<ModelPart> parts{part_from_json(member(m, "first", where), where + ": first")};
  if (failed()) return {};  // (the first part's error, as a throw would have left it)
  parts.push_back(part_from_json(member(m, "second", where), where + ": second"));
  return parts;
}

}  // namespace detail

/// The saved input range of a model document ([lo, hi], finite, lo <= hi), if it has one.
/// Throws std::invalid_argument naming the key when it is malformed.
inline std::optional<std::pair<double, double>> model_input_range(const json& m,
                                                                  const std::string& where) {
  if (!m.is_object() || !m.contains("input_range") || m["input_range"].is_null())
    return std::nullopt;
  const json& v = m["input_range"];  // (const operator[]: the key is there)
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number() ||
      !(v[0].get<double>() <= v[1].get<double>())) {
    detail::fail(where,
                 "key 'input_range' must be [lo, hi] with lo <= hi (got " + detail::shown(v) + ")");
    return std::nullopt;
  }
  return std::make_pair(v[0].get<double>(), v[1].get<double>());
}

/// The description of a "tendonsheath.model" document as a ModelInverse takes it: every model
/// class the identification returns, a Chain of two, and a Scaled model around either. Throws
/// std::invalid_argument, message starting with `where`, naming the bad key.
inline InverseModel inverse_model_from_json(const json& m, const std::string& where) {
  detail::check_format(m, "tendonsheath.model", where);
  InverseModel out;
  if (detail::failed()) return out;
  if (detail::member(m, "model", where) == "Scaled") {
    detail::check_keys(m, {"format", "version", "model", "inner", "map", "input_range"},
                       {"inner", "map"}, where);
    if (detail::failed()) return out;
    out.map = detail::scaled_map(detail::member(m, "map", where), where + ": map");
    const json& inner = detail::member(m, "inner", where);
    if (inner.is_object() && inner.contains("model") && inner["model"] == "Scaled") {
      detail::fail(where, "a Scaled model inside a Scaled model is not supported");
      return out;
    }
    if (detail::failed()) return out;
    out.parts = detail::parts_from_json(inner, where + ": inner");
    return out;
  }
  out.parts = detail::parts_from_json(m, where);
  return out;
}

/// A Loaded model file (Python's models.Loaded: y = base(play_r(L)(x)) + gain L) as
/// LoadCompensated takes it: the base's description and the four load terms.
struct LoadedModel {
  InverseModel base;  ///< the unloaded drive's model (any model inverse_model_from_json reads)
  LoadTerms terms;    ///< gain, slack, slack_load, friction; switch_travel is the compensator's
};

/// The Loaded model of a "tendonsheath.model" document (model "Loaded": base, terms, and an
/// optional input_range). Throws std::invalid_argument, message starting with `where`, naming a
/// missing, unknown, mistyped or out-of-range key.
inline LoadedModel loaded_model_from_json(const json& m, const std::string& where) {
  LoadedModel out;
  detail::check_format(m, "tendonsheath.model", where);
  if (detail::failed()) return out;
  const json& name = detail::member(m, "model", where);
  if (name != "Loaded")
    return detail::fail(where, "key 'model' must be \"Loaded\" (got " + detail::shown(name) + ")"),
           out;
  detail::check_keys(m, {"format", "version", "model", "base", "terms", "input_range"},
                     {"base", "terms"}, where);
  if (detail::failed()) return out;
  model_input_range(m, where);  // a malformed one is an error, though the inverse takes its own
  if (detail::failed()) return out;
  out.base = inverse_model_from_json(detail::member(m, "base", where), where + ": base");
  if (detail::failed()) return out;
  const std::string w = where + ": terms";
  const json& t = detail::member(m, "terms", where);
  const std::set<std::string> keys{"gain", "slack", "slack_load", "friction"};
  detail::check_keys(t, keys, keys, w);
  if (detail::failed()) return out;
  out.terms.gain = detail::number(t, "gain", w);
  out.terms.slack = detail::number(t, "slack", w);
  out.terms.slack_load = detail::number(t, "slack_load", w);
  out.terms.friction = detail::number(t, "friction", w);
  out.terms.validate(w.c_str());
  return out;
}

/// A Coupled model file (Python's models.Coupled: y_i = H_i(x_i) + sum_j C[i][j] y_j).
struct CoupledModel {
  std::vector<InverseModel> joints;  ///< H_i, one description per joint
  std::vector<double> coupling;      ///< C, row-major J x J (validated by CoupledFeedforward)
};

/// The Coupled model of a "tendonsheath.coupled_model" document (models: one model document per
/// joint; coupling: J rows of J numbers). Throws std::invalid_argument, message starting with
/// `where`, naming a missing, unknown or mistyped key.
inline CoupledModel coupled_model_from_json(const json& m, const std::string& where) {
  CoupledModel out;
  detail::check_format(m, "tendonsheath.coupled_model", where);
  if (detail::failed()) return out;
  detail::check_keys(m, {"format", "version", "models", "coupling"}, {"models", "coupling"}, where);
  if (detail::failed()) return out;
  const json& models = detail::member(m, "models", where);
  if (!models.is_array() || models.empty())
    return detail::fail(where, "key 'models' must be a non-empty array of model objects"), out;
  for (std::size_t i = 0; i < models.size(); ++i) {
    out.joints.push_back(
        inverse_model_from_json(models[i], where + ": models[" + std::to_string(i) + "]"));
    if (detail::failed()) return out;
  }
  const std::size_t n = models.size();
  const json& c = detail::member(m, "coupling", where);
  const std::string shape = std::to_string(n) + " rows of " + std::to_string(n) + " numbers";
  if (!c.is_array() || c.size() != n)
    return detail::fail(where, "key 'coupling' must be " + shape + " (got " + detail::shown(c) + ")"),
           out;
  for (const json& row : c) {
    if (!row.is_array() || row.size() != n) {
      detail::fail(where,
                   "key 'coupling' must be " + shape + " (got the row " + detail::shown(row) + ")");
      return out;
    }
    for (const json& v : row) {
      if (!v.is_number())
        return detail::fail(where,
                            "key 'coupling' must hold only numbers (got " + detail::shown(v) + ")"),
               out;
      out.coupling.push_back(v.get<double>());
    }
  }
  return out;
}

}  // namespace tendonsheath::io
