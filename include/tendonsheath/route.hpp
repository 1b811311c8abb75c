// Route of a sheath: its centreline described by the accumulated curve angle
// theta(s) = int_0^s |kappa| ds along the arc length s in [0, L] (spec A.1, A.5).
//
// A route is stored as samples (s_i, theta_i), s non-decreasing from 0 to L,
// theta non-decreasing from 0; theta is linear between samples. Two samples
// with the same s describe a jump (a discrete turning angle of a polyline);
// theta is right-continuous there. Only differences theta(b) - theta(a) are
// used by the plants, so every jump lands in exactly one element and the
// element angles always add up to the total angle.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "validate.hpp"

namespace tendonsheath {

/// @brief The route of a sheath: the accumulated curve angle theta(s) = int_0^s |kappa| ds along
/// the arc length s in [0, L] (spec A.1, A.5).
///
/// Stored as samples (s_i, theta_i), theta linear between them; two samples with the same s are a
/// jump (the turning angle at a polyline vertex), right-continuous. Built once, before the control
/// loop (the constructors allocate and validate); the queries are noexcept and allocate nothing.
class Route {
 public:
  /// Samples of the accumulated angle; validated (finite, s non-decreasing from
  /// 0 to L > 0, theta non-decreasing from 0).
  /// @param s the arc-length samples, m
  /// @param theta the accumulated-angle samples, rad (as many as s)
  /// Throws std::invalid_argument naming the first bad sample.
  Route(std::vector<double> s, std::vector<double> theta) : s_(std::move(s)), th_(std::move(theta)) {
    const char* w = "Route";
    require(s_.size() == th_.size(), w, "s and theta have different lengths (", s_.size(), " and ",
            th_.size(), ")");
    require(s_.size() >= 2, w, "at least two samples are needed");
    if (detail::failed()) return;  // without exceptions, in make(): the samples are not indexed
    for (std::size_t i = 0; i < s_.size(); ++i) {
      require(std::isfinite(s_[i]), w, "s[", i, "] is not finite (", s_[i], ")");
      require(std::isfinite(th_[i]), w, "theta[", i, "] is not finite (", th_[i], ")");
    }
    require(s_[0] == 0.0, w, "s must start at 0 (got ", s_[0], ")");
    require(th_[0] == 0.0, w, "theta must start at 0 (got ", th_[0], ")");
    for (std::size_t i = 1; i < s_.size(); ++i) {
      require(s_[i] >= s_[i - 1], w, "s must be non-decreasing (s[", i, "] = ", s_[i], " < ",
              s_[i - 1], ")");
      require(th_[i] >= th_[i - 1], w, "theta must be non-decreasing (theta[", i, "] = ", th_[i],
              " < ", th_[i - 1], ")");
    }
    require(s_.back() > 0.0, w, "length must be > 0 (got ", s_.back(), ")");
  }

  /// Constant curvature: theta(s) = curve_angle * s / length.
  /// @param length L, m, > 0
  /// @param curve_angle Theta, rad, >= 0
  /// @return the route; throws std::invalid_argument on a bad argument
  static Route uniform(double length, double curve_angle) {
    require_positive(length, "Route.uniform", "length");
    require_non_negative(curve_angle, "Route.uniform", "curve_angle");
    return Route({0.0, length}, {0.0, curve_angle});
  }

  /// Consecutive arcs of constant curvature: (length > 0, bend angle). A bend
  /// to the other side (negative angle) accumulates |angle|.
  /// @param pieces (length, angle) pairs, m and rad, at least one
  /// @return the route; throws std::invalid_argument naming the first bad piece
  static Route arcs(const std::vector<std::pair<double, double>>& pieces) {
    const char* w = "Route.arcs";
    require(!pieces.empty(), w, "at least one (length, angle) piece is needed");
    std::vector<double> s{0.0}, th{0.0};
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const double len = pieces[i].first, ang = pieces[i].second;
      require(std::isfinite(len) && len > 0.0, w, "length of piece ", i, " must be > 0 (got ", len,
              ")");
      require(std::isfinite(ang), w, "angle of piece ", i, " is not finite (", ang, ")");
      s.push_back(s.back() + len);
      th.push_back(th.back() + std::fabs(ang));
    }
    return Route(std::move(s), std::move(th));
  }

  /// A 3-D polyline of K >= 2 points (xyz row-major, K x 3, metres). Each
  /// interior vertex adds its turning angle as a jump of theta at that vertex.
  /// @param xyz the k points, 3 k coordinates, m
  /// @param k the number of points, >= 2
  /// @return the route; throws std::invalid_argument on a non-finite point or two coinciding ones
  static Route from_points(const double* xyz, std::size_t k) {
    const char* w = "Route.from_points";
    require(k >= 2, w, "at least two points are needed (got ", k, ")");
    for (std::size_t i = 0; i < 3 * k; ++i)
      require(std::isfinite(xyz[i]), w, "point ", i / 3, " is not finite (coordinate ", i % 3,
              " = ", xyz[i], ")");
    std::vector<double> s{0.0}, th{0.0};
    double prev[3] = {0, 0, 0};
    for (std::size_t i = 0; i + 1 < k; ++i) {
      const double d[3] = {xyz[3 * (i + 1)] - xyz[3 * i], xyz[3 * (i + 1) + 1] - xyz[3 * i + 1],
                           xyz[3 * (i + 1) + 2] - xyz[3 * i + 2]};
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      require(len > 0.0, w, "points ", i, " and ", i + 1, " coincide");
      if (i > 0) {
        const double cx = prev[1] * d[2] - prev[2] * d[1];
        const double cy = prev[2] * d[0] - prev[0] * d[2];
        const double cz = prev[0] * d[1] - prev[1] * d[0];
        const double turn = std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz),
                                       prev[0] * d[0] + prev[1] * d[1] + prev[2] * d[2]);
        if (turn > 0.0) {
          s.push_back(s.back());
          th.push_back(th.back() + turn);
        }
      }
      s.push_back(s.back() + len);
      th.push_back(th.back());
      for (int c = 0; c < 3; ++c) prev[c] = d[c];
    }
    return Route(std::move(s), std::move(th));
  }

  /// A sampled curvature profile kappa(s) (s strictly increasing, shifted to
  /// start at 0); theta is the trapezoidal integral of |kappa|.
  /// @param s the n arc lengths, m, strictly increasing
  /// @param kappa the n curvatures, 1/m (their magnitudes are used)
  /// @param n the number of samples, >= 2
  /// @return the route; throws std::invalid_argument naming the first bad sample
  static Route from_curvature(const double* s, const double* kappa, std::size_t n) {
    const char* w = "Route.from_curvature";
    require(n >= 2, w, "at least two samples are needed (got ", n, ")");
    for (std::size_t i = 0; i < n; ++i) {
      require(std::isfinite(s[i]), w, "s[", i, "] is not finite (", s[i], ")");
      require(std::isfinite(kappa[i]), w, "kappa[", i, "] is not finite (", kappa[i], ")");
      if (i > 0)
        require(s[i] > s[i - 1], w, "s must be strictly increasing (s[", i, "] = ", s[i], ")");
    }
    std::vector<double> ss(n), th(n);
    ss[0] = 0.0;
    th[0] = 0.0;
    for (std::size_t i = 1; i < n; ++i) {
      ss[i] = s[i] - s[0];
      th[i] = th[i - 1] + 0.5 * (std::fabs(kappa[i]) + std::fabs(kappa[i - 1])) * (s[i] - s[i - 1]);
    }
    return Route(std::move(ss), std::move(th));
  }

  /// The arc length L of the route, metres.
  double length() const noexcept { return s_.back(); }
  /// The curve angle theta(L), radians.
  double curve_angle() const noexcept { return th_.back(); }
  /// The curve angle theta(L) by its old name (docs/vocabulary.md).
  [[deprecated("use curve_angle()")]] double total_angle() const noexcept { return curve_angle(); }
  /// The arc-length samples s_i, metres (non-decreasing, from 0 to L).
  const std::vector<double>& s() const noexcept { return s_; }
  /// The accumulated-angle samples theta_i, radians (non-decreasing, from 0).
  const std::vector<double>& theta() const noexcept { return th_; }

  /// theta(s), right-continuous at jumps; clamped outside [0, L].
  /// @param s the arc length, m
  /// @return theta(s), rad
  double angle_at(double s) const noexcept {
    if (!(s > 0.0)) return (s == 0.0 && s_[1] == 0.0) ? theta_right_of_zero() : 0.0;
    if (s >= s_.back()) return th_.back();
    // last i with s_i <= s (binary search)
    std::size_t lo = 0, hi = s_.size() - 1;
    while (hi - lo > 1) {
      const std::size_t mid = (lo + hi) / 2;
      if (s_[mid] <= s) lo = mid;
      else hi = mid;
    }
    const double ds = s_[hi] - s_[lo];
    if (ds <= 0.0) return th_[lo];
    return th_[lo] + (th_[hi] - th_[lo]) * (s - s_[lo]) / ds;
  }

  /// Angles of n equal elements (out[0..n-1], proximal to distal): the
  /// increments of theta over [e L/n, (e+1) L/n]. Allocation-free, O(n + K).
  /// A jump exactly at an element boundary goes to the element ending there;
  /// a jump at s = 0 goes to the first element. The sum is exactly theta(L)
  /// up to rounding.
  /// @param n the number of elements, >= 1
  /// @param out receives the n element angles, rad
  void element_angles(std::size_t n, double* out) const noexcept {
    const double L = s_.back();
    double prev = 0.0;
    std::size_t i = 0;  // samples [0, i) have s_ < current grid point
    const std::size_t K = s_.size();
    for (std::size_t e = 1; e <= n; ++e) {
      double th;
      if (e == n) {
        th = th_.back();
      } else {
        const double x = L * static_cast<double>(e) / static_cast<double>(n);
        // theta right-continuous at x: jumps located exactly at x are included
        while (i < K && s_[i] <= x) ++i;  // now s_[i-1] <= x < s_[i]
        const std::size_t lo = i - 1;
        if (i >= K) {
          th = th_.back();
        } else {
          const double ds = s_[i] - s_[lo];
          th = ds > 0.0 ? th_[lo] + (th_[i] - th_[lo]) * (x - s_[lo]) / ds : th_[lo];
        }
      }
      out[e - 1] = th - prev;
      if (out[e - 1] < 0.0) out[e - 1] = 0.0;
      prev = th;
    }
  }

  /// Lumped angles of the n-1 interior nodes of an n-element sheath
  /// (out[0..n-2], node 1 to node n-1, proximal to distal): half of each
  /// adjacent element, plus the outer halves of the two end elements (whose
  /// outer nodes are driven ends or the distal pulley). Their sum equals the
  /// total angle. Needs n >= 2; `work` holds n doubles (scratch).
  /// @param n the number of elements, >= 2
  /// @param out receives the n - 1 node angles, rad
  /// @param work scratch space of n doubles
  void node_angles(std::size_t n, double* out, double* work) const noexcept {
    element_angles(n, work);
    for (std::size_t j = 1; j < n; ++j) out[j - 1] = 0.5 * (work[j - 1] + work[j]);
    out[0] += 0.5 * work[0];
    out[n - 2] += 0.5 * work[n - 1];
  }

 private:
  double theta_right_of_zero() const noexcept {
    std::size_t i = 0;
    while (i + 1 < s_.size() && s_[i + 1] == 0.0) ++i;
    return th_[i];
  }

  std::vector<double> s_;
  std::vector<double> th_;
};

}  // namespace tendonsheath
