// The quasi-static N-element friction chain of spec A.5, shared by all plants.
//
// Nodes j = 0..M carry displacements u_j (positive toward node M). Element e
// (e = 1..M) joins nodes e-1 and e, has stiffness k_e = EA/ds and tension
//   T_e = T0_e + k_e (u_e - u_{e-1}).
// Each node is one of
//   Driven  u_j = x (the input; every driven node gets the same x),
//   Sheath  a point of the sheath with friction: stuck (u_j = u_j^prev,
//           allowed while |T_{j+1} - T_j| <= C_j) or slipping in direction
//           s = +-1: (1 - s h_j) T_{j+1} - (1 + s h_j) T_j = 0,
//   Load    a load law T_{j+1} - T_j = F0 + k u_j + c v_j + m a_j with
//           v_j = (u_j - u_j^prev)/dt and a_j = (v_j - v_j^prev)/dt (implicit
//           Euler: a distal joint with inertia, damping and stiffness)
//           (missing elements at the chain ends count as zero tension).
//
// Rate-dependent effects (all linear in u for a fixed stick/slip map, so the
// same tridiagonal solve carries them):
// - viscous sheath friction: a slipping sheath node also feels -c_j v_j
//   (c_j = viscosity x the node's length of sheath), so a fast-moving tendon
//   carries more friction than the Coulomb capacity: rate-dependent hysteresis.
//   A stuck node has v_j = 0, so the capacity test is unchanged.
// - tendon viscoelasticity: each element is a standard linear solid, a spring
//   (1 - r) k in parallel with a Maxwell arm (spring r k, time constant tau):
//   T_e = T0_e + (1 - r) k eps_e + s_e, s_e' = r k eps_e' - s_e/tau. Implicit
//   Euler over a step h (beta = 1/(1 + h/tau)) gives T_e linear in eps_e with
//   k_eff = k (1 - r + r beta) and T0_eff = T0 + beta (s_e^prev - r k eps_e^prev),
//   refreshed before each solve: a held input creeps as the arm relaxes.
// With any of these (or a load damper or mass) the step depends on dt and the
// lazy fast path is off; the solution then costs at least one O(M) solve a step.
// For a sheath node with lumped angle dtheta_j we use h_j = tanh(mu dtheta_j/2)
// instead of mu dtheta_j/2: then the slipping ratio (1 - h)/(1 + h) equals
// exp(-mu dtheta_j) exactly, so the discrete capstan ratio is exact for any
// N (the two differ by O(dtheta^3)). The capacity is C_j = h_j (T_j + T_{j+1}),
// the same h, so a slipping node sits exactly on its capacity.
//
// Per input increment the active-set loop of spec A.5 runs: assemble the
// tridiagonal system for the current stick/slip map, solve it (Thomas, O(M)),
// flip stuck nodes that exceed their capacity and slipping nodes that move
// backwards, until nothing flips (<= max_iterations). On failure the increment
// is halved (<= max_halvings times); at the last level the loop continues from
// its last iterate for extra_iterations more and the result is accepted (and
// counted in nonconverged()). Inputs are split into sub-increments of at most
// max_increment (at most max_substeps of them). step() is noexcept, allocates
// nothing and does bounded work: at most
//   max_solves() = max_substeps + 2 (max_iterations + E),  E = extra_iterations (-1: 2 M + 50)
// tridiagonal solves (an iteration is one solve, plus one after a slip-front march). With the
// default options that is 4 M + 264: 8 N + 264 for a pull-pull pair of N elements per sheath
// (M = 2 N), 4 N + 264 for a single tendon (M = N). A step that reaches the bound keeps its
// last finite iterate (or stops at its last finished sub-increment), reports not_converged
// and counts in nonconverged(); the next step goes on from there to its own input. A
// non-finite input or a non-finite solution leaves the state unchanged (a non-finite
// solution never counts as converged).
// Inputs beyond +-kMaxInput (m) are clamped to it (input_clamped() tells): past
// that the elastic forces k x of a chain no longer fit a double. A node's
// friction angle mu dtheta is capped at kMaxNodeFrictionAngle (capstan ratio
// e^-30 = 1e-13): tanh(mu dtheta/2) would round to exactly 1 near 38 and leave an
// exact zero pivot in the solve.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "../status.hpp"
#include "../validate.hpp"

namespace tendonsheath {

/// What a node of a FrictionChain is: Driven (moved to the input), Sheath (a point of the sheath with
/// friction: stuck or slipping) or Load (a load law: constant force, spring, damper, mass).
enum class NodeKind : unsigned char { Driven = 0, Sheath = 1, Load = 2 };

/// Inputs beyond +-kMaxInput are clamped to it: past that the elastic forces of a chain no longer fit
/// a double.
constexpr double kMaxInput = 1e6;  ///< m: round-off after a return from it stays below 1e-9 m
constexpr double kMaxNodeFrictionAngle = 30.0;  ///< the largest friction angle mu dtheta of one node
constexpr int kMaxIterationsCap = 100000;       ///< the largest accepted max_iterations
constexpr int kMaxSubstepsCap = 100000;         ///< the largest accepted max_substeps and extra_iterations

/// The numerical options of a FrictionChain: they bound the work of one step (see
/// FrictionChain::max_solves()). Validated by validate_chain_options().
struct ChainOptions {
  int max_iterations = 50;     ///< active-set iterations per attempt
  int max_halvings = 4;        ///< halvings of a failed increment
  int max_substeps = 64;       ///< sub-increments per step at most
  double max_increment = 0.0;  ///< largest input sub-increment (m); 0: the plant chooses
  int extra_iterations = -1;   ///< iterations of the last-resort attempt; -1: 2 M + 50
  bool fast_path = true;       ///< exact shortcuts (lazy update while the map stays valid)
};

/// Throws std::invalid_argument (message starting with `where`) naming the first option out of range.
inline void validate_chain_options(const ChainOptions& o, const char* where) {
  require(o.max_iterations >= 1 && o.max_iterations <= kMaxIterationsCap, where,
          "max_iterations must be in [1, " + std::to_string(kMaxIterationsCap) + "] (got " +
              std::to_string(o.max_iterations) + ")");
  require(o.max_halvings >= 0 && o.max_halvings <= 30, where,
          "max_halvings must be in [0, 30] (got " + std::to_string(o.max_halvings) + ")");
  require(o.max_substeps >= 1 && o.max_substeps <= kMaxSubstepsCap, where,
          "max_substeps must be in [1, " + std::to_string(kMaxSubstepsCap) + "] (got " +
              std::to_string(o.max_substeps) + ")");
  require_non_negative(o.max_increment, where, "max_increment");
  require(o.extra_iterations == -1 ||
              (o.extra_iterations >= 1 && o.extra_iterations <= kMaxSubstepsCap),
          where,
          "extra_iterations must be -1 (automatic) or in [1, " + std::to_string(kMaxSubstepsCap) +
              "] (got " + std::to_string(o.extra_iterations) + ")");
}

namespace detail {
inline double node_h(double mu, double dtheta) noexcept {
  const double a = mu * dtheta;
  return std::tanh(0.5 * (a < kMaxNodeFrictionAngle ? a : kMaxNodeFrictionAngle));
}
}  // namespace detail

/// @brief The quasi-static N-element friction chain of spec A.5, shared by all plants.
///
/// Nodes j = 0..M carry displacements u_j; element e joins nodes e-1 and e with tension
/// T_e = T0_e + k_e (u_e - u_{e-1}). Each node is Driven (u_j = x), Sheath (stuck, or slipping with
/// the exact discrete capstan ratio exp(-mu dtheta_j)) or Load (T_{j+1} - T_j = F0 + k u + c v + m a).
/// Viscous sheath friction and viscoelastic (standard linear solid) elements make it rate-dependent.
/// Per input increment an active-set loop solves the tridiagonal system (Thomas, O(M)) and flips
/// nodes until nothing flips, halving a failed increment. The set-up members allocate and may
/// throw; step() is noexcept, allocates nothing and does at most max_solves() solves: a step that
/// reaches the bound keeps its last finite iterate, reports not_converged and counts in
/// nonconverged(). A non-finite input or solution leaves the state unchanged.
class FrictionChain {
 public:
  FrictionChain() = default;

  /// M + 1 nodes (all Sheath, no angle) and M elements (to be set).
  explicit FrictionChain(std::size_t M)
      : M_(M),
        kind_(M + 1, NodeKind::Sheath),
        h_(M + 1, 0.0),
        dtheta_(M + 1, 0.0),
        mu_(M + 1, 0.0),
        cv_(M + 1, 0.0),
        k_(M + 2, 0.0),
        T0_(M + 2, 0.0),
        kb_(M + 2, 0.0),
        T0b_(M + 2, 0.0),
        sigma_(M + 2, 0.0),
        F0_(M + 1, 0.0),
        kl_(M + 1, 0.0),
        cl_(M + 1, 0.0),
        ml_(M + 1, 0.0),
        vel_(M + 1, 0.0),
        u_(M + 1, 0.0),
        w_(M + 1, 0.0),
        sig_(M + 1, 0),
        sw_(M + 1, 0),
        cp_(M + 1, 0.0),
        dp_(M + 1, 0.0),
        zp_(M + 1, 0.0),
        z_(M + 1, 0.0),
        T_(M + 2, 0.0),
        lv_(M + 1, 0.0),
        iv_(M + 1, 1.0),
        fmap_(M + 1, 0) {}

  // ---- set-up (not real-time) ----------------------------------------------------
  /// Set up element e (1..M): stiffness k (N/m) and reference tension T0 (N).
  void set_element(std::size_t e, double k, double T0) {
    k_.at(e) = k;
    T0_.at(e) = T0;
    kb_.at(e) = k;
    T0b_.at(e) = T0;
  }
  /// Make node j a driven node (it moves with the input).
  void set_driven(std::size_t j) { kind_.at(j) = NodeKind::Driven; }
  /// Make node j a load node: T_{j+1} - T_j = F0 + k u_j + c v_j + mass a_j (N, N/m, N s/m, kg).
  void set_load(std::size_t j, double F0, double k, double c, double mass = 0.0) {
    kind_.at(j) = NodeKind::Load;
    F0_.at(j) = F0;
    kl_.at(j) = k;
    cl_.at(j) = c;
    ml_.at(j) = mass;
    has_mass_ = has_mass_ || mass > 0.0;
    has_damper_ = has_damper_ || c > 0.0 || mass > 0.0;
  }
  /// Viscous friction coefficient c_j (N s/m) of sheath node j.
  void set_node_viscosity(std::size_t j, double c) {
    cv_.at(j) = c;
    has_damper_ = has_damper_ || c > 0.0;
  }
  /// Standard-linear-solid elements: fraction r in [0, 1) of each element's
  /// stiffness in a Maxwell arm with time constant tau (s); r = 0: elastic.
  void set_relaxation(double fraction, double tau) {
    relax_ = fraction;
    tau_ = tau;
    has_damper_ = has_damper_ || fraction > 0.0;
  }
  /// Set the numerical options (validate them first with validate_chain_options()).
  void set_options(const ChainOptions& o) noexcept { opt_ = o; }
  /// Set the friction coefficient of every node.
  void set_friction(double mu) noexcept {
    for (std::size_t j = 0; j <= M_; ++j) mu_[j] = mu;
    for (std::size_t j = 0; j <= M_; ++j) h_[j] = detail::node_h(mu_[j], dtheta_[j]);
    dirty_ = true;
    fact_valid_ = false;
    tfact_valid_ = false;
  }
  /// Friction coefficient of one node (e.g.\ a second sheath of another material).
  void set_node_friction(std::size_t j, double mu) {
    mu_.at(j) = mu;
    h_[j] = detail::node_h(mu, dtheta_[j]);
    dirty_ = true;
    fact_valid_ = false;
    tfact_valid_ = false;
  }

  // ---- real-time ---------------------------------------------------------------
  /// Lumped angle of a sheath node (ignored for other nodes). A change takes
  /// effect at the next step; over-capacity nodes then start to slip.
  void set_node_angle(std::size_t j, double dtheta) noexcept {
    if (j > M_ || kind_[j] != NodeKind::Sheath || !(dtheta >= 0.0) || !std::isfinite(dtheta))
      return;
    if (dtheta_[j] == dtheta) return;
    dtheta_[j] = dtheta;
    h_[j] = detail::node_h(mu_[j], dtheta);
    dirty_ = true;
    fact_valid_ = false;
    tfact_valid_ = false;
  }

  /// At rest, uniform reference tensions, everything stuck; the next step()
  /// starts by moving the whole chain rigidly to its input.
  void reset() noexcept {
    std::fill(u_.begin(), u_.end(), 0.0);
    std::fill(sig_.begin(), sig_.end(), 0);
    std::fill(vel_.begin(), vel_.end(), 0.0);
    std::fill(sigma_.begin(), sigma_.end(), 0.0);
    std::copy(kb_.begin(), kb_.end(), k_.begin());
    std::copy(T0b_.begin(), T0b_.end(), T0_.begin());
    elements_dt_ = 0.0;  // at rest the base elements are the effective ones of dt = 0
    x_ = 0.0;
    initialised_ = false;
    dirty_ = true;
    slack_ = false;
    nonconverged_ = 0;
    last_solves_ = 0;
    input_clamped_ = false;
    input_held_ = false;
    last_converged_ = true;
    budget_hit_ = false;
    fact_valid_ = false;
    tfact_valid_ = false;
    consistent_ = false;
    fast_ok_ = false;
    lazy_ = 0.0;
    xref_ = 0.0;
    compute_tensions(u_.data());
  }

  /// Advance to the driven input x (dt: time since the previous step, used by
  /// dampers only). Returns true when the state was updated.
  /// @param x the driven input, m; a non-finite x leaves the state unchanged, one beyond
  /// +-kMaxInput is clamped
  /// @param dt the time since the previous step, s (used only when time_dependent())
  /// @return true when the state was updated (see status())
  bool step(double x, double dt) noexcept {
    input_clamped_ = false;
    input_held_ = !std::isfinite(x);
    if (input_held_) return false;
    if (std::fabs(x) > kMaxInput) {
      x = std::copysign(kMaxInput, x);
      input_clamped_ = true;
    }
    if (!(dt >= 0.0) || !std::isfinite(dt)) dt = 0.0;
    last_solves_ = 0;
    budget_hit_ = false;
    const long noncon_before = nonconverged_;
    if (!initialised_) {
      for (std::size_t j = 0; j <= M_; ++j) u_[j] += x - x_;
      x_ = x;
      initialised_ = true;
      dirty_ = true;
    }
    if (x == x_ && !dirty_ && !(has_damper_ && dt > 0.0)) return true;
    // Fast path: the committed map stays valid for every input in
    // [xlo_, xhi_] moved in an allowed direction (see compute_interval), so
    // the solution is u_ + (x - xref_) z_, kept lazily (O(1) per step).
    if (fast_ok_ && !dirty_ && x >= xlo_ && x <= xhi_ && (x > x_ ? up_ : down_)) {
      x_ = x;
      lazy_ = x - xref_;
      return true;
    }
    materialize();
    const double dx = x - x_;
    int n = 1;
    if (opt_.max_increment > 0.0) {
      const double m = std::ceil(std::fabs(dx) / opt_.max_increment);
      n = m >= static_cast<double>(opt_.max_substeps) ? opt_.max_substeps
                                                        : (m >= 1.0 ? static_cast<int>(m) : 1);
    }
    const double x0 = x_;
    for (int i = 1; i <= n && !budget_hit_; ++i) {
      const double xi = (i == n) ? x : x0 + dx * static_cast<double>(i) / static_cast<double>(n);
      sub_increment(xi, dt / n, 0);
    }
    dirty_ = false;
    last_converged_ = nonconverged_ == noncon_before && !budget_hit_;
    return true;
  }

  // ---- read-out ----------------------------------------------------------------
  /// The number of nodes M + 1.
  std::size_t nodes() const noexcept { return M_ + 1; }
  /// The number of elements M.
  std::size_t elements() const noexcept { return M_; }
  /// The displacement u_j of node j (0..M), m.
  double u(std::size_t j) const noexcept {
    return lazy_ != 0.0 ? u_[j] + lazy_ * z_[j] : u_[j];
  }
  /// Tension of element e (1..M) after the last step.
  double tension(std::size_t e) const noexcept {
    return T0b_[e] + (1.0 - relax_) * kb_[e] * (u(e) - u(e - 1)) + sigma_[e];
  }
  /// Stick/slip state of node j: 0 stuck, +1/-1 slipping toward node M / node 0
  /// (driven and load nodes report 0; frictionless sheath nodes report 0 too).
  int state(std::size_t j) const noexcept { return h_[j] > 0.0 ? sig_[j] : 0; }
  /// The kind of node j.
  NodeKind kind(std::size_t j) const noexcept { return kind_[j]; }
  /// The lumped curve angle of node j, rad.
  double node_angle(std::size_t j) const noexcept { return dtheta_[j]; }
  /// The driven input x of the last step, m (after clamping).
  double input() const noexcept { return x_; }
  /// Smallest element tension (O(M)).
  double min_tension() const noexcept {
    double mn = std::numeric_limits<double>::infinity();
    for (std::size_t e = 1; e <= M_; ++e) mn = std::min(mn, tension(e));
    return mn;
  }
  /// True when the last step left an element tension at or below zero (see set_slack_strict()).
  bool slack() const noexcept { return slack_; }
  /// Slack test used by slack(): min tension <= 0 (strict = false) or < 0.
  void set_slack_strict(bool strict) noexcept { slack_strict_ = strict; }
  /// Steps that reached the work bound since reset().
  long nonconverged() const noexcept { return nonconverged_; }
  /// The last step: its input held (non-finite), clamped, not converged, slack.
  Status status() const noexcept {
    Status s = Status::ok;
    if (input_held_) s |= Status::held_nonfinite_input;
    if (input_clamped_) s |= Status::input_clamped;
    if (!last_converged_) s |= Status::not_converged;
    if (slack_) s |= Status::slack;
    return s;
  }
  /// status() for a plant whose last step() returned `updated`: a step that left the state
  /// unchanged is flagged held when its input was not finite, else not_converged.
  Status status_after(bool updated) const noexcept {
    const Status s = status();
    if (updated || has(s, Status::held_nonfinite_input)) return s;
    return s | Status::not_converged;
  }
  /// The last step's input was beyond +-kMaxInput and was clamped to it.
  bool input_clamped() const noexcept { return input_clamped_; }
  /// Every increment of the last step converged (false: the best bounded iterate was kept).
  bool last_converged() const noexcept { return last_converged_; }
  /// Solves (and shortcut updates) the last step made; never more than max_solves().
  int last_solves() const noexcept { return last_solves_; }
  /// The hard work bound of one step (see the header): max_substeps + 2 (max_iterations + E).
  long long max_solves() const noexcept {
    return opt_.max_substeps + 2LL * (opt_.max_iterations + extra_iterations());
  }
  /// The friction coefficient of the first sheath node.
  double friction() const noexcept { return M_ >= 1 ? mu_[1] : 0.0; }
  /// The friction coefficient of node j.
  double node_friction(std::size_t j) const noexcept { return mu_[j]; }
  /// True when a step depends on dt (dampers, masses, viscosity, relaxation).
  bool time_dependent() const noexcept { return has_damper_; }
  /// The numerical options.
  const ChainOptions& options() const noexcept { return opt_; }

 private:
  // One increment to xt with halving on failure. With no solve left it changes nothing (the
  // step stops at its last finished increment).
  void sub_increment(double xt, double dt, int depth) noexcept {
    if (!solves_left()) {
      if (!budget_hit_) ++nonconverged_;
      budget_hit_ = true;
      return;
    }
    meet_halfway_ = depth == 0 && !has_damper_;  // retries march as before (see meeting_point)
    const bool first_ok = try_increment(xt, dt, opt_.max_iterations, false);
    meet_halfway_ = false;
    if (first_ok) {
      commit(xt, true, dt);
      return;
    }
    // A slack iterate (a tension <= 0) lies outside the model: no smaller increment makes it
    // valid (with a damper, halving only stiffens it), so go straight to the last resort.
    if (depth < opt_.max_halvings && xt != x_ && solves_left() && !(min_of_tensions() <= 0.0)) {
      const double xm = 0.5 * (x_ + xt);
      sub_increment(xm, 0.5 * dt, depth + 1);
      sub_increment(xt, 0.5 * dt, depth + 1);
      return;
    }
    // the last resort goes on from the last iterate; with no solve left that iterate is kept
    const bool ok = solves_left() && try_increment(xt, dt, extra_iterations(), true);
    if (!ok) ++nonconverged_;
    fact_valid_ = fact_valid_ && ok;
    for (std::size_t j = 0; j <= M_; ++j)
      if (!std::isfinite(w_[j])) {
        fact_valid_ = false;
        consistent_ = false;
        fast_ok_ = false;
        return;  // keep the previous state
      }
    commit(xt, ok, dt);
  }

  int extra_iterations() const noexcept {
    return opt_.extra_iterations >= 0 ? opt_.extra_iterations : static_cast<int>(2 * M_ + 50);
  }
  bool solves_left() const noexcept { return last_solves_ < max_solves(); }

  void commit(double xt, bool converged, double dt) noexcept {
    consistent_ = converged && fact_valid_;
    // T_ already holds the tensions of the accepted solution (w_, soon u_).
    const double mn = has_damper_ ? commit_rates(dt) : min_of_tensions();
    u_.swap(w_);
    sig_.swap(sw_);
    x_ = xt;
    xref_ = xt;
    lazy_ = 0.0;
    slack_ = slack_strict_ ? (mn < 0.0) : (mn <= 0.0);
    fast_ok_ = false;
    if (consistent_ && !has_damper_ && mn > 0.0 && opt_.fast_path) compute_interval();
  }

  double min_of_tensions() const noexcept {
    double mn = std::numeric_limits<double>::infinity();
    for (std::size_t e = 1; e <= M_; ++e) mn = std::min(mn, T_[e]);
    return mn;
  }

  // Velocities of massive load nodes and the Maxwell forces of the accepted
  // solution w_ (tensions in T_), before it becomes the committed state; in
  // the same pass, the effective elements of a next step as long as this one
  // (a fixed-rate loop then skips refresh_elements). Returns the least tension.
  double commit_rates(double dt) noexcept {
    const double inv_dt = dt > 0.0 ? 1.0 / dt : 0.0;
    if (has_mass_)
      for (std::size_t j = 0; j <= M_; ++j)
        if (ml_[j] > 0.0) vel_[j] = (w_[j] - u_[j]) * inv_dt;
    if (!(relax_ > 0.0)) return min_of_tensions();
    const double beta = beta_of(dt);
    const double keep = 1.0 - relax_ + relax_ * beta;
    double mn = std::numeric_limits<double>::infinity();
    for (std::size_t e = 1; e <= M_; ++e) {
      const double eps = w_[e] - w_[e - 1];
      const double s = T_[e] - T0b_[e] - (1.0 - relax_) * kb_[e] * eps;
      sigma_[e] = s;
      k_[e] = kb_[e] * keep;
      T0_[e] = T0b_[e] + beta * (s - relax_ * kb_[e] * eps);
      mn = std::min(mn, T_[e]);
    }
    elements_dt_ = dt;
    return mn;
  }

  double beta_of(double dt) const noexcept {
    return 1.0 / (1.0 + (dt > 0.0 ? dt / tau_ : 0.0));
  }

  // Effective element stiffness and reference tension of a step dt (SLS), from
  // the committed state; skipped when commit_rates already made them for dt.
  void refresh_elements(double dt) noexcept {
    if (!(relax_ > 0.0) || dt == elements_dt_) return;
    const double beta = beta_of(dt);
    const double keep = 1.0 - relax_ + relax_ * beta;
    for (std::size_t e = 1; e <= M_; ++e) {
      k_[e] = kb_[e] * keep;
      T0_[e] = T0b_[e] + beta * (sigma_[e] - relax_ * kb_[e] * (u_[e] - u_[e - 1]));
    }
    elements_dt_ = dt;
  }

  // Fold the lazy offset into u_ (before anything that needs u_ itself).
  void materialize() noexcept {
    if (lazy_ != 0.0) {
      for (std::size_t j = 0; j <= M_; ++j)
        u_[j] = kind_[j] == NodeKind::Driven ? x_ : u_[j] + lazy_ * z_[j];
      lazy_ = 0.0;
    }
    xref_ = x_;
    fast_ok_ = false;
  }

  // With the map fixed, u = u_ + X z (X = x - xref_) and every tension is
  // linear in X. The map stays valid (the plain active-set loop would accept
  // it on its first iteration) while every stuck node keeps |net| <= C,
  // every tension stays > 0 and no slipping node moves backwards; the first
  // two give an interval of X, the last the allowed directions of motion.
  // Conservative (no tolerances), so leaving the fast path early is harmless.
  void compute_interval() noexcept {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool ok = true, up = true, down = true;
    auto add = [&](double f0, double f1) {  // f0 + X f1 <= 0
      if (f0 > 0.0) ok = false;
      if (f1 > 0.0) hi = std::min(hi, -f0 / f1);
      else if (f1 < 0.0) lo = std::max(lo, -f0 / f1);
    };
    for (std::size_t e = 1; e <= M_; ++e) add(-T_[e], -k_[e] * (z_[e] - z_[e - 1]));
    for (std::size_t j = 0; j <= M_; ++j) {
      const double hj = h_[j];
      if (!(hj > 0.0)) continue;
      if (sig_[j] != 0) {
        const double zs = z_[j] * static_cast<double>(sig_[j]);
        if (zs > 0.0) down = false;
        if (zs < 0.0) up = false;
        continue;
      }
      const double dTl = j >= 1 ? k_[j] * (z_[j] - z_[j - 1]) : 0.0;
      const double dTr = j < M_ ? k_[j + 1] * (z_[j + 1] - z_[j]) : 0.0;
      const double net0 = T_[j + 1] - T_[j], dnet = dTr - dTl;
      const double sum0 = T_[j + 1] + T_[j], dsum = dTr + dTl;
      add(net0 - hj * sum0, dnet - hj * dsum);
      add(-net0 - hj * sum0, -dnet - hj * dsum);
    }
    fast_ok_ = ok && lo <= 0.0 && hi >= 0.0;
    xlo_ = xref_ + lo;
    xhi_ = xref_ + hi;
    up_ = up;
    down_ = down;
  }

  void compute_tensions(const double* u) noexcept {
    T_[0] = 0.0;
    T_[M_ + 1] = 0.0;
    for (std::size_t e = 1; e <= M_; ++e) T_[e] = T0_[e] + k_[e] * (u[e] - u[e - 1]);
  }

  // Active-set loop from the committed state toward input xt. Leaves the
  // solution in w_, its map in sw_ and its tensions in T_.
  //
  // Shortcut (exact up to rounding): when the committed state u_ was solved
  // with the current matrix (same stick/slip map and angles, no damper), the
  // right-hand side changes only in the driven rows, by dx, so the new solution
  // is u_ + dx z with z = A^{-1} e_driven, cached by the last full solve.
  bool try_increment(double xt, double dt, int max_it, bool from_work) noexcept {
    if (!from_work) std::copy(sig_.begin(), sig_.end(), sw_.begin());
    const double inv_dt = dt > 0.0 ? 1.0 / dt : 0.0;
    const bool damped = has_damper_;  // the matrix then depends on dt
    refresh_elements(dt);
    for (int it = 0; it < max_it && solves_left(); ++it) {
      bool solved = false;  // the elimination factors belong to this iterate
      if (it == 0 && !from_work && fact_valid_ && consistent_ && !damped && opt_.fast_path) {
        const double dx = xt - x_;
        for (std::size_t j = 0; j <= M_; ++j) w_[j] = u_[j] + dx * z_[j];
        for (std::size_t j = 0; j <= M_; ++j)
          if (kind_[j] == NodeKind::Driven) w_[j] = xt;
      } else {
        solve(xt, inv_dt);
        solved = true;
      }
      ++last_solves_;
      if (tensions_and_violations() == 0) return solution_finite();
      // after one plain flip the front is known to be moving: march it (the rows
      // include dampers and viscosity, and the final solve and check decide)
      if (it > 0 && solved && opt_.fast_path && solves_left() && march(xt, inv_dt) > 0) {
        solve(xt, inv_dt);  // one full solve for all the front flips
        ++last_solves_;
        if (tensions_and_violations() == 0) return solution_finite();
      }
      flip_violations();
      fact_valid_ = false;
    }
    return false;
  }

  // Row j of the tridiagonal system for the map sw_: l w_{j-1} + b w_j + c w_{j+1} = d.
  // Returns false for an identity row (driven or stuck node: w_j = d).
#if defined(__GNUC__)
  __attribute__((always_inline))
#endif
  bool row(std::size_t j, double xt, double inv_dt, double& l, double& b, double& c,
           double& d) const noexcept {
    const NodeKind kd = kind_[j];
    if (kd == NodeKind::Driven) {
      d = xt;
      return false;
    }
    if (kd == NodeKind::Sheath) {
      const double hj = h_[j];
      if (hj > 0.0 && sw_[j] == 0) {
        d = u_[j];
        return false;
      }
      const double hs = hj * static_cast<double>(sw_[j]);
      const double p = 1.0 - hs, q = 1.0 + hs;
      const double cv = cv_[j] * inv_dt;  // viscous sheath friction of a moving node
      l = q * k_[j];
      c = p * k_[j + 1];
      b = -(c + l) - cv;
      d = -(p * T0_[j + 1] - q * T0_[j]) - cv * u_[j];
      return true;
    }
    const double cd = cl_[j] * inv_dt;  // Load
    const double mi = ml_[j] * inv_dt * inv_dt;
    l = k_[j];
    c = k_[j + 1];
    b = -(c + l + kl_[j] + cd + mi);
    d = -(T0_[j + 1] - T0_[j]) + F0_[j] - (cd + mi) * u_[j] - ml_[j] * inv_dt * vel_[j];
    return true;
  }

  // Assemble and solve the tridiagonal system (Thomas algorithm) into w_, and
  // the same matrix against the driven-row indicator into z_.
  void solve(double xt, double inv_dt) noexcept {
    if (has_damper_) {
      solve_w(xt, inv_dt);
      return;
    }
    double cprev = 0.0, dprev = 0.0, zprev = 0.0;
    for (std::size_t j = 0; j <= M_; ++j) {
      double l = 0.0, b = 0.0, c = 0.0, d = 0.0;
      if (!row(j, xt, inv_dt, l, b, c, d)) {
        const double zj = kind_[j] == NodeKind::Driven ? 1.0 : 0.0;
        cp_[j] = 0.0;
        dp_[j] = d;
        zp_[j] = zj;
        cprev = 0.0;
        dprev = d;
        zprev = zj;
        continue;
      }
      const double inv = 1.0 / (b - l * cprev);
      cprev = c * inv;
      dprev = (d - l * dprev) * inv;
      zprev = -l * zprev * inv;
      cp_[j] = cprev;
      dp_[j] = dprev;
      zp_[j] = zprev;
    }
    double next = dp_[M_], znext = zp_[M_];
    w_[M_] = next;
    z_[M_] = znext;
    for (std::size_t j = M_; j-- > 0;) {
      next = dp_[j] - cp_[j] * next;
      znext = zp_[j] - cp_[j] * znext;
      w_[j] = next;
      z_[j] = znext;
    }
    fact_valid_ = true;
  }

  // solve() without z_, for time-dependent chains (their shortcuts never use z_).
  // Their matrix changes only with the stick/slip map, the angles or dt, while
  // the right-hand side changes every step; so the pivots are kept (lv_, iv_)
  // and, while the map and dt stay, a step needs no division (a serial chain of
  // divisions is most of a factorisation's time).
  void solve_w(double xt, double inv_dt) noexcept {
    double cprev = 0.0, dprev = 0.0;
    if (tfact_valid_ && inv_dt == tfact_inv_dt_ && std::equal(sw_.begin(), sw_.end(), fmap_.begin())) {
      for (std::size_t j = 0; j <= M_; ++j) {
        double l = 0.0, b = 0.0, c = 0.0, d = 0.0;
        row(j, xt, inv_dt, l, b, c, d);
        dprev = (d - lv_[j] * dprev) * iv_[j];
        dp_[j] = dprev;
      }
    } else {
      for (std::size_t j = 0; j <= M_; ++j) {
        double l = 0.0, b = 0.0, c = 0.0, d = 0.0;
        if (!row(j, xt, inv_dt, l, b, c, d)) {
          cp_[j] = 0.0;
          dp_[j] = d;
          lv_[j] = 0.0;
          iv_[j] = 1.0;
          cprev = 0.0;
          dprev = d;
          continue;
        }
        const double inv = 1.0 / (b - l * cprev);
        cprev = c * inv;
        dprev = (d - l * dprev) * inv;
        cp_[j] = cprev;
        dp_[j] = dprev;
        lv_[j] = l;
        iv_[j] = inv;
      }
      std::copy(sw_.begin(), sw_.end(), fmap_.begin());
      tfact_valid_ = true;
      tfact_inv_dt_ = inv_dt;
    }
    double next = dp_[M_];
    w_[M_] = next;
    for (std::size_t j = M_; j-- > 0;) {
      next = dp_[j] - cp_[j] * next;
      w_[j] = next;
    }
    fact_valid_ = false;  // z_ was not computed
  }

  bool stuck_violates(std::size_t j, double Tl, double Tr) const noexcept {
    const double hj = h_[j];
    const double sum = Tl + Tr;
    const double cap = hj * (sum > 0.0 ? sum : 0.0);
    const double tol = 1e-9 * (std::fabs(Tl) + std::fabs(Tr)) + 1e-12;
    return kind_[j] == NodeKind::Sheath && hj > 0.0 && sw_[j] == 0 &&
           std::fabs(Tr - Tl) > cap + tol;
  }

  // Slip fronts. After a reversal (or a route change) the slip zone grows from a driven end
  // one node per active-set iteration, each a full O(M) solve: O(M^2) per reversal. A front
  // node is a stuck node that violates its capacity while the zone beside it slips; flipping
  // it changes only its own row, so with the elimination factors of that side the next
  // node's test costs O(1). march() makes those flips (what the plain loop would do, one
  // front node per iteration) and leaves the rest to the normal loop: the final solve and
  // check decide, so the answer is the plain algorithm's. Returns the number of flips.
  int march(double xt, double inv_dt) noexcept {
    int flips = 0;
    for (std::size_t g = 1; g < M_; ++g) {  // fronts moving toward node M
      if (!stuck_violates(g, T_[g], T_[g + 1])) continue;
      double l, b, c, d;
      if (!row(g - 1, xt, inv_dt, l, b, c, d)) continue;  // the zone on the left must slip
      double cprev = cp_[g - 1], dprev = dp_[g - 1];
      const std::size_t stop = meet_halfway_ ? meeting_point(g, xt, inv_dt) : M_;
      std::size_t j = g;
      while (j < M_ && j <= stop && stuck_violates(j, T_[j], T_[j + 1])) {
        double lj, bj, cj, dj;
        if (row(j + 1, xt, inv_dt, lj, bj, cj, dj)) break;  // next node not stuck: stop
        sw_[j] = T_[j + 1] > T_[j] ? 1 : -1;
        ++flips;
        row(j, xt, inv_dt, l, b, c, d);
        const double inv = 1.0 / (b - l * cprev);
        cprev = c * inv;
        dprev = (d - l * dprev) * inv;
        const double wn = u_[j + 1];  // stuck neighbour
        const double wj = dprev - cprev * wn;
        T_[j + 1] = T0_[j + 1] + k_[j + 1] * (wn - wj);
        ++j;
      }
      g = j;
    }
    for (std::size_t g = M_ - 1; g >= 1; --g) {  // fronts moving toward node 0
      if (!stuck_violates(g, T_[g], T_[g + 1])) continue;
      double l, b, c, d;
      if (!row(g + 1, xt, inv_dt, l, b, c, d)) continue;  // the zone on the right must slip
      // right-to-left factors of that zone: w_j = dq - cq w_{j-1}
      std::size_t end = g + 1;
      while (end < M_ && row(end + 1, xt, inv_dt, l, b, c, d)) ++end;
      double cq = 0.0, dq = 0.0;
      row(end + 1 <= M_ ? end + 1 : end, xt, inv_dt, l, b, c, d);
      dq = end + 1 <= M_ ? d : 0.0;  // identity row beyond the zone (or none)
      for (std::size_t i = end; i > g; --i) {
        row(i, xt, inv_dt, l, b, c, d);
        const double inv = 1.0 / (b - c * cq);
        const double dn = (d - c * dq) * inv;
        cq = l * inv;
        dq = dn;
      }
      std::size_t j = g;
      while (j >= 1 && stuck_violates(j, T_[j], T_[j + 1])) {
        double lj, bj, cj, dj;
        if (row(j - 1, xt, inv_dt, lj, bj, cj, dj)) break;  // next node not stuck: stop
        sw_[j] = T_[j + 1] > T_[j] ? 1 : -1;
        ++flips;
        row(j, xt, inv_dt, l, b, c, d);
        const double inv = 1.0 / (b - c * cq);
        dq = (d - c * dq) * inv;
        cq = l * inv;
        const double wn = u_[j - 1];  // stuck neighbour
        const double wj = dq - cq * wn;
        T_[j] = T0_[j] + k_[j] * (wj - wn);
        --j;
      }
      g = j + 1 < g ? j + 1 : g;
      if (j == 0) break;
    }
    return flips;
  }

  // The last node a front at g moving toward node M may take: the stuck run it enters may end
  // at a front moving the other way (a slipping zone beyond it and its end node violating),
  // which the second loop of march() would advance through the same run. The plain loop moves
  // both one node per iteration, so they meet halfway; a front that took the whole run left
  // the other blocked at its first node, and the loop then retreated the run a node per two
  // solves. Used on the first attempt of an increment of a chain without dampers (with a
  // damped load it put more steps at the work bound); halvings and the last resort march as
  // before. Adversarial set, N = 400, spring load: solves a step at p99 401 -> 58.
  std::size_t meeting_point(std::size_t g, double xt, double inv_dt) const noexcept {
    std::size_t e = g;
    double l, b, c, d;
    while (e + 1 < M_ && kind_[e + 1] == NodeKind::Sheath && !row(e + 1, xt, inv_dt, l, b, c, d))
      ++e;
    const bool opposed = e + 1 < M_ && kind_[e + 1] == NodeKind::Sheath && sw_[e + 1] != 0 &&
                         h_[e + 1] > 0.0 && stuck_violates(e, T_[e], T_[e + 1]);
    return opposed ? g + (e - g) / 2 : M_;
  }

  // Comparisons with NaN are false, so a NaN solution has no violations: it must not
  // count as converged (nor be committed).
  bool solution_finite() const noexcept {
    double sum = 0.0;
    for (std::size_t j = 0; j <= M_; ++j) sum += w_[j] * 0.0;  // NaN for any inf or NaN
    return sum == 0.0;
  }

  // The tensions of w_ (into T_) and the number of nodes whose solution violates the
  // stick/slip map, in one branch-free pass (the common case: none; flip_violations() flips
  // them). Only sheath nodes have h_ > 0.
  int tensions_and_violations() noexcept {
    T_[0] = 0.0;
    T_[M_ + 1] = 0.0;
    int viol = 0;
    for (std::size_t e = 1; e <= M_; ++e) {
      T_[e] = T0_[e] + k_[e] * (w_[e] - w_[e - 1]);
      viol += violates(e - 1) ? 1 : 0;
    }
    return viol + (violates(M_) ? 1 : 0);
  }

  int flip_violations() noexcept {
    int flips = 0;
    for (std::size_t j = 0; j <= M_; ++j) {
      if (!violates(j)) continue;
      if (sw_[j] == 0) sw_[j] = T_[j + 1] > T_[j] ? 1 : -1;
      else sw_[j] = 0;
      ++flips;
    }
    return flips;
  }

  bool violates(std::size_t j) const noexcept {
    const double hj = h_[j];
    const double Tl = T_[j], Tr = T_[j + 1];
    const double s = static_cast<double>(sw_[j]);
    const double net = Tr - Tl;
    const double sum = Tl + Tr;
    const double cap = hj * (sum > 0.0 ? sum : 0.0);
    const double tol = 1e-9 * (std::fabs(Tl) + std::fabs(Tr)) + 1e-12;
    const double du = w_[j] - u_[j];
    const double eps = 1e-13 * (std::fabs(u_[j]) + std::fabs(w_[j])) + 1e-18;
    const bool stuck_v = (s == 0.0) & (std::fabs(net) > cap + tol);
    const bool slip_v = (s != 0.0) & (du * s < -eps);
    return (hj > 0.0) & (stuck_v | slip_v);
  }

  std::size_t M_ = 0;
  std::vector<NodeKind> kind_;
  std::vector<double> h_, dtheta_, mu_, cv_;
  std::vector<double> k_, T0_;     // effective element stiffness/reference tension (solver)
  std::vector<double> kb_, T0b_;   // the elements' own (instantaneous) values
  std::vector<double> sigma_;      // Maxwell-arm forces of the SLS elements
  std::vector<double> F0_, kl_, cl_, ml_, vel_;
  std::vector<double> u_, w_;
  std::vector<signed char> sig_, sw_;
  std::vector<double> cp_, dp_, zp_, z_, T_;
  std::vector<double> lv_, iv_;        // kept pivots of a time-dependent chain (solve_w)
  std::vector<signed char> fmap_;      // the map they belong to
  bool tfact_valid_ = false;
  double tfact_inv_dt_ = 0.0;
  ChainOptions opt_;
  double relax_ = 0.0, tau_ = 1.0;
  double elements_dt_ = 0.0;  // the step k_/T0_ were made for (SLS)
  double x_ = 0.0;
  long nonconverged_ = 0;
  int last_solves_ = 0;
  bool input_clamped_ = false;
  bool input_held_ = false;
  bool last_converged_ = true;
  bool budget_hit_ = false;  // the last step reached max_solves()
  bool meet_halfway_ = false;  // march() stops opposed fronts halfway (first attempts only)
  bool has_damper_ = false;  // any time-dependent effect (damper, mass, viscosity, SLS)
  bool has_mass_ = false;
  bool initialised_ = false;
  bool dirty_ = true;
  bool slack_ = false;
  bool slack_strict_ = false;
  bool fast_ok_ = false;     // [xlo_, xhi_] and up_/down_ describe the committed map
  bool up_ = false, down_ = false;
  double xlo_ = 0.0, xhi_ = 0.0, xref_ = 0.0, lazy_ = 0.0;
  bool fact_valid_ = false;  // cp_/z_ belong to the matrix of the current map sw_
  bool consistent_ = false;  // u_ solves that matrix (committed from a converged solve)
};

}  // namespace tendonsheath
