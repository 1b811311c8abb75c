// One of the core's forward models, optionally followed by a static polynomial (Python's
// Chain(model, Polynomial)): what RootInverse inverts. A std::variant, so copy-assigning one
// ForwardModel to another of the same kind and sizes allocates nothing.
#pragma once

#include <optional>
#include <variant>

#include "../status.hpp"
#include "../type_list.hpp"
#include "model_list.hpp"

namespace tendonsheath {

/// @brief A forward model of the core, optionally followed by a static polynomial:
/// y = second(first(x, dt)).
class ForwardModel {
 public:
  /// The models a ForwardModel can run first: those of the model list (model_list.hpp) that are
  /// root_invertible (Backlash, BoucWenBacklash, BoucWen, PrandtlIshlinskii,
  /// GeneralizedPrandtlIshlinskii, Polynomial, PlantModel).
  using Models = filter_list_t<tendonsheath::Models, root_invertible>;
  /// One of Models.
  using First = apply_list_t<Models, std::variant>;

  /// @param first the model (copied)
  explicit ForwardModel(First first) : first_(std::move(first)) {}
  /// @param first the model (copied)
  /// @param second the static polynomial applied to its output (copied)
  ForwardModel(First first, const Polynomial& second)
      : first_(std::move(first)), second_(second) {}

  /// Start afresh from the initial state.
  void reset() noexcept {
    std::visit([](auto& m) noexcept { m.reset(); }, first_);
  }
  /// @param x the input
  /// @param dt the time since the previous step, s
  /// @return second(first(x))
  double step(double x, double dt) noexcept {
    const double u = std::visit([&](auto& m) noexcept { return m.step(x, dt); }, first_);
    return second_ ? second_->step(u, dt) : u;
  }
  /// The last step's status flags of both parts.
  Status status() const noexcept {
    const Status s = std::visit([](const auto& m) noexcept { return m.status(); }, first_);
    return second_ ? s | second_->status() : s;
  }
  /// The first model.
  First& first() noexcept { return first_; }
  /// The first model.
  const First& first() const noexcept { return first_; }
  /// True when a polynomial follows the first model.
  bool has_second() const noexcept { return second_.has_value(); }

  /// New parameters of the first model, by its Params::assign order (a BoucWen's: the route
  /// changed them); the state is kept. False (nothing changed) when the model cannot take them.
  bool set_base_params(const double* values) noexcept {
    if (auto* bw = std::get_if<BoucWen>(&first_)) {
      BoucWenParams p = bw->params();
      p.assign(values);
      return bw->set_params(p);
    }
    return false;
  }

 private:
  First first_;
  std::optional<Polynomial> second_;
};

}  // namespace tendonsheath
