// |w|^p for the Bouc-Wen family: exact repeated multiplication when p is a
// small integer (the usual case, and 10x faster than std::pow).
#pragma once

#include <cmath>

namespace tendonsheath::detail {

class AbsPower {
 public:
  AbsPower() = default;
  explicit AbsPower(double p) : p_(p) {
    const double r = std::round(p);
    integer_ = (r == p && r >= 0.0 && r <= 64.0);
    ip_ = integer_ ? static_cast<int>(r) : 0;
  }
  double operator()(double a) const noexcept {  // a >= 0
    if (!integer_) return a > 0.0 ? std::pow(a, p_) : (p_ == 0.0 ? 1.0 : 0.0);
    double result = 1.0, base = a;
    for (int e = ip_; e > 0; e >>= 1) {
      if (e & 1) result *= base;
      base *= base;
    }
    return result;
  }

 private:
  double p_ = 1.0;
  int ip_ = 1;
  bool integer_ = true;
};

inline double clamp_unit(double w) noexcept { return w > 1.0 ? 1.0 : (w < -1.0 ? -1.0 : w); }

}  // namespace tendonsheath::detail
