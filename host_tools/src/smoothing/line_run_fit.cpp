// SPDX-License-Identifier: MIT
// Least-squares cubic B-spline fits of line runs (line_run_fit.hpp).
#include <curvestep/host/smoothing/line_run_fit.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <set>

#include <curvestep/host/smoothing/segment_geometry.hpp>

namespace curvestep::host::smoothing {
namespace {

constexpr std::size_t degree = 3;
/// Spline samples per span when distances are checked.
constexpr std::size_t samples_per_span = 12;
/// Weight of the second-difference term relative to one data point.
constexpr double smoothing_weight = 1e-6;
/// Quantising the pieces' control points moves the curve by at most this much (2^-17 mm per axis).
constexpr double grid_allowance_mm = 2e-5;
constexpr int max_refinements = 40;

/// Knot vector: four 0s, the interior knots, four 1s.
std::vector<double> clamped_knots(const std::vector<double>& interior) {
  std::vector<double> knots(degree + 1, 0.0);
  knots.insert(knots.end(), interior.begin(), interior.end());
  knots.insert(knots.end(), degree + 1, 1.0);
  return knots;
}

/// The span s (knots[s] <= t < knots[s+1], degree <= s < control count) holding t.
std::size_t find_span(const std::vector<double>& knots, std::size_t control_count, double t) {
  if (t >= knots[control_count]) return control_count - 1;
  const auto it = std::upper_bound(knots.begin() + degree, knots.begin() + static_cast<std::ptrdiff_t>(control_count), t);
  return static_cast<std::size_t>(it - knots.begin()) - 1;
}

/// The four non-zero basis functions N_{s-3..s}(t) (Cox–de Boor, triangular scheme).
std::array<double, degree + 1> basis(const std::vector<double>& knots, std::size_t s, double t) {
  std::array<double, degree + 1> n{};
  std::array<double, degree + 1> left{};
  std::array<double, degree + 1> right{};
  n[0] = 1;
  for (std::size_t j = 1; j <= degree; ++j) {
    left[j] = t - knots[s + 1 - j];
    right[j] = knots[s + j] - t;
    double saved = 0;
    for (std::size_t r = 0; r < j; ++r) {
      const double denominator = right[r + 1] + left[j - r];
      const double term = denominator != 0 ? n[r] / denominator : 0.0;
      n[r] = saved + right[r + 1] * term;
      saved = left[j - r] * term;
    }
    n[j] = saved;
  }
  return n;
}

struct Spline {
  std::vector<double> knots;
  std::vector<MachinePoint> control;
  [[nodiscard]] MachinePoint at(double t) const {
    const std::size_t s = find_span(knots, control.size(), t);
    const auto n = basis(knots, s, t);
    MachinePoint p{};
    for (std::size_t r = 0; r <= degree; ++r) p = p + control[s - degree + r] * n[r];
    return p;
  }
  /// Blossom of span s at (a, b, c): de Boor's scheme with a different parameter per level.
  [[nodiscard]] MachinePoint blossom(std::size_t s, const std::array<double, degree>& args) const {
    std::array<MachinePoint, degree + 1> d{};
    for (std::size_t r = 0; r <= degree; ++r) d[r] = control[s - degree + r];
    for (std::size_t level = 1; level <= degree; ++level) {
      const double u = args[level - 1];
      for (std::size_t r = degree; r >= level; --r) {
        const std::size_t i = s - degree + r;
        const double denominator = knots[i + degree + 1 - level] - knots[i];
        const double alpha = denominator != 0 ? (u - knots[i]) / denominator : 0.0;
        d[r] = d[r - 1] * (1 - alpha) + d[r] * alpha;
      }
    }
    return d[degree];
  }
};

/// Solves the symmetric positive definite band system A x = b (A given by its lower band:
/// band[i][k] = A(i, i - k), k <= width) in place by Cholesky.
bool solve_band(std::vector<std::array<double, 4>>& band, std::vector<MachinePoint>& rhs) {
  const std::size_t n = band.size();
  constexpr std::size_t width = 3;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = std::min(i, width); k >= 1; --k) {
      // L(i, i-k) = (A(i, i-k) - Σ_{m > k} L(i, i-m) L(i-k, i-m)) / L(i-k, i-k)
      const std::size_t j = i - k;
      double sum = band[i][k];
      for (std::size_t m = k + 1; m <= std::min(i, width); ++m) {
        if (m - k <= width) sum -= band[i][m] * band[j][m - k];
      }
      band[i][k] = sum / band[j][0];
    }
    double diagonal = band[i][0];
    for (std::size_t m = 1; m <= std::min(i, width); ++m) diagonal -= band[i][m] * band[i][m];
    if (!(diagonal > 0)) return false;
    band[i][0] = std::sqrt(diagonal);
  }
  for (std::size_t i = 0; i < n; ++i) {  // L y = b
    MachinePoint sum = rhs[i];
    for (std::size_t m = 1; m <= std::min(i, width); ++m) sum = sum - rhs[i - m] * band[i][m];
    rhs[i] = sum / band[i][0];
  }
  for (std::size_t i = n; i-- > 0;) {  // Lᵀ x = y
    MachinePoint sum = rhs[i];
    for (std::size_t m = 1; m <= width && i + m < n; ++m) sum = sum - rhs[i + m] * band[i + m][m];
    rhs[i] = sum / band[i][0];
  }
  return true;
}

/// Least-squares control points for the knots (ends fixed to the first and last vertex).
std::optional<Spline> least_squares(const std::vector<MachinePoint>& q, const std::vector<double>& t, const std::vector<double>& interior) {
  Spline spline;
  spline.knots = clamped_knots(interior);
  const std::size_t count = interior.size() + degree + 1;  // control points
  spline.control.assign(count, MachinePoint{});
  spline.control.front() = q.front();
  spline.control.back() = q.back();
  const std::size_t unknowns = count - 2;  // control[1 .. count-2]
  std::vector<std::array<double, 4>> band(unknowns, std::array<double, 4>{});
  std::vector<MachinePoint> rhs(unknowns, MachinePoint{});
  const auto add_point = [&](double param, const MachinePoint& target, double weight) {
    const std::size_t s = find_span(spline.knots, count, param);
    const auto n = basis(spline.knots, s, param);
    MachinePoint residual = target;
    for (std::size_t r = 0; r <= degree; ++r) {
      const std::size_t j = s - degree + r;
      if (j == 0 || j == count - 1) residual = residual - spline.control[j] * n[r];
    }
    for (std::size_t r = 0; r <= degree; ++r) {
      const std::size_t j = s - degree + r;
      if (j == 0 || j == count - 1) continue;
      rhs[j - 1] = rhs[j - 1] + residual * (weight * n[r]);
      for (std::size_t c = 0; c <= r; ++c) {
        const std::size_t k = s - degree + c;
        if (k == 0 || k == count - 1) continue;
        band[j - 1][j - k] += weight * n[r] * n[c];
      }
    }
  };
  for (std::size_t i = 1; i + 1 < q.size(); ++i) add_point(t[i], q[i], 1.0);
  for (std::size_t i = 1; i < q.size(); ++i) add_point((t[i - 1] + t[i]) / 2, (q[i - 1] + q[i]) * 0.5, 0.5);
  // Second differences of all control points: μ |P_{j-1} - 2 P_j + P_{j+1}|².
  const double mu = smoothing_weight;
  for (std::size_t j = 1; j + 1 < count; ++j) {
    const std::array<std::size_t, 3> index{j - 1, j, j + 1};
    const std::array<double, 3> coefficient{1, -2, 1};
    MachinePoint residual{};
    for (std::size_t a = 0; a < 3; ++a) {
      if (index[a] == 0 || index[a] == count - 1) residual = residual - spline.control[index[a]] * coefficient[a];
    }
    for (std::size_t a = 0; a < 3; ++a) {
      if (index[a] == 0 || index[a] == count - 1) continue;
      rhs[index[a] - 1] = rhs[index[a] - 1] + residual * (mu * coefficient[a]);
      for (std::size_t b = 0; b <= a; ++b) {
        if (index[b] == 0 || index[b] == count - 1) continue;
        band[index[a] - 1][index[a] - index[b]] += mu * coefficient[a] * coefficient[b];
      }
    }
  }
  if (unknowns > 0) {
    if (!solve_band(band, rhs)) return std::nullopt;
    for (std::size_t j = 1; j + 1 < count; ++j) spline.control[j] = rhs[j - 1];
  }
  return spline;
}

/// Samples of the spline: parameters and points, `samples_per_span` per knot span.
struct Samples {
  std::vector<double> t;
  std::vector<MachinePoint> p;
};
Samples sample_spline(const Spline& spline) {
  Samples out;
  const auto& k = spline.knots;
  for (std::size_t s = degree; s + 1 < k.size() - degree; ++s) {
    if (!(k[s] < k[s + 1])) continue;
    for (std::size_t i = 0; i < samples_per_span; ++i) {
      const double param = k[s] + (k[s + 1] - k[s]) * static_cast<double>(i) / samples_per_span;
      out.t.push_back(param);
      out.p.push_back(spline.at(param));
    }
  }
  out.t.push_back(1.0);
  out.p.push_back(spline.control.back());
  return out;
}

/// Index range [first, last] of sorted `values` that covers [low, high], widened by `margin` entries.
std::pair<std::size_t, std::size_t> window(const std::vector<double>& values, double low, double high, std::size_t margin) {
  const auto a = std::lower_bound(values.begin(), values.end(), low);
  const auto b = std::upper_bound(values.begin(), values.end(), high);
  std::size_t first = static_cast<std::size_t>(a - values.begin());
  std::size_t last = static_cast<std::size_t>(b - values.begin());
  first = first > margin ? first - margin : 0;
  last = std::min(values.size() - 1, last + margin);
  return {first, last};
}

/// Largest deviation both ways, and the spans (indexes into the distinct-knot list) that exceed `limit`.
double check(const Spline& spline, const std::vector<MachinePoint>& q, const std::vector<double>& t, double limit,
             std::set<double>& bad_span_starts) {
  const Samples s = sample_spline(spline);
  const auto span_start = [&](double param) { return spline.knots[find_span(spline.knots, spline.control.size(), param)]; };
  double worst = 0;
  // Every vertex near the spline.
  for (std::size_t i = 0; i < q.size(); ++i) {
    const double low = i > 0 ? t[i - 1] : 0.0;
    const double high = i + 1 < q.size() ? t[i + 1] : 1.0;
    const auto [first, last] = window(s.t, low, high, 2);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = first; j < last; ++j) best = std::fmin(best, distance_to_chord(q[i], s.p[j], s.p[j + 1]));
    if (first == last) best = norm(q[i] - s.p[first]);
    worst = std::fmax(worst, best);
    if (best > limit) bad_span_starts.insert(span_start(t[i]));
  }
  // Every spline sample near the polyline.
  for (std::size_t j = 0; j < s.p.size(); ++j) {
    const auto [first, last] = window(t, s.t[j], s.t[j], 2);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = first; i < last; ++i) best = std::fmin(best, distance_to_chord(s.p[j], q[i], q[i + 1]));
    worst = std::fmax(worst, best);
    if (best > limit) bad_span_starts.insert(span_start(s.t[j]));
  }
  // No cusp: consecutive samples must move.
  for (std::size_t j = 1; j < s.p.size(); ++j) {
    if (!(norm(s.p[j] - s.p[j - 1]) > 1e-9)) return std::numeric_limits<double>::infinity();
  }
  return worst;
}

}  // namespace

std::optional<LineRunFit> fit_line_run(const std::vector<MachinePoint>& vertices, double tolerance_mm, double feed_mm_per_s) {
  if (vertices.size() < 4 || !(tolerance_mm > grid_allowance_mm)) return std::nullopt;
  std::vector<double> t(vertices.size(), 0.0);
  for (std::size_t i = 1; i < vertices.size(); ++i) t[i] = t[i - 1] + norm(vertices[i] - vertices[i - 1]);
  const double total = t.back();
  if (!(total > 0)) return std::nullopt;
  for (auto& value : t) value /= total;
  t.back() = 1.0;
  const std::size_t lines = vertices.size() - 1;
  const double limit = tolerance_mm - grid_allowance_mm;

  std::vector<double> interior;
  std::optional<Spline> fitted;
  double deviation = 0;
  for (int round = 0; round < max_refinements; ++round) {
    if (interior.size() + 1 >= lines) return std::nullopt;  // as many pieces as lines: nothing gained
    auto spline = least_squares(vertices, t, interior);
    if (!spline) return std::nullopt;
    std::set<double> bad;
    deviation = check(*spline, vertices, t, limit, bad);
    if (!std::isfinite(deviation)) return std::nullopt;
    if (bad.empty()) {
      fitted = std::move(spline);
      break;
    }
    // Halve every span that strays.
    std::vector<double> distinct{0.0};
    distinct.insert(distinct.end(), interior.begin(), interior.end());
    distinct.push_back(1.0);
    for (std::size_t k = 0; k + 1 < distinct.size(); ++k) {
      if (bad.count(distinct[k]) != 0) interior.push_back((distinct[k] + distinct[k + 1]) / 2);
    }
    std::sort(interior.begin(), interior.end());
  }
  if (!fitted) return std::nullopt;

  // Bézier pieces by blossoming each span, on the grid, sharing end points exactly.
  LineRunFit fit;
  fit.deviation_mm = deviation + grid_allowance_mm;
  const auto& k = fitted->knots;
  MachinePoint previous_end = vertices.front();
  for (std::size_t s = degree; s + 1 < k.size() - degree; ++s) {
    const double a = k[s];
    const double b = k[s + 1];
    if (!(a < b)) continue;
    std::array<MachinePoint, 4> control{previous_end, fitted->blossom(s, {a, a, b}), fitted->blossom(s, {a, b, b}),
                                        fitted->blossom(s, {b, b, b})};
    for (std::size_t i = 1; i < 4; ++i) {
      const auto g = on_grid(control[i]);
      if (!g) return std::nullopt;
      control[i] = *g;
    }
    if (b >= 1.0) control[3] = vertices.back();
    // A straight piece (collinear lines) is a line: the planner keeps a line's full limits.
    const bool straight = distance_to_chord(control[1], control[0], control[3]) < 1e-7 &&
                          distance_to_chord(control[2], control[0], control[3]) < 1e-7;
    auto piece = straight ? PathSegment::make_line(control[0], control[3]) : PathSegment::make_bezier(control);
    if (!piece) return std::nullopt;
    piece.value().set_feed_mm_per_s(feed_mm_per_s);
    fit.pieces.push_back(piece.value());
    previous_end = control[3];
  }
  if (fit.pieces.empty() || fit.pieces.size() >= lines) return std::nullopt;
  return fit;
}

}  // namespace curvestep::host::smoothing
