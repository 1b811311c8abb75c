// Bidirectional pull-pull pair (Sun, Wang & Phee 2015; Do et al. 2015; spec A.4/A.5): two
// pretensioned tendons in two sheaths between a proximal pulley (angle in,
// radius r_p) and a distal pulley (angle out, radius r_d) with a load.
//
// Chain: node 0 is the proximal end of tendon 2, nodes 1..N-1 run through
// sheath 2 (proximal to distal), node N is the distal pulley, nodes N+1..2N-1
// run back through sheath 1 (distal to proximal) and node 2N is the proximal
// end of tendon 1. Positive displacement flows toward node 2N: a positive
// input angle pulls tendon 1 and feeds tendon 2; u_0 = u_2N = r_p q_in and
// q_out = u_N / r_d. The load at the distal pulley is a linear law in the
// output angle, tau_L = tau_0 + k_theta q_out + c_theta dq_out/dt (resisting
// positive motion), i.e. F_L = tau_L / r_d at the tendon level.
//
// Effects beyond the quasi-static capstan pair, all off by default (see
// friction_chain.hpp for how each enters the solve):
// - a dynamic distal joint: inertia J_d (and damping c_d) on the distal
//   pulley, i.e. a mass J_d / r_d^2 at the tendon level;
// - viscous sheath friction (N s/m per metre of sheath) on the sliding tendon;
// - tendon viscoelasticity: a standard linear solid in every element
//   (relaxation_fraction of EA relaxing with relaxation_time), which creeps;
// - an unequal pair: tendon 2 may have its own EA (stiffness2) and sheath 2
//   its own friction (friction2), besides its own route and length.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "../route.hpp"
#include "../validate.hpp"
#include "friction_chain.hpp"
#include "single_tendon.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of PullPullPlant (validated by its constructor); SI units.
struct PullPullParams {
  double friction = 0.1;           ///< mu
  double stiffness = 2.4e4;        ///< EA, N
  double pretension = 10.0;        ///< T0, N
  double proximal_radius = 5e-3;   ///< r_p, m
  double distal_radius = 5e-3;     ///< r_d, m
  int elements = 100;              ///< N per sheath, >= 2
  double load_torque = 0.0;        ///< tau_0, N m
  double load_stiffness = 0.0;     ///< k_theta, N m/rad
  double load_damping = 0.0;       ///< c_theta, N m s/rad
  double distal_inertia = 0.0;     ///< J_d, kg m^2: the distal joint's inertia
  double distal_damping = 0.0;     ///< c_d, N m s/rad: the distal joint's viscous damping
  double sheath_viscosity = 0.0;   ///< N s/m^2: viscous drag per metre of sheath
  double relaxation_fraction = 0.0;  ///< r in [0, 1): share of EA in the Maxwell arm
  double relaxation_time = 1.0;      ///< tau, s
  double friction2 = -1.0;         ///< mu of sheath 2; -1: the same as friction
  double stiffness2 = -1.0;        ///< EA of tendon 2, N; -1: the same as stiffness
  ChainOptions options;  ///< numerical options of the friction chain (bound the work of a step)
};

/// The parameter table of PullPullParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<PullPullParams> {
  static constexpr const char* owner = "PullPullPlant";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("friction", &PullPullParams::friction, "", non_negative(),
            "mu, the sheaths' Coulomb friction coefficient"),
      param("stiffness", &PullPullParams::stiffness, "N", positive(),
            "EA of each tendon"),
      param("pretension", &PullPullParams::pretension, "N", positive(),
            "T0, pretension / EA < 0.05"),
      param("proximal_radius", &PullPullParams::proximal_radius, "m", positive(),
            "r_p, the proximal pulley's radius"),
      param("distal_radius", &PullPullParams::distal_radius, "m", positive(),
            "r_d, the distal pulley's radius"),
      param("elements", &PullPullParams::elements, "", documented(2, true, 1000000, true),
            "N per sheath"),
      param("load_torque", &PullPullParams::load_torque, "N m", finite(),
            "tau_0, the distal load's constant torque"),
      param("load_stiffness", &PullPullParams::load_stiffness, "N m/rad", non_negative(),
            "k_theta, the distal load's spring"),
      param("load_damping", &PullPullParams::load_damping, "N m s/rad", non_negative(),
            "c_theta, the distal load's damper"),
      param("distal_inertia", &PullPullParams::distal_inertia, "kg m^2", non_negative(),
            "J_d, the distal joint's inertia"),
      param("distal_damping", &PullPullParams::distal_damping, "N m s/rad", non_negative(),
            "c_d, the distal joint's viscous damping"),
      param("sheath_viscosity", &PullPullParams::sheath_viscosity, "N s/m^2", non_negative(),
            "viscous drag per metre of sheath"),
      param("relaxation_fraction", &PullPullParams::relaxation_fraction, "", documented(0.0, true, 1.0, false),
            "SLS tendon: share of EA in the Maxwell arm"),
      param("relaxation_time", &PullPullParams::relaxation_time, "s", positive(),
            "tau of the Maxwell arm"),
      param("friction2", &PullPullParams::friction2, "", documented(0.0, true, kInf, false),
            "mu of sheath 2; -1: the same as friction"),
      param("stiffness2", &PullPullParams::stiffness2, "N", documented(0.0, false, kInf, false),
            "EA of tendon 2; -1: the same as stiffness"),
      param("options", &PullPullParams::options, "", any(),
            "ChainOptions: numerical options of the friction chain (bound the work of a step)"));
};

namespace detail {
inline double friction2_of(const PullPullParams& p) noexcept {
  return p.friction2 == -1.0 ? p.friction : p.friction2;
}
inline double stiffness2_of(const PullPullParams& p) noexcept {
  return p.stiffness2 == -1.0 ? p.stiffness : p.stiffness2;
}
}  // namespace detail

/// @brief Bidirectional pull-pull pair (spec A.4/A.5): two pretensioned tendons in two sheaths
/// between a proximal pulley (angle in, radius r_p) and a distal pulley (angle out, radius r_d)
/// with a load.
///
/// A FrictionChain of 2N elements: tendon 2 from its proximal end through sheath 2 to the distal
/// pulley (node N), then back through sheath 1 to the proximal end of tendon 1. A positive input
/// pulls tendon 1; u_0 = u_2N = r_p q_in and q_out = u_N / r_d. The load resists positive motion:
/// tau_L = tau_0 + k_theta q_out + c_theta dq_out/dt. Optional (off by default): distal inertia and
/// damping, viscous sheath friction, tendon viscoelasticity, an unequal pair. The constructor
/// allocates and may throw (set_route() may throw too); step() is noexcept, allocates nothing and
/// does bounded work (FrictionChain::max_solves()).
class PullPullPlant {
 public:
  /// The parameter struct its constructor takes.
  using Params = PullPullParams;

  /// route1: sheath of tendon 1 (pulled by positive input); route2: sheath of tendon 2.
  /// @param p the parameters; throws std::invalid_argument naming the first one out of range
  /// @param route1 the route of sheath 1 (its tendon is pulled by a positive input)
  /// @param route2 the route of sheath 2
  PullPullPlant(const Params& p, const Route& route1, const Route& route2)
      : p_(p),
        N_(static_cast<std::size_t>(p.elements > 0 ? p.elements : 0)),
        L1_(route1.length()),
        L2_(route2.length()) {
    const char* w = "PullPullPlant";
    validate_fields(p, w);  // each field's own bound, from ParamTable<PullPullParams>
    detail::validate_elements(p.elements, w);
    detail::validate_relaxation_fraction(p.relaxation_fraction, w);
    require(p.friction2 == -1.0 || (p.friction2 >= 0.0 && std::isfinite(p.friction2)), w,
            "friction2 must be finite and >= 0, or -1 for the same as friction (got ", p.friction2,
            ")");
    require(p.stiffness2 == -1.0 || (p.stiffness2 > 0.0 && std::isfinite(p.stiffness2)), w,
            "stiffness2 must be finite and > 0, or -1 for the same as stiffness (got ",
            p.stiffness2, ")");
    detail::validate_rest_strain(p.pretension, std::fmin(p.stiffness, detail::stiffness2_of(p)), w,
                                 "pretension");
    validate_chain_options(p.options, w);
    if (detail::failed()) return;  // without exceptions, in make(): no chain of a bad size
    const std::size_t M = 2 * N_;
    chain_ = FrictionChain(M);
    const double k2 = detail::stiffness2_of(p) * static_cast<double>(N_) / L2_;
    const double k1 = p.stiffness * static_cast<double>(N_) / L1_;
    for (std::size_t e = 1; e <= N_; ++e) chain_.set_element(e, k2, p.pretension);
    for (std::size_t e = N_ + 1; e <= M; ++e) chain_.set_element(e, k1, p.pretension);
    chain_.set_driven(0);
    chain_.set_driven(M);
    const double rd = p.distal_radius;
    chain_.set_load(N_, p.load_torque / rd, p.load_stiffness / (rd * rd),
                    (p.load_damping + p.distal_damping) / (rd * rd), p.distal_inertia / (rd * rd));
    chain_.set_options(p.options);
    chain_.set_friction(p.friction);
    const double mu2 = detail::friction2_of(p);
    for (std::size_t i = 1; i < N_; ++i) {
      chain_.set_node_friction(i, mu2);  // sheath 2 node i
      if (p.sheath_viscosity > 0.0) {
        chain_.set_node_viscosity(i, p.sheath_viscosity * L2_ / static_cast<double>(N_));
        chain_.set_node_viscosity(2 * N_ - i, p.sheath_viscosity * L1_ / static_cast<double>(N_));
      }
    }
    if (p.relaxation_fraction > 0.0) chain_.set_relaxation(p.relaxation_fraction, p.relaxation_time);
    angles_.assign(2 * (N_ - 1), 0.0);
    work_.assign(N_, 0.0);
    set_route(route1, route2);
    reset();
  }

  /// Both sheaths along the same route.
  PullPullPlant(const Params& p, const Route& route) : PullPullPlant(p, route, route) {}

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// The number of elements N per sheath.
  std::size_t elements() const noexcept { return N_; }
  /// The length of sheath 1, m.
  double length1() const noexcept { return L1_; }
  /// The length of sheath 2, m.
  double length2() const noexcept { return L2_; }
  /// The curve angle of sheath 1's current route, rad.
  double curve_angle1() const noexcept { return theta1_; }
  /// The curve angle of sheath 2's current route, rad.
  double curve_angle2() const noexcept { return theta2_; }
  /// curve_angle1() by its old name (docs/vocabulary.md).
  [[deprecated("use curve_angle1()")]] double total_angle1() const noexcept { return theta1_; }
  /// curve_angle2() by its old name (docs/vocabulary.md).
  [[deprecated("use curve_angle2()")]] double total_angle2() const noexcept { return theta2_; }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    chain_.reset();
    updated_ = true;
  }

  /// Proximal pulley angle in (rad), distal pulley angle out (rad).
  /// @param q_in the proximal pulley angle, rad; a non-finite one leaves the state unchanged
  /// @param dt the time since the previous step, s (used only when time_dependent())
  /// @return the distal pulley angle, rad
  double step(double q_in, double dt = 0.0) noexcept {
    updated_ = chain_.step(p_.proximal_radius * q_in, dt);
    return output();
  }
  /// The distal pulley angle after the last step, rad.
  double output() const noexcept { return chain_.u(N_) / p_.distal_radius; }
  /// The proximal pulley angle of the last step, rad (after clamping).
  double input() const noexcept { return chain_.input() / p_.proximal_radius; }
  /// The distal pulley's displacement at the tendon level, r_d q_out, m.
  double output_displacement() const noexcept { return chain_.u(N_); }

  /// New routes for the sheaths (each length must stay the same; throws std::invalid_argument
  /// otherwise). It allocates nothing; in a noexcept loop, compute node_angles() beforehand and call
  /// set_node_angles().
  void set_route(const Route& r1, const Route& r2) {
    detail::check_route_length(r1, L1_, "PullPullPlant.set_route (sheath 1)");
    detail::check_route_length(r2, L2_, "PullPullPlant.set_route (sheath 2)");
    r1.node_angles(N_, angles_.data(), work_.data());
    r2.node_angles(N_, angles_.data() + (N_ - 1), work_.data());
    set_node_angles(angles_.data());
  }
  /// Both sheaths along the same new route (see the two-route set_route()).
  void set_route(const Route& r) { set_route(r, r); }

  /// 2(N-1) lumped node angles: sheath 1 then sheath 2, each proximal to distal.
  void set_node_angles(const double* a) noexcept {
    double s1 = 0.0, s2 = 0.0;
    for (std::size_t i = 1; i < N_; ++i) {
      chain_.set_node_angle(2 * N_ - i, a[i - 1]);  // sheath 1 node i
      chain_.set_node_angle(i, a[N_ - 1 + i - 1]);  // sheath 2 node i
      s1 += a[i - 1];
      s2 += a[N_ - 1 + i - 1];
    }
    theta1_ = s1;
    theta2_ = s2;
    update_increment();
  }
  /// The number of lumped node angles set_node_angles() reads, 2 (N - 1).
  std::size_t n_node_angles() const noexcept { return 2 * (N_ - 1); }
  /// Write the routes' 2 (N - 1) lumped node angles (rad) into out, for set_node_angles() in a loop
  /// later (not real-time: it allocates; throws when a length differs from the sheath's).
  void node_angles(const Route& r1, const Route& r2, double* out) const {
    detail::check_route_length(r1, L1_, "PullPullPlant (sheath 1)");
    detail::check_route_length(r2, L2_, "PullPullPlant (sheath 2)");
    std::vector<double> work(N_);
    r1.node_angles(N_, out, work.data());
    r2.node_angles(N_, out + (N_ - 1), work.data());
  }

  /// Tensions (2 x N): row 0 tendon 1, row 1 tendon 2, each proximal to distal.
  void tensions(double* out) const noexcept {
    for (std::size_t i = 1; i <= N_; ++i) {
      out[i - 1] = chain_.tension(2 * N_ - i + 1);
      out[N_ + i - 1] = chain_.tension(i);
    }
  }
  /// Stick/slip (2 x (N-1)), proximal to distal: +1 tendon slipping toward its
  /// proximal end, -1 toward its distal end, 0 stuck.
  void slip_state(int* out) const noexcept {
    for (std::size_t i = 1; i < N_; ++i) {
      out[i - 1] = chain_.state(2 * N_ - i);
      out[N_ - 1 + i - 1] = -chain_.state(i);
    }
  }
  /// Torque of the tendons on the proximal pulley, positive along the input.
  double drive_reaction() const noexcept {
    return p_.proximal_radius * (chain_.tension(1) - chain_.tension(2 * N_));
  }
  /// True when the last step left a tension <= 0 (a tendon went slack: the model is not valid there).
  bool slack() const noexcept { return chain_.slack(); }
  /// The smallest element tension, N (O(N)).
  double min_tension() const noexcept { return chain_.min_tension(); }
  /// Steps that reached the work bound since reset().
  long nonconverged() const noexcept { return chain_.nonconverged(); }
  /// The last step's status (see status.hpp): read right after step(). A step whose state
  /// the chain did not update (FrictionChain::step returned false) is flagged held when its
  /// input was not finite, else not_converged.
  Status status() const noexcept { return chain_.status_after(updated_); }
  /// True when a step depends on dt (distal dynamics, damping, viscosity, creep).
  bool time_dependent() const noexcept { return chain_.time_dependent(); }
  /// The underlying friction chain.
  const FrictionChain& chain() const noexcept { return chain_; }

 private:
  void update_increment() noexcept {
    if (p_.options.max_increment > 0.0) return;
    ChainOptions o = chain_.options();
    const double L = L1_ > L2_ ? L1_ : L2_;
    const double a1 = p_.friction * theta1_, a2 = detail::friction2_of(p_) * theta2_;
    const double EA1 = p_.stiffness, EA2 = detail::stiffness2_of(p_);
    o.max_increment = detail::default_increment(p_.pretension, L, EA1 > EA2 ? EA1 : EA2,
                                                a1 > a2 ? a1 : a2);
    chain_.set_options(o);
  }

  Params p_;
  std::size_t N_;
  double L1_, L2_;
  double theta1_ = 0.0, theta2_ = 0.0;
  FrictionChain chain_;
  std::vector<double> angles_, work_;
  bool updated_ = true;
};

}  // namespace tendonsheath
