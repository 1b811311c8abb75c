// One tendon in one sheath (spec A.1-A.3): proximal displacement in, distal
// displacement out (metres), with a distal load law F = F0 + k x_out that
// resists pulling. The tendon is at rest with uniform tension F0 (the load
// at x_out = 0), so F0 > 0 unless the load is a plain spring.
//
// Chain (spec A.5): node 0 is the distal end (load node), nodes 1..N-1 are
// sheath nodes, node N is the driven proximal end; positive displacement
// points toward the proximal end (pulling).
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "../route.hpp"
#include "../validate.hpp"
#include "friction_chain.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of SingleTendonPlant (validated by its constructor); SI units.
struct SingleTendonParams {
  double friction = 0.1;        ///< mu
  double stiffness = 2.4e4;     ///< EA, N
  int elements = 100;           ///< N >= 2
  double load_force = 10.0;     ///< F0, N: distal load (and tendon tension) at x_out = 0
  double load_stiffness = 0.0;  ///< k, N/m
  double sheath_viscosity = 0.0;     ///< N s/m^2: viscous drag per metre of sheath
  double relaxation_fraction = 0.0;  ///< SLS tendon: share of EA in the Maxwell arm, [0, 1)
  double relaxation_time = 1.0;      ///< s
  ChainOptions options;  ///< numerical options of the friction chain (bound the work of a step)
};

/// The parameter table of SingleTendonParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<SingleTendonParams> {
  static constexpr const char* owner = "SingleTendonPlant";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("friction", &SingleTendonParams::friction, "", non_negative(),
            "mu, the sheath's Coulomb friction coefficient"),
      param("stiffness", &SingleTendonParams::stiffness, "N", positive(),
            "EA, the tendon's axial stiffness"),
      param("elements", &SingleTendonParams::elements, "", documented(2, true, 1000000, true),
            "N, the sheath's element count"),
      param("load_force", &SingleTendonParams::load_force, "N", finite(),
            "F0: distal load (and tendon tension) at x_out = 0; F0 > 0 or k > 0, F0 / EA < 0.05"),
      param("load_stiffness", &SingleTendonParams::load_stiffness, "N/m", non_negative(),
            "k, the distal load's spring"),
      param("sheath_viscosity", &SingleTendonParams::sheath_viscosity, "N s/m^2", non_negative(),
            "viscous drag per metre of sheath"),
      param("relaxation_fraction", &SingleTendonParams::relaxation_fraction, "", documented(0.0, true, 1.0, false),
            "SLS tendon: share of EA in the Maxwell arm"),
      param("relaxation_time", &SingleTendonParams::relaxation_time, "s", positive(),
            "tau of the Maxwell arm"),
      param("options", &SingleTendonParams::options, "", any(),
            "ChainOptions: numerical options of the friction chain (bound the work of a step)"));
};

namespace detail {
inline void validate_elements(int N, const char* w) {
  require(N >= 2, w, "elements must be >= 2 (got ", N, ")");
  require(N <= 1000000, w, "elements must be <= 1000000 (got ", N, ")");
}

/// The largest rest strain T / EA a plant accepts. The model is linear and small-strain (spec A.2:
/// eps = T / EA, the geometry unchanged by the stretch); spec section 1 puts T0 / EA at 8e-3 at most
/// (T0 <= 40 N, EA >= 5e3 N), and a steel rope breaks near 2 % strain, a polymer (UHMWPE) one near
/// 3.5 %: at 5 % the tendon has broken and the model means nothing.
constexpr double kMaxRestStrain = 0.05;

// The tension a tendon carries at rest must stretch it by less than kMaxRestStrain.
inline void validate_rest_strain(double T, double EA, const char* w, const char* name) {
  require(!(T / EA >= kMaxRestStrain), w, name, " / EA must be < 0.05 (got ", T, " N / ", EA,
          " N = ", T / EA, "): a tendon breaks near 2-4 % strain and the model (spec A.2) is "
          "small-strain");
}

// Default sub-increment: 1/20 of the backlash half-width T L tanh(a/2)/EA;
// 0 (no limit) without friction.
inline double default_increment(double T, double L, double EA, double a) noexcept {
  const double e = T * L * std::tanh(0.5 * a) / EA;
  return e > 0.0 ? e / 20.0 : 0.0;
}

// The half-open bound of the relaxing share every plant has (the table's other rows are
// checked by validate_fields).
inline void validate_relaxation_fraction(double fraction, const char* w) {
  require(fraction >= 0.0 && fraction < 1.0, w, "relaxation_fraction must be in [0, 1) (got ",
          fraction, ")");
}

inline void check_route_length(const Route& r, double L, const char* w) {
  require(std::fabs(r.length() - L) <= 1e-9 * L, w, "the new route is ", r.length(),
          " m long but the sheath is ", L, " m (a route may bend, not change length)");
}
}  // namespace detail

/// @brief One tendon in one sheath (spec A.1-A.3): proximal displacement in, distal displacement
/// out (m), with a distal load law F = F0 + k x_out that resists pulling.
///
/// A FrictionChain of N elements: node 0 is the distal end (load node), nodes 1..N-1 sheath
/// nodes, node N the driven proximal end; positive displacement is toward the proximal end. At
/// rest the tension is uniform, F0. The constructor allocates and may throw (set_route() may
/// throw too); step() is noexcept, allocates nothing and does bounded work (FrictionChain::max_solves()).
class SingleTendonPlant {
 public:
  /// The parameter struct its constructor takes.
  using Params = SingleTendonParams;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range
  /// @param route the sheath's route (its length is the sheath length)
  SingleTendonPlant(const Params& p, const Route& route)
      : p_(p), N_(static_cast<std::size_t>(p.elements > 0 ? p.elements : 0)), L_(route.length()) {
    const char* w = "SingleTendonPlant";
    validate_fields(p, w);  // each field's own bound, from ParamTable<SingleTendonParams>
    detail::validate_elements(p.elements, w);
    detail::validate_relaxation_fraction(p.relaxation_fraction, w);
    require(p.load_force > 0.0 || p.load_stiffness > 0.0, w,
            "the load must pull the tendon: load_force > 0 or load_stiffness > 0");
    detail::validate_rest_strain(p.load_force, p.stiffness, w, "load_force");
    validate_chain_options(p.options, w);
    if (detail::failed()) return;  // without exceptions, in make(): no chain of a bad size
    chain_ = FrictionChain(N_);
    const double k = p.stiffness * static_cast<double>(N_) / L_;
    for (std::size_t e = 1; e <= N_; ++e) chain_.set_element(e, k, p.load_force);
    chain_.set_load(0, p.load_force, p.load_stiffness, 0.0);
    chain_.set_driven(N_);
    chain_.set_options(p.options);
    chain_.set_friction(p.friction);
    if (p.sheath_viscosity > 0.0)
      for (std::size_t i = 1; i < N_; ++i)
        chain_.set_node_viscosity(i, p.sheath_viscosity * L_ / static_cast<double>(N_));
    if (p.relaxation_fraction > 0.0) chain_.set_relaxation(p.relaxation_fraction, p.relaxation_time);
    chain_.set_slack_strict(true);  // a plain spring load starts at exactly zero tension
    angles_.assign(N_ - 1, 0.0);
    work_.assign(N_, 0.0);
    set_route(route);
    reset();
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// The number of elements N.
  std::size_t elements() const noexcept { return N_; }
  /// The sheath length L, m.
  double length() const noexcept { return L_; }
  /// The curve angle of the current route, rad.
  double curve_angle() const noexcept { return curve_angle_; }
  /// The curve angle by its old name (docs/vocabulary.md).
  [[deprecated("use curve_angle()")]] double total_angle() const noexcept { return curve_angle(); }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    chain_.reset();
    updated_ = true;
  }

  /// Proximal displacement in (m), distal displacement out (m).
  /// @param x_in the proximal displacement, m; a non-finite one leaves the state unchanged
  /// @param dt the time since the previous step, s (used only when time_dependent())
  /// @return the distal displacement, m
  double step(double x_in, double dt = 0.0) noexcept {
    updated_ = chain_.step(x_in, dt);
    return output();
  }
  /// The distal displacement after the last step, m.
  double output() const noexcept { return chain_.u(0); }
  /// The proximal displacement of the last step, m (after clamping).
  double input() const noexcept { return chain_.input(); }

  /// Route changes (length must stay the same; throws std::invalid_argument otherwise). It
  /// allocates nothing; in a noexcept loop, compute node_angles() beforehand and call
  /// set_node_angles().
  void set_route(const Route& r) {
    detail::check_route_length(r, L_, "SingleTendonPlant.set_route");
    r.node_angles(N_, angles_.data(), work_.data());
    set_node_angles(angles_.data());
  }
  /// N-1 lumped angles of the interior sheath nodes, proximal to distal.
  void set_node_angles(const double* a) noexcept {
    double sum = 0.0;
    for (std::size_t i = 1; i < N_; ++i) {
      chain_.set_node_angle(N_ - i, a[i - 1]);
      sum += a[i - 1];
    }
    curve_angle_ = sum;
    update_increment();
  }
  /// The number of lumped node angles set_node_angles() reads, N - 1.
  std::size_t n_node_angles() const noexcept { return N_ - 1; }
  /// Write route r's N - 1 lumped node angles (rad) into out, for set_node_angles() in a loop later
  /// (not real-time: it allocates; throws when r's length differs from the sheath's).
  void node_angles(const Route& r, double* out) {
    detail::check_route_length(r, L_, "SingleTendonPlant");
    std::vector<double> work(N_);
    r.node_angles(N_, out, work.data());
  }

  /// Tensions of the N elements, proximal to distal.
  void tensions(double* out) const noexcept {
    for (std::size_t i = 1; i <= N_; ++i) out[i - 1] = chain_.tension(N_ - i + 1);
  }
  /// Stick/slip state of the N-1 interior nodes, proximal to distal:
  /// +1 slipping toward the proximal end (pulled), -1 toward the distal end, 0 stuck.
  void slip_state(int* out) const noexcept {
    for (std::size_t i = 1; i < N_; ++i) out[i - 1] = chain_.state(N_ - i);
  }
  /// Force the tendon exerts on the actuator, in the direction of positive input.
  double drive_reaction() const noexcept { return -chain_.tension(N_); }
  /// True when the last step left a tension <= 0 (the load pushes: the model is not valid there).
  bool slack() const noexcept { return chain_.slack(); }
  /// The smallest element tension, N (O(N)).
  double min_tension() const noexcept { return chain_.min_tension(); }
  /// Steps that reached the work bound since reset().
  long nonconverged() const noexcept { return chain_.nonconverged(); }
  /// The last step's status (see status.hpp): read right after step(). A step whose state
  /// the chain did not update (FrictionChain::step returned false) is flagged held when its
  /// input was not finite, else not_converged.
  Status status() const noexcept { return chain_.status_after(updated_); }
  /// True when a step depends on dt (sheath viscosity or tendon relaxation).
  bool time_dependent() const noexcept { return chain_.time_dependent(); }
  /// The underlying friction chain.
  const FrictionChain& chain() const noexcept { return chain_; }

 private:
  void update_increment() noexcept {
    if (p_.options.max_increment > 0.0) return;
    ChainOptions o = chain_.options();
    const double T = p_.load_force > 1.0 ? p_.load_force : 1.0;
    o.max_increment = detail::default_increment(T, L_, p_.stiffness, p_.friction * curve_angle_);
    chain_.set_options(o);
  }

  Params p_;
  std::size_t N_;
  double L_;
  double curve_angle_ = 0.0;
  FrictionChain chain_;
  std::vector<double> angles_, work_;
  bool updated_ = true;
};

}  // namespace tendonsheath
