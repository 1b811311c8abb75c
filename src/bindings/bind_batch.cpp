// Batched population evaluation for identification: one call per generation,
// spread over the machine's cores in C++ with the GIL released.
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <memory>
#include <optional>
#include <string>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

#include "../batch/batch.hpp"
#include "bindings.hpp"

namespace tsbind {
namespace ts = tendonsheath;
namespace tb = tendonsheath::batch;
using namespace nb::literals;

using InMatrix = nb::ndarray<const double, nb::ndim<2>, nb::c_contig, nb::device::cpu>;

// Owns copies of the recordings (concatenated) so that repeated calls pass nothing. Routes
// (optional): route_counts[r] samples of recording r's route (0: none), their arc lengths and
// angles concatenated in route_s and route_theta.
class RecordingSet {
 public:
  RecordingSet(std::optional<InArray> t, InArray x, std::optional<InArray> y,
               std::optional<InArray> theta, const std::vector<std::size_t>& lengths,
               const std::vector<std::size_t>& warmups, std::optional<InArray> x_fine = {},
               int fine = 0, std::optional<InArray> route_s = {},
               std::optional<InArray> route_theta = {},
               const std::vector<std::size_t>& route_counts = {}) {
    const std::size_t n = x.shape(0);
    std::size_t total = 0;
    for (std::size_t len : lengths) total += len;
    if (lengths.empty()) throw std::invalid_argument("RecordingSet: no recordings");
    if (total != n)
      throw std::invalid_argument("RecordingSet: lengths add up to " + std::to_string(total) +
                                  " but x has " + std::to_string(n) + " samples");
    if (warmups.size() != lengths.size())
      throw std::invalid_argument("RecordingSet: one warm-up per recording is needed");
    auto copy = [n](const std::optional<InArray>& a, std::vector<double>& dst, const char* name) {
      if (!a) return;
      if (a->shape(0) != n)
        throw std::invalid_argument(std::string("RecordingSet: ") + name + " has " +
                                    std::to_string(a->shape(0)) + " samples, x has " +
                                    std::to_string(n));
      dst.assign(a->data(), a->data() + n);
    };
    x_.assign(x.data(), x.data() + n);
    copy(t, t_, "t");
    copy(y, y_, "y");
    copy(theta, theta_, "curve_angle");
    if (x_fine) {
      if (fine < 1 || x_fine->shape(0) != n * static_cast<std::size_t>(fine))
        throw std::invalid_argument("RecordingSet: x_fine must have fine * " + std::to_string(n) +
                                    " values (fine >= 1)");
      x_fine_.assign(x_fine->data(), x_fine->data() + x_fine->shape(0));
    }
    std::size_t off = 0;
    for (std::size_t r = 0; r < lengths.size(); ++r) {
      tb::Recording rec;
      rec.n = lengths[r];
      rec.warmup = warmups[r];
      rec.x = x_.data() + off;
      rec.t = t_.empty() ? nullptr : t_.data() + off;
      rec.y = y_.empty() ? nullptr : y_.data() + off;
      rec.theta = theta_.empty() ? nullptr : theta_.data() + off;
      if (!x_fine_.empty()) {
        rec.x_fine = x_fine_.data() + off * static_cast<std::size_t>(fine);
        rec.fine = fine;
      }
      recs_.push_back(rec);
      off += lengths[r];
    }
    attach_routes(route_s, route_theta, route_counts);
    tb::check_recordings(recs_, false, "RecordingSet");
  }
  const std::vector<tb::Recording>& recordings() const { return recs_; }
  std::size_t total() const { return x_.size(); }
  std::size_t count() const { return recs_.size(); }
  bool has_output() const { return !y_.empty(); }

 private:
  void attach_routes(const std::optional<InArray>& s, const std::optional<InArray>& theta,
                     const std::vector<std::size_t>& counts) {
    if (counts.empty()) return;
    if (counts.size() != recs_.size() || !s || !theta || s->shape(0) != theta->shape(0))
      throw std::invalid_argument(
          "RecordingSet: routes need one count per recording and as many s as theta samples");
    std::size_t total = 0;
    for (std::size_t c : counts) total += c;
    if (total != s->shape(0))
      throw std::invalid_argument("RecordingSet: route counts add up to " +
                                  std::to_string(total) + " but route_s has " +
                                  std::to_string(s->shape(0)) + " samples");
    route_s_.assign(s->data(), s->data() + total);
    route_theta_.assign(theta->data(), theta->data() + total);
    std::size_t off = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
      if (counts[r] > 0) {
        recs_[r].route_s = route_s_.data() + off;
        recs_[r].route_theta = route_theta_.data() + off;
        recs_[r].route_n = counts[r];
      }
      off += counts[r];
    }
  }

  std::vector<double> t_, x_, y_, theta_, x_fine_, route_s_, route_theta_;
  std::vector<tb::Recording> recs_;
};

template <class Model>
void def_population(nb::module_& m, const std::string& name) {
  using Params = typename Model::Params;
  constexpr std::size_t np = Params::vector_size;
  auto check = [name](const InMatrix& params, const RecordingSet& rs) {
    const std::size_t want = rs.count() * np;
    if (params.shape(1) != want)
      throw std::invalid_argument(name + ": params must have " + std::to_string(want) +
                                  " columns (recordings x parameters), got " +
                                  std::to_string(params.shape(1)));
  };
  m.def(
      ("population_cost_" + name).c_str(),
      [check](const Params& base, InMatrix params, const RecordingSet& rs, unsigned workers) {
        check(params, rs);
        if (!rs.has_output()) throw std::invalid_argument("population_cost: no measured output");
        const std::size_t P = params.shape(0);
        auto [out, costs] = new_array(P);
        {
          nb::gil_scoped_release release;
          tb::population_cost<Model>(base, params.data(), P, rs.recordings(), costs, workers);
        }
        return out;
      },
      "base"_a, "params"_a, "recordings"_a, "workers"_a = 0,
      "Sum of squared simulation errors after warm-up for each row of params.");
  m.def(
      ("population_simulate_" + name).c_str(),
      [check](const Params& base, InMatrix params, const RecordingSet& rs, unsigned workers) {
        check(params, rs);
        const std::size_t P = params.shape(0);
        auto [out, y] = new_matrix(P, rs.total());
        {
          nb::gil_scoped_release release;
          tb::population_simulate<Model>(base, params.data(), P, rs.recordings(), y, workers);
        }
        return out;
      },
      "base"_a, "params"_a, "recordings"_a, "workers"_a = 0,
      "Simulated outputs (rows: members; columns: concatenated samples; NaN if invalid).");
}

template <class F>
void def_separable(nb::module_& m, const std::string& name) {
  using Params = typename F::Params;
  m.def(
      ("separable_cost_" + name).c_str(),
      [name](const Params& base, InMatrix v, const RecordingSet& rs, unsigned workers) {
        const std::size_t nv = tb::features_vector_size<F>(base);
        if (v.shape(1) != nv)
          throw std::invalid_argument(name + ": nonlinear parameters must have " +
                                      std::to_string(nv) + " columns, got " +
                                      std::to_string(v.shape(1)));
        if (!rs.has_output()) throw std::invalid_argument("separable_cost: no measured output");
        const std::size_t P = v.shape(0);
        auto [out, costs] = new_array(P);
        {
          nb::gil_scoped_release release;
          tb::separable_population_cost<F>(base, v.data(), P, rs.recordings(), costs, workers);
        }
        return out;
      },
      "base"_a, "nonlinear"_a, "recordings"_a, "workers"_a = 0,
      "Residual sum of squares after solving the linear coefficients, per row.");
  m.def(
      ("features_" + name).c_str(),
      [name](const Params& base, InArray v, const RecordingSet& rs) {
        const std::size_t nv = tb::features_vector_size<F>(base);
        if (v.shape(0) != nv)
          throw std::invalid_argument(name + ": nonlinear parameters must have " +
                                      std::to_string(nv) + " values, got " +
                                      std::to_string(v.shape(0)));
        Params p = base;
        F::assign(p, v.data());
        const std::size_t K = static_cast<std::size_t>(F::size(p));
        auto [out, data] = new_matrix(rs.total(), K);
        {
          nb::gil_scoped_release release;
          tb::features_matrix<F>(base, v.data(), rs.recordings(), data);
        }
        return out;
      },
      "base"_a, "nonlinear"_a, "recordings"_a,
      "Regressor matrix (samples x K) of the linear coefficients.");
}

void bind_batch(nb::module_& m) {
  nb::class_<RecordingSet>(m, "RecordingSet")
      .def(nb::init<std::optional<InArray>, InArray, std::optional<InArray>,
                    std::optional<InArray>, const std::vector<std::size_t>&,
                    const std::vector<std::size_t>&, std::optional<InArray>, int,
                    std::optional<InArray>, std::optional<InArray>,
                    const std::vector<std::size_t>&>(),
           "t"_a.none(), "x"_a, "y"_a.none(), "curve_angle"_a.none(), "lengths"_a, "warmups"_a,
           "x_fine"_a.none() = nb::none(), "fine"_a = 0, "route_s"_a.none() = nb::none(),
           "route_theta"_a.none() = nb::none(),
           "route_counts"_a = std::vector<std::size_t>{})
      .def_prop_ro("total", &RecordingSet::total)
      .def_prop_ro("count", &RecordingSet::count);
  m.def("default_workers", &tb::default_workers);
  m.def(
      "bouc_wen_paths",
      [](InArray y, InMatrix params, unsigned workers) {
        if (params.shape(1) != 3)
          throw std::invalid_argument("bouc_wen_paths: params must have 3 columns (G, D, nu)");
        const std::size_t n = y.shape(0), P = params.shape(0);
        auto [out, w] = new_matrix(P, n);
        const double* yp = y.data();
        const double* pp = params.data();
        {
          nb::gil_scoped_release release;
          tb::parallel_for(P, workers, [&](std::size_t p) {
            ts::bouc_wen_path(yp, n, pp[3 * p], pp[3 * p + 1], pp[3 * p + 2], w + p * n);
          });
        }
        return out;
      },
      "y"_a, "params"_a, "workers"_a = 0,
      "Bouc-Wen state w (z / alpha) along the displacement path y for each row (G, D, nu).");

  // every model of the list with a parameter vector (model_list.hpp)
  ts::for_each_type(ts::filter_list_t<ts::Models, ts::has_param_vector>{}, [&](auto tag) {
    using M = typename decltype(tag)::type;
    def_population<M>(m, ts::model_kind<M>());
  });

  def_separable<tb::BoucWenBacklashFeatures>(m, "BoucWenBacklash");
  def_separable<tb::BoucWenFeatures>(m, "BoucWen");
  def_separable<tb::PrandtlIshlinskiiFeatures>(m, "PrandtlIshlinskii");
  def_separable<tb::GeneralizedPrandtlIshlinskiiFeatures>(m, "GeneralizedPrandtlIshlinskii");
}

}  // namespace tsbind
