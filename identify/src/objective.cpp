// Curve metrics of docs/spec.md 3; the conventions are documented in objective.hpp.
#include "demfit/identify/objective.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace demfit::identify {
namespace {

int computed_stations(int target_stations) { return 3 * (target_stations - 1) + 1; }

double polyline_length(const Curve& curve, double x_scale, double y_scale) {
  double length = 0.0;
  for (std::size_t i = 1; i < curve.x.size(); ++i)
    length += std::hypot((curve.x[i] - curve.x[i - 1]) / x_scale, (curve.y[i] - curve.y[i - 1]) / y_scale);
  return length;
}

// Cumulative arc length of an interleaved polyline.
std::vector<double> cumulative_arc(const double* xy, int points) {
  std::vector<double> arc(points, 0.0);
  for (int i = 1; i < points; ++i)
    arc[i] = arc[i - 1] + std::hypot(xy[2 * i] - xy[2 * i - 2], xy[2 * i + 1] - xy[2 * i - 1]);
  return arc;
}

// Point at arc length s along an interleaved polyline (clamped to its ends).
void point_at(const double* xy, const std::vector<double>& arc, double s, double& x, double& y) {
  const int n = static_cast<int>(arc.size());
  if (s <= arc.front()) {
    x = xy[0];
    y = xy[1];
    return;
  }
  if (s >= arc.back()) {
    x = xy[2 * n - 2];
    y = xy[2 * n - 1];
    return;
  }
  const int i = static_cast<int>(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin());  // arc[i-1] <= s < arc[i]
  const double length = arc[i] - arc[i - 1];
  const double t = length > 0.0 ? (s - arc[i - 1]) / length : 0.0;
  x = xy[2 * i - 2] + t * (xy[2 * i] - xy[2 * i - 2]);
  y = xy[2 * i - 1] + t * (xy[2 * i + 1] - xy[2 * i - 1]);
}

double max_abs(const std::vector<double>& values) {
  double m = 0.0;
  for (double v : values) m = std::max(m, std::abs(v));
  return m;
}

// Integral of |d(x)| over [a, b] for d linear from d(a) = da to d(b) = db (exact, also when d
// changes sign inside).
double absolute_linear_integral(double da, double db, double length) {
  if ((da >= 0.0) == (db >= 0.0)) return 0.5 * std::abs(da + db) * length;
  return 0.5 * (da * da + db * db) / (std::abs(da) + std::abs(db)) * length;
}

}  // namespace

double profile_area_between(const std::vector<double>& x, const double* f, const std::vector<double>& g, double lower,
                            double upper) {
  double area = 0.0;
  for (std::size_t i = 1; i < x.size(); ++i) {
    const double a = std::max(x[i - 1], lower), b = std::min(x[i], upper);
    if (!(b > a)) continue;
    const double span = x[i] - x[i - 1];
    auto difference = [&](double at) {
      const double t = span > 0.0 ? (at - x[i - 1]) / span : 0.0;
      return (f[i - 1] - g[i - 1]) + t * ((f[i] - g[i]) - (f[i - 1] - g[i - 1]));
    };
    area += absolute_linear_integral(difference(a), difference(b), b - a);
  }
  return area;
}

std::vector<double> resample_monotone(const Curve& curve, const std::vector<double>& at_x) {
  const std::size_t n = curve.x.size();
  if (n < 2 || curve.y.size() != n) throw std::runtime_error("curve '" + curve.y_label + "' has fewer than 2 points");
  bool increasing = true, decreasing = true;
  for (std::size_t i = 1; i < n; ++i) {
    increasing = increasing && curve.x[i] >= curve.x[i - 1];
    decreasing = decreasing && curve.x[i] <= curve.x[i - 1];
  }
  if (!increasing && !decreasing)
    throw std::runtime_error("curve '" + curve.y_label + "' is not monotone in x; use metric \"curve_mapping\"");
  std::vector<double> xs = curve.x, ys = curve.y;
  if (!increasing) {
    std::reverse(xs.begin(), xs.end());
    std::reverse(ys.begin(), ys.end());
  }
  std::vector<double> out(at_x.size());
  for (std::size_t k = 0; k < at_x.size(); ++k) {
    const double x = at_x[k];
    if (x <= xs.front()) {
      out[k] = ys.front();
      continue;
    }  // flat extrapolation
    if (x >= xs.back()) {
      out[k] = ys.back();
      continue;
    }
    const std::size_t i = std::upper_bound(xs.begin(), xs.end(), x) - xs.begin();  // xs[i-1] <= x < xs[i]
    const double dx = xs[i] - xs[i - 1];
    const double t = dx > 0.0 ? (x - xs[i - 1]) / dx : 0.0;
    out[k] = ys[i - 1] + t * (ys[i] - ys[i - 1]);
  }
  return out;
}

std::vector<double> equal_arc_length_points(const Curve& curve, int count, double x_scale, double y_scale) {
  const int n = static_cast<int>(curve.x.size());
  if (n < 2) throw std::runtime_error("curve '" + curve.y_label + "' has fewer than 2 points");
  std::vector<double> xy(2 * n);
  for (int i = 0; i < n; ++i) {
    xy[2 * i] = curve.x[i] / x_scale;
    xy[2 * i + 1] = curve.y[i] / y_scale;
  }
  const auto arc = cumulative_arc(xy.data(), n);
  std::vector<double> out(2 * count);
  for (int k = 0; k < count; ++k) {
    const double s = arc.back() * k / (count - 1);
    point_at(xy.data(), arc, s, out[2 * k], out[2 * k + 1]);
  }
  return out;
}

CompositeObjective::CompositeObjective(std::vector<TargetSpec> targets) : targets_(std::move(targets)) {
  for (const auto& t : targets_) {
    Prepared p;
    const double gmax = max_abs(t.data.y);
    p.y_scale = t.scale > 0.0 ? t.scale : (gmax > 0.0 ? gmax : 1.0);
    if (t.metric == CurveMetric::mse) {
      offsets_.push_back(offsets_.back() + static_cast<int>(t.data.x.size()));
      residual_offsets_.push_back(residual_offsets_.back() + static_cast<int>(t.data.x.size()));
    } else if (t.metric == CurveMetric::profile_area) {
      for (std::size_t i = 1; i < t.data.x.size(); ++i)
        if (!(t.data.x[i] > t.data.x[i - 1]))
          throw std::runtime_error("target '" + t.name + "': metric profile_area needs increasing x");
      // Responses: the simulated profile at the target abscissae, then its x-range (2 values).
      offsets_.push_back(offsets_.back() + static_cast<int>(t.data.x.size()) + 2);
      residual_offsets_.push_back(residual_offsets_.back() + 1);
    } else {
      const auto [xmin, xmax] = std::minmax_element(t.data.x.begin(), t.data.x.end());
      p.x_scale = (*xmax - *xmin) > 0.0 ? (*xmax - *xmin) : 1.0;
      p.stations = t.mapping_points > 0 ? t.mapping_points : static_cast<int>(t.data.x.size());
      p.target_stations = equal_arc_length_points(t.data, p.stations, p.x_scale, p.y_scale);
      // Station arc lengths along the target as given (not along its resampled polyline, which
      // cuts corners and would shorten the target at every sharp turn of a loop).
      const double length = polyline_length(t.data, p.x_scale, p.y_scale);
      for (int k = 0; k < p.stations; ++k) p.station_arc.push_back(length * k / (p.stations - 1));
      // The computed curve gets M = 3(K-1)+1 stations (it may be longer than the target; every
      // target station of an identical curve coincides with one) plus its exact length, so arc
      // positions along it are exact and not those of its corner-cutting resampled polyline.
      offsets_.push_back(offsets_.back() + 2 * computed_stations(p.stations) + 1);
      residual_offsets_.push_back(residual_offsets_.back() + 2 * p.stations);
    }
    prepared_.push_back(std::move(p));
  }
}

Eigen::VectorXd CompositeObjective::responses(const CurveSet& curves) const {
  Eigen::VectorXd out(response_size());
  for (std::size_t t = 0; t < targets_.size(); ++t) {
    const auto found = curves.find(targets_[t].curve);
    if (found == curves.end()) throw std::runtime_error("the model produced no curve '" + targets_[t].curve + "'");
    const Curve& curve = found->second;
    if (curve.x.size() != curve.y.size() || curve.x.size() < 2)
      throw std::runtime_error("curve '" + targets_[t].curve + "' has fewer than 2 points");
    for (std::size_t i = 0; i < curve.x.size(); ++i)
      if (!std::isfinite(curve.x[i]) || !std::isfinite(curve.y[i]))
        throw std::runtime_error("curve '" + targets_[t].curve + "' contains a non-finite value");
    std::vector<double> values;
    if (targets_[t].metric == CurveMetric::mse) {
      values = resample_monotone(curve, targets_[t].data.x);
    } else if (targets_[t].metric == CurveMetric::profile_area) {
      values = resample_monotone(curve, targets_[t].data.x);
      const auto [xmin, xmax] = std::minmax_element(curve.x.begin(), curve.x.end());
      if (!(*xmax > targets_[t].data.x.front() && *xmin < targets_[t].data.x.back()))
        throw std::runtime_error("curve '" + targets_[t].curve + "' does not overlap the x-range of target '" +
                                 targets_[t].name + "'");
      values.push_back(*xmin);
      values.push_back(*xmax);
    } else {
      const Prepared& p = prepared_[t];
      values = equal_arc_length_points(curve, computed_stations(p.stations), p.x_scale, p.y_scale);
      values.push_back(polyline_length(curve, p.x_scale, p.y_scale));
    }
    for (std::size_t i = 0; i < values.size(); ++i) out(offsets_[t] + static_cast<int>(i)) = values[i];
  }
  return out;
}

Eigen::VectorXd CompositeObjective::mapping_residuals(const Prepared& p, const double* computed,
                                                      int computed_points) const {
  // Arc positions of the computed stations: equal steps of the stored exact length.
  std::vector<double> arc(computed_points);
  const double stored_length = std::max(computed[2 * computed_points], 0.0);
  for (int i = 0; i < computed_points; ++i) arc[i] = stored_length * i / (computed_points - 1);
  const double target_length = p.station_arc.back();
  const double computed_length = arc.back();
  Eigen::VectorXd r(2 * p.stations);
  auto fill = [&](double offset, double stretch) {
    double total = 0.0;
    for (int k = 0; k < p.stations; ++k) {
      double x = 0.0, y = 0.0;
      point_at(computed, arc, offset + stretch * p.station_arc[k], x, y);
      r(2 * k) = x - p.target_stations[2 * k];
      r(2 * k + 1) = y - p.target_stations[2 * k + 1];
      total += r(2 * k) * r(2 * k) + r(2 * k + 1) * r(2 * k + 1);
    }
    return total;
  };
  if (computed_length <= target_length || target_length <= 0.0) {
    fill(0.0, target_length > 0.0 ? computed_length / target_length : 0.0);
    return r;
  }
  // Best-aligned segment: coarse scan of the offset, then golden-section refinement.
  const double span = computed_length - target_length;
  const int scan = 64;
  int best = 0;
  double best_value = fill(0.0, 1.0);
  for (int i = 1; i <= scan; ++i) {
    const double value = fill(span * i / scan, 1.0);
    if (value < best_value) {
      best_value = value;
      best = i;
    }
  }
  double a = span * std::max(0, best - 1) / scan, b = span * std::min(scan, best + 1) / scan;
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double c = b - golden * (b - a), d = a + golden * (b - a);
    if (fill(c, 1.0) < fill(d, 1.0))
      b = d;
    else
      a = c;
  }
  const double refined = 0.5 * (a + b);
  if (fill(refined, 1.0) > best_value) fill(span * best / scan, 1.0);
  return r;
}

double CompositeObjective::profile_area_residual(const TargetSpec& target, const Prepared& p,
                                                 const double* values) const {
  // Mean gap over the common x-range: area / (length of the common range), scaled by s. A
  // (predicted) range that misses the target's gets the whole target range (ends held flat).
  const std::vector<double>& x = target.data.x;
  const int n = static_cast<int>(x.size());
  double lower = std::max(values[n], x.front()), upper = std::min(values[n + 1], x.back());
  if (!(upper > lower)) {
    lower = x.front();
    upper = x.back();
  }
  return profile_area_between(x, values, target.data.y, lower, upper) / ((upper - lower) * p.y_scale);
}

Eigen::VectorXd CompositeObjective::residuals(const Eigen::VectorXd& responses) const {
  Eigen::VectorXd r(residual_size());
  for (std::size_t t = 0; t < targets_.size(); ++t) {
    const TargetSpec& target = targets_[t];
    const Prepared& p = prepared_[t];
    if (target.metric == CurveMetric::mse) {
      const int n = static_cast<int>(target.data.y.size());
      const double factor = std::sqrt(target.weight / n) / p.y_scale;
      for (int i = 0; i < n; ++i)
        r(residual_offsets_[t] + i) = factor * (responses(offsets_[t] + i) - target.data.y[i]);
    } else if (target.metric == CurveMetric::profile_area) {
      r(residual_offsets_[t]) =
          std::sqrt(target.weight) * profile_area_residual(target, p, responses.data() + offsets_[t]);
    } else {
      const Eigen::VectorXd part = mapping_residuals(p, responses.data() + offsets_[t], computed_stations(p.stations));
      r.segment(residual_offsets_[t], 2 * p.stations) = std::sqrt(target.weight / p.stations) * part;
    }
  }
  return r;
}

std::vector<double> CompositeObjective::target_objectives(const Eigen::VectorXd& responses) const {
  const Eigen::VectorXd r = residuals(responses);
  std::vector<double> out;
  for (std::size_t t = 0; t < targets_.size(); ++t)
    out.push_back(r.segment(residual_offsets_[t], residual_offsets_[t + 1] - residual_offsets_[t]).squaredNorm());
  return out;
}

Curve CompositeObjective::response_curve(const Eigen::VectorXd& responses, int target) const {
  const TargetSpec& t = targets_[target];
  Curve curve{t.data.x_label, t.data.y_label, {}, {}};
  if (t.metric != CurveMetric::curve_mapping) {
    curve.x = t.data.x;
    for (std::size_t i = 0; i < t.data.x.size(); ++i)
      curve.y.push_back(responses(offsets_[target] + static_cast<int>(i)));
  } else {
    const Prepared& p = prepared_[target];
    for (int k = 0; k < computed_stations(p.stations); ++k) {
      curve.x.push_back(responses(offsets_[target] + 2 * k) * p.x_scale);
      curve.y.push_back(responses(offsets_[target] + 2 * k + 1) * p.y_scale);
    }
  }
  return curve;
}

}  // namespace demfit::identify
