// The grey-box pull-pull plant of Python's models.PlantModel: a PullPullPlant reduced to the
// groups input/output data can identify, built exactly as PlantModel._make_plant builds it.
//
//   route: uniform, length 1 m, wrap angle 2 pi; friction = friction_angle / (2 pi)
//   L/EA = backlash / tanh(friction_angle / 2) at T0 = 1 N, r_p = r_d = 1 m
//   sheath_viscosity = viscous_time * EA (per metre; off when 0)
//   y = offset + gain * q_out
#pragma once

#include <cmath>

#include "../plant/pull_pull.hpp"
#include "../route.hpp"
#include "../status.hpp"
#include "../validate.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of PlantModel (validated by its constructor): Python's PlantModel groups.
struct PlantModelParams {
  double friction_angle = 1.0;  ///< mu Theta of the uniform route, rad, in (0, 20)
  double backlash = 0.1;        ///< half the dead zone e_b, input units, > 0
  double viscous_time = 0.0;    ///< c_v L^2 / EA, s, >= 0
  double gain = 1.0;            ///< output gain, finite and != 0
  double offset = 0.0;          ///< output offset, finite
  int elements = 10;            ///< the sheath's element count, >= 2
};

/// The parameter table of PlantModelParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<PlantModelParams> {
  static constexpr const char* owner = "PlantModel";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("friction_angle", &PlantModelParams::friction_angle, "rad", documented(0.0, false, 20.0, false),
            "mu Theta of the uniform route"),
      param("backlash", &PlantModelParams::backlash, "input", positive(),
            "half the dead zone e_b"),
      param("viscous_time", &PlantModelParams::viscous_time, "s", non_negative(),
            "c_v L^2 / EA"),
      param("gain", &PlantModelParams::gain, "output/input", documented(-kInf, false, kInf, false),
            "output gain, finite and != 0"),
      param("offset", &PlantModelParams::offset, "output", finite(),
            "output offset"),
      option("elements", &PlantModelParams::elements, "", at_least(2.0),
            "the sheath's element count"));
};

/// The wrap angle of PlantModel's internal uniform route, rad (only friction * wrap matters).
constexpr double kPlantModelWrap = 2.0 * 3.14159265358979323846;

/// @brief The grey-box pull-pull plant of Python's models.PlantModel: y = offset + gain * q_out of a
/// PullPullPlant built from the identified groups (see the file's comment).
///
/// The constructor allocates (the plant) and may throw; step() is the plant's: noexcept, no
/// allocation, bounded work. Copy-assigning one PlantModel to another of equal elements allocates
/// nothing (the plant's vectors keep their storage).
class PlantModel {
 public:
  /// The parameter struct its constructor takes.
  using Params = PlantModelParams;
  /// False: the viscous drag makes a step depend on dt.
  static constexpr bool rate_independent = false;

  /// @param p the groups; throws std::invalid_argument naming the first one out of range.
  explicit PlantModel(const Params& p) : p_(p), plant_(make(p)) {}

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// Back to rest; the next step takes its input as the rest state.
  void reset() noexcept { plant_.reset(); }
  /// @param x the input (pulley angle); a non-finite one leaves the state unchanged
  /// @param dt the time since the previous step, s
  /// @return offset + gain * q_out
  double step(double x, double dt = 0.0) noexcept {
    return p_.offset + p_.gain * plant_.step(x, dt);
  }
  /// The plant's last status (slack, not_converged, held).
  Status status() const noexcept { return plant_.status(); }
  /// The plant it runs.
  const PullPullPlant& plant() const noexcept { return plant_; }

 private:
  static PullPullPlant make(const Params& p) {
    const char* w = "PlantModel";
    validate_fields(p, w);  // each field's own bound, from ParamTable<PlantModelParams>
    // the open range and the excluded 0 the table's kinds do not hold
    require(std::isfinite(p.friction_angle) && p.friction_angle > 0.0 && p.friction_angle < 20.0,
            w, "friction_angle must be in (0, 20) (got ", p.friction_angle, ")");
    require(std::isfinite(p.gain) && p.gain != 0.0, w, "gain must be finite and not 0 (got ",
            p.gain, ")");
    // L / EA at T0 = 1 N and L = 1 m, per unit radius; the pulleys' radius r is a free scale
    // (e_b = T0 L tanh(a/2) / (EA r)), chosen so that the rest strain T0 / EA = compliance r
    // stays <= 1e-3, well inside the plant's small-strain bound (T0 / EA < 0.05).
    const double compliance = p.backlash / std::tanh(0.5 * p.friction_angle);
    const double radius = std::fmin(1.0, 1e-3 / compliance);
    const double stiffness = 1.0 / (compliance * radius);
    const double viscosity = p.viscous_time * stiffness;
    PullPullParams q;
    q.friction = p.friction_angle / kPlantModelWrap;
    q.stiffness = stiffness;
    q.pretension = 1.0;
    q.proximal_radius = radius;
    q.distal_radius = radius;
    q.elements = p.elements;
    if (viscosity > 0.0) q.sheath_viscosity = viscosity;
    q.options.fast_path = true;
    return PullPullPlant(q, Route::uniform(1.0, kPlantModelWrap));
  }

  Params p_;
  PullPullPlant plant_;
};

}  // namespace tendonsheath
