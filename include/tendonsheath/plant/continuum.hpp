// A pull-pull pair driving one constant-curvature continuum segment (Lau et al. 2015,
// spec C.5). Li and Rahn: the tendon pull that holds the bending angle
// theta_b = kappa l is F = kappa EI / r_t, and the tendon stroke is
// x_out = r_t theta_b. The segment is therefore a linear spring on the stroke,
// k = EI / (r_t^2 l), i.e. a pull-pull plant whose "distal pulley" has radius
// r_t and a torsional stiffness EI / l; its output angle is theta_b.
#pragma once

#include "../route.hpp"
#include "../validate.hpp"
#include "pull_pull.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of ContinuumPlant (validated by its constructor); SI units.
struct ContinuumParams {
  double friction = 0.1;          ///< mu
  double stiffness = 2.4e4;       ///< EA of each tendon, N
  double pretension = 10.0;       ///< T0, N
  double proximal_radius = 5e-3;  ///< r_p, m
  double bending_stiffness = 4e-4;  ///< EI of the backbone, N m^2
  double tendon_offset = 2e-3;      ///< r_t, m
  double backbone_length = 0.03;    ///< l, m
  int elements = 100;  ///< N per sheath, >= 2
  // effects beyond the quasi-static pair (see PullPullParams)
  double distal_inertia = 0.0;     ///< kg m^2 of the segment about its bending (at theta_b)
  double distal_damping = 0.0;     ///< N m s/rad
  double sheath_viscosity = 0.0;   ///< N s/m^2
  double relaxation_fraction = 0.0;  ///< r in [0, 1): share of EA in the Maxwell arm
  double relaxation_time = 1.0;  ///< tau, s
  double friction2 = -1.0;  ///< mu of sheath 2; -1: the same as friction
  double stiffness2 = -1.0;  ///< EA of tendon 2, N; -1: the same as stiffness
  ChainOptions options;  ///< numerical options of the friction chain (bound the work of a step)
};

/// The parameter table of ContinuumParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<ContinuumParams> {
  static constexpr const char* owner = "ContinuumPlant";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("friction", &ContinuumParams::friction, "", non_negative(),
            "mu, the sheaths' Coulomb friction coefficient"),
      param("stiffness", &ContinuumParams::stiffness, "N", positive(),
            "EA of each tendon"),
      param("pretension", &ContinuumParams::pretension, "N", positive(),
            "T0, pretension / EA < 0.05"),
      param("proximal_radius", &ContinuumParams::proximal_radius, "m", positive(),
            "r_p, the proximal pulley's radius"),
      param("bending_stiffness", &ContinuumParams::bending_stiffness, "N m^2", positive(),
            "EI of the backbone"),
      param("tendon_offset", &ContinuumParams::tendon_offset, "m", positive(),
            "r_t, the tendons' offset from the backbone"),
      param("backbone_length", &ContinuumParams::backbone_length, "m", positive(),
            "l, the bending segment's length"),
      param("elements", &ContinuumParams::elements, "", documented(2, true, 1000000, true),
            "N per sheath"),
      param("distal_inertia", &ContinuumParams::distal_inertia, "kg m^2", non_negative(),
            "of the segment about its bending (at theta_b)"),
      param("distal_damping", &ContinuumParams::distal_damping, "N m s/rad", non_negative(),
            "the segment's viscous damping"),
      param("sheath_viscosity", &ContinuumParams::sheath_viscosity, "N s/m^2", non_negative(),
            "viscous drag per metre of sheath"),
      param("relaxation_fraction", &ContinuumParams::relaxation_fraction, "", documented(0.0, true, 1.0, false),
            "SLS tendon: share of EA in the Maxwell arm"),
      param("relaxation_time", &ContinuumParams::relaxation_time, "s", positive(),
            "tau of the Maxwell arm"),
      param("friction2", &ContinuumParams::friction2, "", documented(0.0, true, kInf, false),
            "mu of sheath 2; -1: the same as friction"),
      param("stiffness2", &ContinuumParams::stiffness2, "N", documented(0.0, false, kInf, false),
            "EA of tendon 2; -1: the same as stiffness"),
      param("options", &ContinuumParams::options, "", any(),
            "ChainOptions: numerical options of the friction chain (bound the work of a step)"));
};

/// The pull-pull pair a continuum segment maps to: distal radius r_t and a torsional load stiffness
/// EI / l. Throws std::invalid_argument naming the first field out of its range (the table's
/// bounds, then elements and relaxation_fraction).
inline PullPullParams continuum_to_pull_pull(const ContinuumParams& c) {
  const char* w = "ContinuumPlant";
  validate_fields(c, w);  // each field's own bound, from ParamTable<ContinuumParams>
  detail::validate_elements(c.elements, w);
  detail::validate_relaxation_fraction(c.relaxation_fraction, w);
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

/// @brief A pull-pull pair driving one constant-curvature continuum segment (spec C.5): desired
/// motor angle in, bending angle theta_b out.
///
/// Li and Rahn: the tendon pull that holds theta_b = kappa l is F = kappa EI / r_t and the stroke
/// is x_out = r_t theta_b, so the segment is a linear spring k = EI / (r_t^2 l) on the stroke: a
/// PullPullPlant whose distal pulley has radius r_t and torsional stiffness EI / l.
class ContinuumPlant : public PullPullPlant {
 public:
  /// The parameter struct its constructor takes.
  using Params = ContinuumParams;

  /// @param c the parameters; throws std::invalid_argument naming the first one out of range
  /// @param r1 the route of sheath 1 (its tendon is pulled by a positive input)
  /// @param r2 the route of sheath 2
  ContinuumPlant(const ContinuumParams& c, const Route& r1, const Route& r2)
      : PullPullPlant(continuum_to_pull_pull(c), r1, r2), c_(c) {}
  /// Both sheaths along the same route.
  ContinuumPlant(const ContinuumParams& c, const Route& r) : ContinuumPlant(c, r, r) {}

  /// Params is ContinuumParams: params() returns them (the pull-pull pair they map to is
  /// pull_pull_params()).
  const ContinuumParams& params() const noexcept { return c_; }
  /// The parameters it was built with (the same as params()).
  const ContinuumParams& continuum_params() const noexcept { return c_; }
  /// The parameters of the pull-pull pair they map to.
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
