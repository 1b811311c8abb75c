// The one list of the core's model classes that a model file, a ModelPart and the inverse's
// factory know by name. Everything that dispatches on a model's kind follows from it:
// ModelPart's members (and their Python properties), ForwardModel's variant, the JSON reader's
// dispatch (io/json_models.hpp), make_model_inverse's, the batch population bindings and the
// maps Python reads (_core.model_kinds()).
//
// Adding a model: its header (the class, `using Params`, a ParamTable<Params> whose `owner` is
// the class name, and `vector_size` / `assign()` for a fixed-size parameter vector), one
// X(...) line below (the class and the ModelPart member that holds its parameters), and its
// Python class. A model whose inverse is not the root search on the model itself says so with
// root_invertible below, and gets its own inverse_plan() in make_model_inverse.hpp.
#pragma once

#include <string>
#include <type_traits>

#include "../param_table.hpp"
#include "../type_list.hpp"
#include "backlash.hpp"
#include "bouc_wen.hpp"
#include "bouc_wen_backlash.hpp"
#include "curve_angle.hpp"
#include "dead_zone.hpp"
#include "generalized_prandtl_ishlinskii.hpp"
#include "hysteretic_oscillator.hpp"
#include "plant_model.hpp"
#include "polynomial.hpp"
#include "prandtl_ishlinskii.hpp"

/// X(Model, member) for every model class of the list: the class, and the ModelPart member (its
/// Python property too) that holds its Model::Params. The order is the order of ModelPart's
/// members, of ForwardModel's variant and of the loader's messages.
#define TENDONSHEATH_MODELS(X)                                      \
  X(Backlash, backlash)                                             \
  X(BoucWenBacklash, bouc_wen_backlash)                             \
  X(BoucWen, bouc_wen)                                              \
  X(PrandtlIshlinskii, prandtl_ishlinskii)                          \
  X(GeneralizedPrandtlIshlinskii, generalized_prandtl_ishlinskii)   \
  X(Polynomial, polynomial)                                         \
  X(PlantModel, plant_model)                                        \
  X(HystereticOscillator, hysteretic_oscillator)                    \
  X(CurveAngleModel, curve_angle_model)                             \
  X(DeadZone, dead_zone)

namespace tendonsheath {

#define TENDONSHEATH_DETAIL_LIST_ENTRY(Model, member) +TypeList<Model>{}
/// The model classes of TENDONSHEATH_MODELS, as a TypeList.
using Models = decltype(TypeList<>{} TENDONSHEATH_MODELS(TENDONSHEATH_DETAIL_LIST_ENTRY));
#undef TENDONSHEATH_DETAIL_LIST_ENTRY

/// The name a model file, a ModelPart's `kind` and Python give model class M (its Python class
/// name): the owner of its parameter table.
template <class M>
constexpr const char* model_kind() noexcept {
  return ParamTable<typename M::Params>::owner;
}

/// Whether model M's inverse may be the root search on M itself (RootInverse<ForwardModel>, so
/// M is one of ForwardModel's models): false for the models whose inverse is their own and
/// cannot be the root search (the oscillator's OscillatorInverse; the curve-angle model's
/// CurveAngleFeedforward, which follows the route).
template <class M>
struct root_invertible : std::true_type {};
/// (see root_invertible)
template <>
struct root_invertible<HystereticOscillator> : std::false_type {};
/// (see root_invertible)
template <>
struct root_invertible<CurveAngleModel> : std::false_type {};

/// Whether parameter struct P has a fixed-size identifiable vector (vector_size and assign()):
/// what the batch population evaluation and an AngleDependent's laws need.
template <class P, class = void>
struct has_vector_size : std::false_type {};
/// (see has_vector_size)
template <class P>
struct has_vector_size<P, std::void_t<decltype(P::vector_size)>> : std::true_type {};

/// Whether model M's parameters are a fixed-size vector (has_vector_size of M::Params).
template <class M>
struct has_param_vector : has_vector_size<typename M::Params> {};

/// Calls f(TypeTag<M>{}) for the model M of the list whose kind is `kind`, if there is one.
/// @return whether there was one
template <class F>
bool visit_model_kind(const std::string& kind, F&& f) {
  return any_type(Models{}, [&](auto tag) {
    using M = typename decltype(tag)::type;
    if (kind != model_kind<M>()) return false;
    f(tag);
    return true;
  });
}

}  // namespace tendonsheath
