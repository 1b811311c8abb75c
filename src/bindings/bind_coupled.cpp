// The feedforward of coupled joints (CoupledFeedforward): one ModelInverse per joint and the
// coupling matrix; a whole trajectory's commands in one C++ loop.
#include <nanobind/stl/vector.h>

#include <string>
#include <tendonsheath/compensators/coupled_feedforward.hpp>
#include <vector>

#include "bindings.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

namespace {

// The desired angles of one cycle: exactly one per joint.
void check_joints(std::size_t got, std::size_t joints, const char* what) {
  if (got != joints)
    throw std::invalid_argument(std::string("CoupledFeedforward: ") + what + " has " +
                                std::to_string(got) + " columns, one per joint (" +
                                std::to_string(joints) + ") needed");
}

OutArray step(ts::CoupledFeedforward& self, InArray y_d, double dt) {
  check_joints(y_d.shape(0), self.joints(), "y_d");
  auto [out, u] = new_array(self.joints());
  self.step(y_d.data(), u, dt);
  return out;
}

// A copy over a whole trajectory (rows: samples, columns: joints), from the initial state:
// (commands, each cycle's Status flags).
nb::tuple command(const ts::CoupledFeedforward& self, InArray t, InMatrix y) {
  const std::size_t n = y.shape(0), joints = self.joints();
  check_joints(y.shape(1), joints, "y_desired");
  check_lengths(n, t.shape(0), "t", "CoupledFeedforward");
  for (std::size_t j = 0; j < joints; ++j) {
    std::vector<double> column(n);
    for (std::size_t k = 0; k < n; ++k) column[k] = y.data()[k * joints + j];
    ts::check_series(t.data(), column.data(), n, "CoupledFeedforward");
  }
  auto [out, u] = new_matrix(n, joints);
  auto [flags, f] = new_bytes(n);
  ts::CoupledFeedforward ff = self;
  ff.reset();
  const double* tp = t.data();
  const double* yp = y.data();
  {
    nb::gil_scoped_release release;
    for (std::size_t k = 0; k < n; ++k) {
      ff.step(yp + k * joints, u + k * joints, k == 0 ? 0.0 : tp[k] - tp[k - 1]);
      f[k] = static_cast<std::uint8_t>(ff.status());
    }
  }
  return nb::make_tuple(out, flags);
}

}  // namespace

void bind_coupled(nb::module_& m) {
  using C = ts::CoupledFeedforward;
  bind_copy(nb::class_<C>(m, "CoupledFeedforward"))
      .def(nb::init<std::vector<ts::ModelInverse>, std::vector<double>>(), "joints"_a,
           "coupling"_a)
      .def("joints", &C::joints)
      .def("coupling", &C::coupling, "i"_a, "j"_a)
      .def("reset", &C::reset)
      .def("step", &step, "y_d"_a, "dt"_a)
      .def("status", [](const C& c) { return static_cast<unsigned>(c.status()); })
      .def("targets", &C::targets)
      .def("command", &command, "t"_a, "y_d"_a);
}

}  // namespace tsbind
