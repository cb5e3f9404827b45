// Residual statistics; formulas and references in residual_tests.hpp and docs/diagnose.md.
#include "demfit/diagnose/residual_tests.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <Eigen/Dense>

namespace demfit::diagnose {

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

double chi_square_upper_p(double statistic, double k) {
  if (k <= 0.0) return 1.0;
  if (statistic <= 0.0) return 1.0;
  // Wilson & Hilferty (1931): (X/k)^(1/3) is nearly normal, mean 1 - 2/(9k), variance 2/(9k).
  const double v = 2.0 / (9.0 * k);
  const double z = (std::cbrt(statistic / k) - (1.0 - v)) / std::sqrt(v);
  return 1.0 - normal_cdf(z);
}

double f_upper_p(double ratio, double d1, double d2) {
  if (ratio <= 0.0 || d1 <= 0.0) return 1.0;
  // Paulson (1942): with a = 2/(9 d1), b = 2/(9 d2),
  // z = ((1 - b) F^(1/3) - (1 - a)) / sqrt(a + b F^(2/3)) is nearly standard normal.
  const double a = 2.0 / (9.0 * d1), b = d2 > 0.0 ? 2.0 / (9.0 * d2) : 0.0;
  const double c = std::cbrt(ratio);
  const double z = ((1.0 - b) * c - (1.0 - a)) / std::sqrt(a + b * c * c);
  return 1.0 - normal_cdf(z);
}

double estimate_noise_sigma(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = y.size();
  if (n < 3 || x.size() != n) throw std::runtime_error("noise estimate: needs at least 3 points with x and y");
  double sum = 0.0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double span = x[i + 1] - x[i - 1];
    double w = 0.5;
    const bool monotone = (x[i] - x[i - 1]) * (x[i + 1] - x[i]) > 0.0;
    if (monotone && span != 0.0) w = (x[i + 1] - x[i]) / span;
    const double e = w * y[i - 1] + (1.0 - w) * y[i + 1] - y[i];
    sum += e * e / (w * w + (1.0 - w) * (1.0 - w) + 1.0);
  }
  return std::sqrt(sum / static_cast<double>(n - 2));
}

double noise_estimate_dof(int points) { return std::max(1.0, (points - 2) / 1.944); }

RunsTest runs_test(const std::vector<double>& r) {
  RunsTest t;
  int previous = 0;
  for (double v : r) {
    if (v == 0.0) continue;
    const int sign = v > 0.0 ? 1 : -1;
    (sign > 0 ? t.positive : t.negative)++;
    if (sign != previous) ++t.runs;
    previous = sign;
  }
  const double n1 = t.positive, n2 = t.negative, n = n1 + n2;
  if (n1 == 0 || n2 == 0) {
    // One sign only: as few runs as possible. With n >= 8 this alone is significant.
    t.z = -std::sqrt(std::max(n, 1.0));
    t.p_value = n >= 2 ? std::pow(0.5, n - 1) : 1.0;
    return t;
  }
  const double mean = 2.0 * n1 * n2 / n + 1.0;
  const double var = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n * n * (n - 1.0));
  // Continuity correction +0.5: runs is an integer.
  t.z = var > 0.0 ? (t.runs - mean + 0.5) / std::sqrt(var) : 0.0;
  t.p_value = normal_cdf(t.z);
  return t;
}

AutocorrelationTest autocorrelation_test(const std::vector<double>& r) {
  AutocorrelationTest t;
  const std::size_t n = r.size();
  double ss = 0.0, lag = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    ss += r[i] * r[i];
    if (i > 0) {
      lag += r[i] * r[i - 1];
      diff += (r[i] - r[i - 1]) * (r[i] - r[i - 1]);
    }
  }
  if (n < 3 || ss <= 0.0) return t;
  t.lag1 = lag / ss;
  t.durbin_watson = diff / ss;
  // White noise: lag-1 autocorrelation ~ N(-1/n, 1/n) (Bartlett).
  t.p_value = 1.0 - normal_cdf((t.lag1 + 1.0 / n) * std::sqrt(static_cast<double>(n)));
  return t;
}

VarianceTest variance_test(const std::vector<double>& r, double sigma, int fitted, double dof_noise) {
  VarianceTest t;
  double ss = 0.0;
  for (double v : r) ss += v * v;
  t.dof_residual = std::max(1.0, static_cast<double>(r.size()) - fitted);
  t.dof_noise = dof_noise;
  t.ratio = ss / t.dof_residual / (sigma * sigma);
  t.p_value = f_upper_p(t.ratio, t.dof_residual, dof_noise);
  return t;
}

SmoothStructureTest smooth_structure_test(const std::vector<std::vector<double>>& x,
                                          const std::vector<std::vector<double>>& normalised, double dof_noise) {
  SmoothStructureTest t;
  int total = 0;
  for (std::size_t s = 0; s < x.size(); ++s) {
    const int n = static_cast<int>(normalised[s].size());
    const int k = std::min(8, n / 4);
    if (k < 1) continue;
    bool increasing = true, decreasing = true;
    for (int i = 1; i < n; ++i) {
      increasing = increasing && x[s][i] > x[s][i - 1];
      decreasing = decreasing && x[s][i] < x[s][i - 1];
    }
    const double lo = *std::min_element(x[s].begin(), x[s].end()), hi = *std::max_element(x[s].begin(), x[s].end());
    Eigen::MatrixXd basis(n, k);
    Eigen::VectorXd r(n);
    for (int i = 0; i < n; ++i) {
      const double u = (increasing || decreasing) && hi > lo ? 2.0 * (x[s][i] - lo) / (hi - lo) - 1.0
                                                             : (n > 1 ? 2.0 * i / (n - 1) - 1.0 : 0.0);
      // Legendre recurrence: (m+1) P_{m+1} = (2m+1) u P_m - m P_{m-1}.
      double p_prev = 1.0, p = u;
      basis(i, 0) = 1.0;
      if (k > 1) basis(i, 1) = u;
      for (int m = 1; m + 1 < k; ++m) {
        const double next = ((2.0 * m + 1.0) * u * p - m * p_prev) / (m + 1.0);
        p_prev = p;
        p = next;
        basis(i, m + 1) = p;
      }
      r(i) = normalised[s][i];
    }
    // Orthonormal basis of the span (QR), so the projection is |Q' r|^2.
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(basis);
    const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(n, k);
    t.statistic += (q.transpose() * r).squaredNorm();
    total += k;
  }
  t.basis = total;
  if (total > 0) t.p_value = f_upper_p(t.statistic / total, total, dof_noise);
  return t;
}

namespace {

std::string region_label(const ResidualSegment& s, int begin, int end, std::pair<int, int> branch, int third,
                         bool several_branches) {
  static const char* names[] = {"first third", "middle third", "last third"};
  std::string branch_text;
  if (several_branches)
    branch_text = s.x[branch.second - 1] >= s.x[branch.first] ? " x-increasing branch" : " x-decreasing branch";
  char buffer[240];
  std::snprintf(buffer, sizeof buffer, "%s%s: x %.4g..%.4g (%s)", s.target.c_str(), branch_text.c_str(), s.x[begin],
                s.x[end - 1], names[third]);
  return buffer;
}

// Branches: maximal index ranges over which x moves in one direction.
std::vector<std::pair<int, int>> branches_of(const std::vector<double>& x) {
  std::vector<std::pair<int, int>> out;
  const int n = static_cast<int>(x.size());
  int start = 0, direction = 0;
  for (int i = 1; i < n; ++i) {
    const double d = x[i] - x[i - 1];
    const int dir = d > 0 ? 1 : (d < 0 ? -1 : 0);
    if (dir == 0) continue;
    if (direction != 0 && dir != direction) {
      out.push_back({start, i});
      start = i;
    }
    direction = dir;
  }
  out.push_back({start, n});
  return out;
}

}  // namespace

ResidualAnalysis analyse_residuals(const std::vector<ResidualSegment>& segments, int fitted_parameters,
                                   double dof_noise, double alpha) {
  ResidualAnalysis a;
  a.alpha = alpha;
  a.fitted_parameters = fitted_parameters;
  std::vector<double> normalised;
  double ss = 0.0, sigma_ss = 0.0;
  int offset = 0;
  for (const auto& s : segments) {
    const int n = static_cast<int>(s.residual.size());
    for (int i = 0; i < n; ++i) {
      normalised.push_back(s.residual[i] / s.sigma);
      ss += s.residual[i] * s.residual[i];
      a.max_abs = std::max(a.max_abs, std::abs(s.residual[i]));
    }
    sigma_ss += s.sigma * s.sigma * n;
    const auto branches = branches_of(s.x);
    for (std::size_t br = 0; br < branches.size(); ++br) {
      const auto [b0, b1] = branches[br];
      for (int third = 0; third < 3; ++third) {
        const int begin = b0 + (b1 - b0) * third / 3, end = b0 + (b1 - b0) * (third + 1) / 3;
        if (end <= begin) continue;
        RegionStats r;
        r.label = region_label(s, begin, end, branches[br], third, branches.size() > 1);
        r.begin = offset + begin;
        r.end = offset + end;
        double rss = 0.0;
        for (int i = begin; i < end; ++i) {
          rss += s.residual[i] * s.residual[i];
          if (std::abs(s.residual[i]) >= r.max_abs) {
            r.max_abs = std::abs(s.residual[i]);
            r.x_at_max = s.x[i];
          }
        }
        r.rms = std::sqrt(rss / (end - begin));
        r.rms_over_sigma = r.rms / s.sigma;
        r.max_over_sigma = r.max_abs / s.sigma;
        a.regions.push_back(r);
      }
    }
    offset += n;
  }
  a.points = static_cast<int>(normalised.size());
  if (a.points == 0) throw std::runtime_error("residual analysis: no residual points");
  a.rms = std::sqrt(ss / a.points);
  a.sigma = std::sqrt(sigma_ss / a.points);
  double nss = 0.0;
  for (double r : normalised) {
    nss += r * r;
    a.max_over_sigma = std::max(a.max_over_sigma, std::abs(r));
  }
  a.rms_over_sigma = std::sqrt(nss / a.points);
  a.runs = runs_test(normalised);
  a.autocorrelation = autocorrelation_test(normalised);
  a.variance = variance_test(normalised, 1.0, fitted_parameters, dof_noise);
  std::vector<std::vector<double>> xs, rs;
  std::size_t k = 0;
  for (const auto& s : segments) {
    xs.push_back(s.x);
    rs.emplace_back(normalised.begin() + k, normalised.begin() + k + s.residual.size());
    k += s.residual.size();
  }
  a.smooth = smooth_structure_test(xs, rs, dof_noise);
  const double per_test = alpha / 4.0;  // Bonferroni over the four tests
  a.structural = a.runs.p_value < per_test || a.autocorrelation.p_value < per_test || a.variance.p_value < per_test ||
                 a.smooth.p_value < per_test;
  for (std::size_t i = 0; i < a.regions.size(); ++i)
    if (a.worst_region < 0 || a.regions[i].rms_over_sigma > a.regions[a.worst_region].rms_over_sigma)
      a.worst_region = static_cast<int>(i);
  return a;
}

bool fails_only_autocorrelation(const ResidualAnalysis& a) {
  const double per_test = a.alpha / 4.0;  // as in analyse_residuals
  return a.autocorrelation.p_value < per_test && a.runs.p_value >= per_test && a.variance.p_value >= per_test &&
         a.smooth.p_value >= per_test;
}

}  // namespace demfit::diagnose
