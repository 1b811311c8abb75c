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
    switch (ip_) {  // the usual sharpness exponents, unrolled
      case 0: return 1.0;
      case 1: return a;
      case 2: return a * a;
      case 3: return a * a * a;
      case 4: { const double a2 = a * a; return a2 * a2; }
      case 5: { const double a2 = a * a; return a2 * a2 * a; }
      case 6: { const double a3 = a * a * a; return a3 * a3; }
      case 7: { const double a3 = a * a * a; return a3 * a3 * a; }
      case 8: { const double a2 = a * a, a4 = a2 * a2; return a4 * a4; }
      default: break;
    }
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

// NaN passes through; callers reject a non-finite result as a whole.
inline double clamp_unit(double w) noexcept { return w > 1.0 ? 1.0 : (w < -1.0 ? -1.0 : w); }

}  // namespace tendonsheath::detail
