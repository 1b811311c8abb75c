// The JSON loaders (tendonsheath/io/json*.hpp) without C++ exceptions. This file is built twice
// (CMakeLists.txt beside it): with exceptions, and with g++ -fno-exceptions (plus
// AddressSanitizer and UndefinedBehaviorSanitizer where the compiler has them). compare.cmake
// runs both and requires the same output, line for line, so that without exceptions:
//   - every malformed file of the loaders' tests (the 32 of test_io_json_multi_input.cpp and 42
//     single-input ones, json_malformed_cases.hpp) gives the same message, one line naming the
//     file and the key, through the try_ loaders' Result (never an abort inside nlohmann/json);
//   - files on disk that cannot be opened, are not JSON or hold a number beyond a double give the
//     same message as with exceptions;
//   - random changes to good files (a value replaced by one of another type, size or range, a key
//     removed or added) give the same message, or load and step bit for bit alike.
// With exceptions it also checks each Result's message against the throwing loader's
// std::invalid_argument, and both builds check the words each malformed file's message must say.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <tendonsheath/io/json_multi_input.hpp>

#include "../json_malformed_cases.hpp"

#include "harness.hpp"

namespace ts = tendonsheath;
using json = ts::io::json;

using no_exceptions::check;
using no_exceptions::failures;
using no_exceptions::Rng;

namespace {

int refused = 0;    // loads that returned an error
int malformed = 0;  // malformed files whose message was checked for its words

std::string dir;  // this run's temporary directory: "DIR" in what is printed

std::string masked(std::string text) {
  for (std::size_t at; !dir.empty() && (at = text.find(dir)) != std::string::npos;)
    text.replace(at, dir.size(), "DIR");
  return text;
}

// try_load() printed as "<label>: ok" or "<label>: <message>"; with exceptions, load() must throw
// that message (or load)
template <class T, class Try, class Throw>
ts::Result<T> loaded(const std::string& label, const Try& try_load, const Throw& load) {
  ts::Result<T> r = try_load();
  refused += r.ok() ? 0 : 1;
  std::printf("%s: %s\n", label.c_str(), r.ok() ? "ok" : masked(r.error()).c_str());
#if TENDONSHEATH_EXCEPTIONS
  std::string thrown = "ok";
  try {
    (void)load();
  } catch (const std::invalid_argument& e) {
    thrown = e.what();
  }
  check(thrown == (r.ok() ? "ok" : r.error()),
        label + ": the Result said '" + r.error() + "', the throw '" + thrown + "'");
#else
  (void)load;
#endif
  return r;
}

// a malformed file's message: refused, one line starting with `name`, holding `words`
template <class T>
void named(const std::string& label, const ts::Result<T>& r, const std::string& name,
           const std::string& words) {
  ++malformed;
  check(!r.ok(), label + ": loaded");
  const std::string& m = r.error();
  check(m.rfind(name, 0) == 0 && m.find(words) != std::string::npos && m.find('\n') == std::string::npos,
        label + ": '" + m + "' should start with '" + name + "' and say '" + words + "'");
}

// the hash of the bits of one output
void mix(std::uint64_t& h, double y) {
  std::uint64_t bits;
  std::memcpy(&bits, &y, sizeof bits);
  h = (h ^ bits) * 1099511628211ull;
}

// 200 steps of each loaded kind, over the same input in both builds, hashed
std::uint64_t run(ts::io::LoadedCompensator& c) {
  std::uint64_t h = 1469598103934665603ull;
  for (int k = 0; k < 200; ++k) {
    const double y = 0.8 * std::sin(0.03 * k);
    mix(h, c.step(y, k % 50 == 7 ? NAN : 0.9 * y, k ? 1e-3 : 0.0));
  }
  return h;
}
std::uint64_t run(ts::io::LoadCompensatedInverse& c) {
  std::uint64_t h = 1469598103934665603ull;
  for (int k = 0; k < 200; ++k) mix(h, c.step(0.8 * std::sin(0.03 * k), k ? 1e-3 : 0.0, 0.1 * k));
  return h;
}
std::uint64_t run(ts::CoupledFeedforward& c) {
  std::uint64_t h = 1469598103934665603ull;
  std::vector<double> y(c.joints()), u(c.joints());
  for (int k = 0; k < 200; ++k) {
    for (std::size_t j = 0; j < y.size(); ++j) y[j] = 0.5 * std::sin(0.03 * k + j);
    c.step(y.data(), u.data(), k ? 1e-3 : 0.0);
    for (double v : u) mix(h, v);
  }
  return h;
}

template <class T>
void print_steps(const std::string& label, ts::Result<T>& r) {
  if (r.ok()) std::printf("%s steps: %016llx\n", label.c_str(), static_cast<unsigned long long>(run(r.value())));
}

// the three loaders of parsed files, under one label
void load_single(const std::string& label, const json& f) {
  auto r = loaded<ts::io::LoadedCompensator>(
      label, [&] { return ts::io::try_compensator_from_json(f, "f"); },
      [&] { return ts::io::compensator_from_json(f, "f"); });
  print_steps(label, r);
}
void load_lc(const std::string& label, const json& f) {
  auto r = loaded<ts::io::LoadCompensatedInverse>(
      label, [&] { return ts::io::try_load_compensated_from_json(f, "f.json"); },
      [&] { return ts::io::load_compensated_from_json(f, "f.json"); });
  print_steps(label, r);
}
void load_cf(const std::string& label, const json& f) {
  auto r = loaded<ts::CoupledFeedforward>(
      label, [&] { return ts::io::try_coupled_feedforward_from_json(f, "f.json"); },
      [&] { return ts::io::coupled_feedforward_from_json(f, "f.json"); });
  print_steps(label, r);
}

// the malformed files of the loaders' tests: 18 + 14 multi-input, 42 single-input
void malformed_files() {
  const json lc = malformed_json::load_compensated_file(0.3, 0.02, 0.1, 0.05);
  const auto lc_cases = malformed_json::load_compensated_cases();
  for (std::size_t k = 0; k < lc_cases.size(); ++k) {
    json f = lc;
    lc_cases[k].change(f);
    const std::string label = "LoadCompensated case " + std::to_string(k);
    named(label, loaded<ts::io::LoadCompensatedInverse>(
                     label, [&] { return ts::io::try_load_compensated_from_json(f, "f.json"); },
                     [&] { return ts::io::load_compensated_from_json(f, "f.json"); }),
          "f.json", lc_cases[k].words);
  }
  const json cf = malformed_json::three_joints();
  const auto cf_cases = malformed_json::coupled_feedforward_cases();
  for (std::size_t k = 0; k < cf_cases.size(); ++k) {
    json f = cf;
    cf_cases[k].change(f);
    const std::string label = "CoupledFeedforward case " + std::to_string(k);
    named(label, loaded<ts::CoupledFeedforward>(
                     label, [&] { return ts::io::try_coupled_feedforward_from_json(f, "f.json"); },
                     [&] { return ts::io::coupled_feedforward_from_json(f, "f.json"); }),
          "f.json", cf_cases[k].words);
  }
  const auto cases = malformed_json::compensator_cases();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const std::string label = "compensator case " + std::to_string(k);
    named(label, loaded<ts::io::LoadedCompensator>(
                     label, [&] { return ts::io::try_compensator_from_json(cases[k].file, "f"); },
                     [&] { return ts::io::compensator_from_json(cases[k].file, "f"); }),
          cases[k].start, cases[k].words);
  }
}

// the good files load, and step alike in both builds
void good_files() {
  for (const auto& [name, f] : malformed_json::good_compensator_files()) {
    const std::string label = "good " + name;
    auto r = loaded<ts::io::LoadedCompensator>(
        label, [&] { return ts::io::try_compensator_from_json(f, "f"); },
        [&] { return ts::io::compensator_from_json(f, "f"); });
    check(r.ok(), label + ": refused: " + r.error());
    print_steps(label, r);
  }
  load_lc("good LoadCompensated", malformed_json::load_compensated_file(0.3, 0.02, 0.1, 0.05));
  load_cf("good CoupledFeedforward", malformed_json::three_joints());
}

void write(const std::string& path, const std::string& text) {
  std::FILE* out = std::fopen(path.c_str(), "wb");
  check(out != nullptr, "cannot write " + path);
  if (!out) return;
  std::fwrite(text.data(), 1, text.size(), out);
  std::fclose(out);
}

// `text` with `from` replaced by `to` (once)
std::string swapped(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  check(at != std::string::npos, "'" + from + "' not in the file");
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// files on disk: unreadable, not JSON, a number beyond a double, and good ones
void files() {
  const std::string curve = malformed_json::curve_angle_file().dump();
  const std::string lc = malformed_json::load_compensated_file(0.3, 0.02, 0.1, 0.05).dump();
  const std::string cf = malformed_json::three_joints().dump();
  const std::string learned = malformed_json::learned_file().dump();
  const std::vector<std::pair<std::string, std::string>> texts{
      {"empty", ""},
      {"open", "{"},
      {"trailing comma", "{\"a\": 1,}"},
      {"no comma", "[1 2]"},
      {"bad literal", "nul"},
      {"after the end", "{} x"},
      {"bad surrogate", "\"\\uD800\""},
      {"not UTF-8", "\"\xff\""},
      {"max_rate 1e999", swapped(curve, "\"max_rate\":20.0", "\"max_rate\":1e999")},
      {"max_rate of 400 digits", swapped(curve, "\"max_rate\":20.0", "\"max_rate\":" + std::string(400, '9'))},
      {"table -1e999", swapped(learned, "[0.0,0.01,0.03]", "[0.0,-1e999]")},
      {"c_r 1e400", swapped(learned, "\"c_r\":1.0", "\"c_r\":1e400")},
      {"switch 1e999", swapped(lc, "\"switch\":0.001", "\"switch\":1e999")},
      {"coupling 1e999", swapped(cf, "0.05", "1e999")},
      {"good curve angle", curve},
      {"good LoadCompensated", lc},
      {"good CoupledFeedforward", cf},
      {"bad key", swapped(curve, "\"pretension\"", "\"pre_tension\"")},
  };
  for (std::size_t k = 0; k < texts.size(); ++k) {
    const std::string path = dir + "/file" + std::to_string(k) + ".json";
    write(path, texts[k].second);
    const std::string label = "file " + texts[k].first;
    loaded<json>(label + " read", [&] { return ts::io::try_read_json_file(path); },
                 [&] { return ts::io::read_json_file(path); });
    auto single = loaded<ts::io::LoadedCompensator>(
        label + " single", [&] { return ts::io::try_load_compensator_json(path); },
        [&] { return ts::io::load_compensator_json(path); });
    print_steps(label + " single", single);
    auto l = loaded<ts::io::LoadCompensatedInverse>(
        label + " LoadCompensated", [&] { return ts::io::try_load_load_compensated_json(path); },
        [&] { return ts::io::load_load_compensated_json(path); });
    print_steps(label + " LoadCompensated", l);
    auto c = loaded<ts::CoupledFeedforward>(
        label + " CoupledFeedforward", [&] { return ts::io::try_load_coupled_feedforward_json(path); },
        [&] { return ts::io::load_coupled_feedforward_json(path); });
    print_steps(label + " CoupledFeedforward", c);
    std::remove(path.c_str());
  }
  const std::string missing = dir + "/missing.json";
  named("missing file", ts::io::try_load_compensator_json(missing), missing, "cannot open the file");
}

// every JSON pointer into v (v itself, and each member and element, at any depth)
void pointers(const json& v, const json::json_pointer& at, std::vector<json::json_pointer>& out) {
  out.push_back(at);
  if (v.is_object()) {
    for (const auto& item : v.items()) pointers(item.value(), at / item.key(), out);
  } else if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i) pointers(v[i], at / i, out);
  }
}

// a value of another type, size or range than the one it replaces
json odd_value(Rng& rng) {
  switch (rng.below(17)) {
    case 0: return nullptr;
    case 1: return true;
    case 2: return "x";
    case 3: return "";
    case 4: return -1;
    case 5: return 0;
    case 6: return 1;
    case 7: return 2.5;
    case 8: return -1e300;
    case 9: return std::int64_t{1} << 40;
    case 10: return std::uint64_t(-1);
    case 11: return std::nan("");
    case 12: return json::array();
    case 13: return json::object();
    case 14: return {1.0, 2.0};
    case 15: return json::array({json::array({1.0, 2.0})});
    default: return {{"a", 1}};
  }
}

// f with one or two random changes: a value replaced, a key removed, or a key added
json mutated(json f, Rng& rng) {
  const int n = 1 + static_cast<int>(rng.below(2));
  for (int i = 0; i < n; ++i) {
    std::vector<json::json_pointer> at;
    pointers(f, json::json_pointer(), at);
    const json::json_pointer p = at[rng.below(at.size())];
    const std::size_t what = rng.below(4);
    if (what == 0 && !p.empty() && f[p.parent_pointer()].is_object()) {
      f[p.parent_pointer()].erase(p.back());
    } else if (what == 1 && f[p].is_object()) {
      f[p]["unexpected"] = 1;
    } else {
      f[p] = odd_value(rng);
    }
  }
  return f;
}

// random changes to every good file: the same message (or the same steps) in both builds
void mutations(Rng& rng) {
  auto good = malformed_json::good_compensator_files();
  for (int trial = 0; trial < 30; ++trial) {
    for (const auto& [name, f] : good)
      load_single("mutated " + name + " #" + std::to_string(trial), mutated(f, rng));
    load_lc("mutated LoadCompensated #" + std::to_string(trial),
            mutated(malformed_json::load_compensated_file(0.3, 0.02, 0.1, 0.05), rng));
    load_cf("mutated CoupledFeedforward #" + std::to_string(trial),
            mutated(malformed_json::three_joints(), rng));
  }
}

}  // namespace

int main() {
  char tmp[] = "/tmp/ts_json_cases_XXXXXX";
  if (mkdtemp(tmp) == nullptr) return 2;
  dir = tmp;
  Rng rng{20261127};
  malformed_files();
  good_files();
  files();
  mutations(rng);
  rmdir(dir.c_str());
  // the 74 malformed files of the tests and the missing one; of the loads 513 refuse (measured:
  // the 74, 65 of the 72 loads of files on disk, 374 of the 420 mutations); 450 leaves a margin
  // and still fails if the mutations stopped biting
  check(malformed == 75, std::to_string(malformed) + " malformed files checked (75 expected)");
  check(refused >= 450, "only " + std::to_string(refused) + " loads refused");
  std::fprintf(stderr, "%d malformed files, %d refused, %d failures\n", malformed, refused, failures);
  return failures == 0 ? 0 : 1;
}
