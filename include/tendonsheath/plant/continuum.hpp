// A pull-pull pair driving one constant-curvature continuum segment (seed 001,
// spec C.5). Li and Rahn: the tendon pull that holds the bending angle
// theta_b = kappa l is F = kappa EI / r_t, and the tendon stroke is
// x_out = r_t theta_b. The segment is therefore a linear spring on the stroke,
// k = EI / (r_t^2 l), i.e. a pull-pull plant whose "distal pulley" has radius
// r_t and a torsional stiffness EI / l; its output angle is theta_b.
#pragma once

#include "../route.hpp"
#include "../validate.hpp"
#include "pull_pull.hpp"

namespace tendonsheath {

struct ContinuumParams {
  double friction = 0.1;          ///< mu
  double stiffness = 2.4e4;       ///< EA of each tendon, N
  double pretension = 10.0;       ///< T0, N
  double proximal_radius = 5e-3;  ///< r_p, m
  double bending_stiffness = 4e-4;  ///< EI of the backbone, N m^2
  double tendon_offset = 2e-3;      ///< r_t, m
  double backbone_length = 0.03;    ///< l, m
  int elements = 100;
  /// effects beyond the quasi-static pair (see PullPullParams)
  double distal_inertia = 0.0;     ///< kg m^2 of the segment about its bending (at theta_b)
  double distal_damping = 0.0;     ///< N m s/rad
  double sheath_viscosity = 0.0;   ///< N s/m^2
  double relaxation_fraction = 0.0;
  double relaxation_time = 1.0;
  double friction2 = -1.0;
  double stiffness2 = -1.0;
  ChainOptions options;
};

inline PullPullParams continuum_to_pull_pull(const ContinuumParams& c) {
  const char* w = "ContinuumPlant";
  require_positive(c.bending_stiffness, w, "bending_stiffness");
  require_positive(c.tendon_offset, w, "tendon_offset");
  require_positive(c.backbone_length, w, "backbone_length");
  PullPullParams p;
  p.friction = c.friction;
  p.stiffness = c.stiffness;
  p.pretension = c.pretension;
  p.proximal_radius = c.proximal_radius;
  p.distal_radius = c.tendon_offset;
  p.elements = c.elements;
  p.load_stiffness = c.bending_stiffness / c.backbone_length;
  p.distal_inertia = c.distal_inertia;
  p.distal_damping = c.distal_damping;
  p.sheath_viscosity = c.sheath_viscosity;
  p.relaxation_fraction = c.relaxation_fraction;
  p.relaxation_time = c.relaxation_time;
  p.friction2 = c.friction2;
  p.stiffness2 = c.stiffness2;
  p.options = c.options;
  return p;
}

class ContinuumPlant : public PullPullPlant {
 public:
  /// The parameter struct its constructor takes.
  using Params = ContinuumParams;

  ContinuumPlant(const ContinuumParams& c, const Route& r1, const Route& r2)
      : PullPullPlant(continuum_to_pull_pull(c), r1, r2), c_(c) {}
  ContinuumPlant(const ContinuumParams& c, const Route& r) : ContinuumPlant(c, r, r) {}

  /// Params is ContinuumParams: params() returns them (the pull-pull pair they map to is
  /// pull_pull_params()).
  const ContinuumParams& params() const noexcept { return c_; }
  const ContinuumParams& continuum_params() const noexcept { return c_; }
  const PullPullParams& pull_pull_params() const noexcept { return PullPullPlant::params(); }
  /// Bending angle theta_b (rad), the same as output().
  double bending_angle() const noexcept { return output(); }
  /// Li and Rahn tendon force F = kappa EI / r_t for the current bending angle.
  double tendon_force() const noexcept {
    return output() / c_.backbone_length * c_.bending_stiffness / c_.tendon_offset;
  }

 private:
  ContinuumParams c_;
};

}  // namespace tendonsheath
