// 12: a compensator identified in Python, loaded from its JSON file and run in a 1 kHz loop.
//
//   example_12_load_and_run COMPENSATOR.json             1 kHz sine, self-check (ctest)
//   example_12_load_and_run COMPENSATOR.json TRAJ OUT    t,y_d lines in TRAJ -> commands in OUT
//                                                        (t,y_d,c lines: c is the motor encoder
//                                                        for an EncoderLoop, the tip angle for a
//                                                        TipLoop, else the curve angle set before
//                                                        each step; t,y_d,c,a lines: a is the
//                                                        curve angle set before each step)
//   example_12_load_and_run LOAD_COMPENSATED.json TRAJ OUT      t,y_d,load lines -> commands
//   example_12_load_and_run COUPLED_FEEDFORWARD.json TRAJ OUT   t,y_1,...,y_J lines -> lines of
//                                                        J commands (io/json_multi_input.hpp)
//
// The file comes from Python (examples/cpp/data/make_inverse_feedforward.py):
//   ts.compensate.InverseFeedforward(identified_model, ...).to_json("inverse_feedforward.json")
// Loading (tendonsheath/io/json.hpp, needs nlohmann/json) allocates, so it happens once before the
// loop; the loop's step() is the real-time core's. The try_ loaders return a tendonsheath::Result
// (the compensator, or the message naming the file and the bad key), so this example builds and
// runs the same with C++ exceptions or without them (g++ -fno-exceptions, as `make test-cpp`
// builds it too; docs/cpp-without-exceptions.md). The self-check drives the
// identified backlash with the commands and exits 0 when it tracks the sine to 2 % of its
// amplitude (measured: 0.16 %, the smoothing's rounding at each reversal; without the
// compensator the error is the dead band, ~10 %).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <tendonsheath/io/json_multi_input.hpp>
#include <vector>
#include <tendonsheath/tendonsheath.hpp>

namespace ts = tendonsheath;

namespace {

// f's member `key` (null when f is not an object or has no such key: the loaders say what is wrong)
const ts::io::json& member(const ts::io::json& f, const char* key) {
  static const ts::io::json none;
  return f.is_object() && f.contains(key) ? f[key] : none;
}

// a file that did not load: its message (naming the file and the key), exit status 2
int failed(const std::string& message) {
  std::fprintf(stderr, "%s\n", message.c_str());
  return 2;
}

int run_trajectory(ts::io::LoadedCompensator& ff, const char* in_path, const char* out_path) {
  std::FILE* in = std::fopen(in_path, "r");
  std::FILE* out = in ? std::fopen(out_path, "w") : nullptr;
  if (!out) {
    std::fprintf(stderr, "cannot open %s or %s\n", in_path, out_path);
    if (in) std::fclose(in);
    return 2;
  }
  double t = 0.0, y_d = 0.0, c = 0.0, a = 0.0, t_prev = 0.0;
  const bool looped = ff.kind() == "EncoderLoop" || ff.kind() == "TipLoop";
  char line[256];
  for (bool first = true; std::fgets(line, sizeof line, in) != nullptr; first = false) {
    const int fields = std::sscanf(line, "%lf,%lf,%lf,%lf", &t, &y_d, &c, &a);
    if (fields < 2) break;
    if (fields == 3 && !looped) ff.set_curve_angle(c);  // a compensator that follows the route
    if (fields == 4) ff.set_curve_angle(a);
    const double dt = first ? 0.0 : t - t_prev;  // as Python's command(): dt 0 on the first cycle
    std::fprintf(out, "%.17g\n", fields >= 3 && looped ? ff.step(y_d, c, dt) : ff.step(y_d, dt));
    t_prev = t;
  }
  std::fclose(in);
  std::fclose(out);
  return 0;
}

// TRAJ and OUT opened together (false, with a message, when either cannot be)
bool open_files(const char* in_path, const char* out_path, std::FILE*& in, std::FILE*& out) {
  in = std::fopen(in_path, "r");
  out = in ? std::fopen(out_path, "w") : nullptr;
  if (out) return true;
  std::fprintf(stderr, "cannot open %s or %s\n", in_path, out_path);
  if (in) std::fclose(in);
  return false;
}

// t,y_d,load lines: the load measured each cycle (a LoadCompensated file)
int run_loaded(ts::io::LoadCompensatedInverse& c, const char* in_path, const char* out_path) {
  std::FILE *in = nullptr, *out = nullptr;
  if (!open_files(in_path, out_path, in, out)) return 2;
  double t = 0.0, y_d = 0.0, load = 0.0, t_prev = 0.0;
  char line[256];
  for (bool first = true; std::fgets(line, sizeof line, in) != nullptr; first = false) {
    if (std::sscanf(line, "%lf,%lf,%lf", &t, &y_d, &load) != 3) break;
    std::fprintf(out, "%.17g\n", c.step(y_d, first ? 0.0 : t - t_prev, load));
    t_prev = t;
  }
  std::fclose(in);
  std::fclose(out);
  return 0;
}

// t,y_1,...,y_J lines: every joint's desired angle each cycle (a CoupledFeedforward file)
int run_coupled(ts::CoupledFeedforward& c, const char* in_path, const char* out_path) {
  std::FILE *in = nullptr, *out = nullptr;
  if (!open_files(in_path, out_path, in, out)) return 2;
  const std::size_t n = c.joints();
  std::vector<double> y_d(n), u(n);  // sized before the loop: step() allocates nothing
  double t_prev = 0.0;
  char line[4096];
  for (bool first = true; std::fgets(line, sizeof line, in) != nullptr; first = false) {
    char* p = line;
    const double t = std::strtod(p, &p);
    for (std::size_t j = 0; j < n && *p == ','; ++j) y_d[j] = std::strtod(p + 1, &p);
    c.step(y_d.data(), u.data(), first ? 0.0 : t - t_prev);
    for (std::size_t j = 0; j < n; ++j) std::fprintf(out, j + 1 < n ? "%.17g," : "%.17g\n", u[j]);
    t_prev = t;
  }
  std::fclose(in);
  std::fclose(out);
  return 0;
}

int self_check(ts::io::LoadedCompensator& ff, const std::string& path) {
  const double pi = 3.14159265358979323846, dt = 1e-3, amplitude = 1.0;
  if (ff.kind() != "InverseFeedforward") {
    std::fprintf(stderr, "the self-check runs an InverseFeedforward (got %s): give TRAJ OUT\n",
                 ff.kind().c_str());
    return 2;
  }
  const ts::Result<ts::io::json> file = ts::io::try_read_json_file(path);
  if (!file.ok()) return failed(file.error());
  const ts::Result<ts::io::InvertibleModel> model =
      ts::io::try_invertible_model_from_json(member(file.value(), "model"), path);
  if (!model.ok()) return failed(model.error());
  const ts::io::InvertibleModel& m = model.value();
  if (m.name != "Backlash" || m.map.input_scale != 1.0 || m.map.output_gain != 1.0) {
    std::fprintf(stderr, "the self-check drives a Backlash model (got %s): give TRAJ OUT\n",
                 m.name.c_str());
    return 2;
  }
  ts::BacklashParams bp;
  bp.c_r = m.backlash.c_r, bp.c_l = m.backlash.c_l, bp.B_r = m.backlash.B_r, bp.B_l = m.backlash.B_l;
  ts::Backlash plant(bp);
  double worst = 0.0;
  for (int k = 0; k < 5000; ++k) {  // 5 s at 1 kHz
    const double y_d = amplitude * std::sin(2 * pi * 0.5 * k * dt);
    const double y = plant.step(ff.step(y_d, k == 0 ? 0.0 : dt));
    if (k >= 1000) worst = std::fmax(worst, std::fabs(y - y_d));
  }
  std::printf("%s from %s: worst tracking error %.4g (amplitude %.3g)\n", ff.kind().c_str(),
              path.c_str(), worst, amplitude);
  return worst < 0.02 * amplitude ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && argc != 4) {
    std::fprintf(stderr, "usage: %s COMPENSATOR.json [TRAJECTORY.csv OUT.csv]\n", argv[0]);
    return 2;
  }
  const ts::Result<ts::io::json> file = ts::io::try_read_json_file(argv[1]);
  if (!file.ok()) return failed(file.error());
  const ts::io::json& f = file.value();
  const ts::io::json& kind = member(f, "compensator");
  const bool multi = kind == "LoadCompensated" || kind == "CoupledFeedforward";
  if (multi && argc != 4) {
    std::fprintf(stderr, "%s: give TRAJ OUT (the self-check runs an InverseFeedforward)\n", argv[1]);
    return 2;
  }
  if (kind == "LoadCompensated") {
    auto c = ts::io::try_load_compensated_from_json(f, argv[1]);
    return c.ok() ? run_loaded(c.value(), argv[2], argv[3]) : failed(c.error());
  }
  if (multi) {
    auto c = ts::io::try_coupled_feedforward_from_json(f, argv[1]);
    return c.ok() ? run_coupled(c.value(), argv[2], argv[3]) : failed(c.error());
  }
  auto ff = ts::io::try_compensator_from_json(f, argv[1]);
  if (!ff.ok()) return failed(ff.error());
  return argc == 4 ? run_trajectory(ff.value(), argv[2], argv[3]) : self_check(ff.value(), argv[1]);
}
