// Bidirectional pull-pull pair (seeds 000 and 002, spec A.4/A.5): two
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
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "../route.hpp"
#include "../validate.hpp"
#include "friction_chain.hpp"
#include "single_tendon.hpp"

namespace tendonsheath {

struct PullPullParams {
  double friction = 0.1;           // mu
  double stiffness = 2.4e4;        // EA, N
  double pretension = 10.0;        // T0, N
  double proximal_radius = 5e-3;   // r_p, m
  double distal_radius = 5e-3;     // r_d, m
  int elements = 100;              // N per sheath, >= 2
  double load_torque = 0.0;        // tau_0, N m
  double load_stiffness = 0.0;     // k_theta, N m/rad
  double load_damping = 0.0;       // c_theta, N m s/rad
  ChainOptions options;
};

class PullPullPlant {
 public:
  using Params = PullPullParams;

  // route1: sheath of tendon 1 (pulled by positive input); route2: sheath of tendon 2.
  PullPullPlant(const Params& p, const Route& route1, const Route& route2)
      : p_(p),
        N_(static_cast<std::size_t>(p.elements > 0 ? p.elements : 0)),
        L1_(route1.length()),
        L2_(route2.length()) {
    const char* w = "PullPullPlant";
    detail::validate_tendon(p.friction, p.stiffness, p.elements, w);
    require_positive(p.pretension, w, "pretension");
    require_positive(p.proximal_radius, w, "proximal_radius");
    require_positive(p.distal_radius, w, "distal_radius");
    require_finite(p.load_torque, w, "load_torque");
    require_non_negative(p.load_stiffness, w, "load_stiffness");
    require_non_negative(p.load_damping, w, "load_damping");
    validate_chain_options(p.options, w);
    const std::size_t M = 2 * N_;
    chain_ = FrictionChain(M);
    const double k2 = p.stiffness * static_cast<double>(N_) / L2_;
    const double k1 = p.stiffness * static_cast<double>(N_) / L1_;
    for (std::size_t e = 1; e <= N_; ++e) chain_.set_element(e, k2, p.pretension);
    for (std::size_t e = N_ + 1; e <= M; ++e) chain_.set_element(e, k1, p.pretension);
    chain_.set_driven(0);
    chain_.set_driven(M);
    const double rd = p.distal_radius;
    chain_.set_load(N_, p.load_torque / rd, p.load_stiffness / (rd * rd),
                    p.load_damping / (rd * rd));
    chain_.set_options(p.options);
    chain_.set_friction(p.friction);
    angles_.assign(2 * (N_ - 1), 0.0);
    work_.assign(N_, 0.0);
    set_route(route1, route2);
    reset();
  }

  PullPullPlant(const Params& p, const Route& route) : PullPullPlant(p, route, route) {}

  const Params& params() const noexcept { return p_; }
  std::size_t elements() const noexcept { return N_; }
  double length1() const noexcept { return L1_; }
  double length2() const noexcept { return L2_; }
  double total_angle1() const noexcept { return theta1_; }
  double total_angle2() const noexcept { return theta2_; }

  void reset() noexcept { chain_.reset(); }

  // Proximal pulley angle in (rad), distal pulley angle out (rad).
  double step(double q_in, double dt = 0.0) noexcept {
    chain_.step(p_.proximal_radius * q_in, dt);
    return output();
  }
  double output() const noexcept { return chain_.u(N_) / p_.distal_radius; }
  double input() const noexcept { return chain_.input() / p_.proximal_radius; }
  double output_displacement() const noexcept { return chain_.u(N_); }

  void set_route(const Route& r1, const Route& r2) {
    detail::check_route_length(r1, L1_, "PullPullPlant.set_route (sheath 1)");
    detail::check_route_length(r2, L2_, "PullPullPlant.set_route (sheath 2)");
    r1.node_angles(N_, angles_.data(), work_.data());
    r2.node_angles(N_, angles_.data() + (N_ - 1), work_.data());
    set_node_angles(angles_.data());
  }
  void set_route(const Route& r) { set_route(r, r); }

  // 2(N-1) lumped node angles: sheath 1 then sheath 2, each proximal to distal.
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
  std::size_t n_node_angles() const noexcept { return 2 * (N_ - 1); }
  void node_angles(const Route& r1, const Route& r2, double* out) const {
    detail::check_route_length(r1, L1_, "PullPullPlant (sheath 1)");
    detail::check_route_length(r2, L2_, "PullPullPlant (sheath 2)");
    std::vector<double> work(N_);
    r1.node_angles(N_, out, work.data());
    r2.node_angles(N_, out + (N_ - 1), work.data());
  }

  // Tensions (2 x N): row 0 tendon 1, row 1 tendon 2, each proximal to distal.
  void tensions(double* out) const noexcept {
    for (std::size_t i = 1; i <= N_; ++i) {
      out[i - 1] = chain_.tension(2 * N_ - i + 1);
      out[N_ + i - 1] = chain_.tension(i);
    }
  }
  // Stick/slip (2 x (N-1)), proximal to distal: +1 tendon slipping toward its
  // proximal end, -1 toward its distal end, 0 stuck.
  void slip_state(int* out) const noexcept {
    for (std::size_t i = 1; i < N_; ++i) {
      out[i - 1] = chain_.state(2 * N_ - i);
      out[N_ - 1 + i - 1] = -chain_.state(i);
    }
  }
  // Torque of the tendons on the proximal pulley, positive along the input.
  double drive_reaction() const noexcept {
    return p_.proximal_radius * (chain_.tension(1) - chain_.tension(2 * N_));
  }
  bool slack() const noexcept { return chain_.slack(); }
  double min_tension() const noexcept { return chain_.min_tension(); }
  long nonconverged() const noexcept { return chain_.nonconverged(); }
  const FrictionChain& chain() const noexcept { return chain_; }

 private:
  void update_increment() noexcept {
    if (p_.options.max_increment > 0.0) return;
    ChainOptions o = chain_.options();
    const double L = L1_ > L2_ ? L1_ : L2_;
    const double th = theta1_ > theta2_ ? theta1_ : theta2_;
    o.max_increment = detail::default_increment(p_.pretension, L, p_.stiffness, p_.friction * th);
    chain_.set_options(o);
  }

  Params p_;
  std::size_t N_;
  double L1_, L2_;
  double theta1_ = 0.0, theta2_ = 0.0;
  FrictionChain chain_;
  std::vector<double> angles_, work_;
};

}  // namespace tendonsheath
