// Posterior sampling on the local linear surrogate of the residuals (uncertainty.hpp):
// correlated simulation noise estimated from the runs, data noise from what the best fit
// leaves, uniform prior on the bounds, Gibbs sampling of the truncated normal posterior.
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

#include "demfit/identify/gnuplot.hpp"
#include "demfit/identify/uncertainty.hpp"
#include "study_support.hpp"

namespace demfit::identify {
namespace {

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

// One draw of N(mean, sd²) truncated to [0, 1] by the inverse CDF (clamped in the far tails,
// where the truncated mass sits at the nearer bound).
double truncated_normal_unit(double mean, double sd, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  if (!(sd > 0.0) || !std::isfinite(sd) || sd > 1e6) return uniform(rng);
  const double a = normal_cdf((0.0 - mean) / sd), b = normal_cdf((1.0 - mean) / sd);
  if (!(b - a > 1e-300)) return mean < 0.0 ? 0.0 : 1.0;
  const double p = std::clamp(a + uniform(rng) * (b - a), 1e-300, 1.0 - 1e-16);
  return std::clamp(mean + sd * normal_quantile(p), 0.0, 1.0);
}

double unit_to_physical(const VariableSpec& v, double u) {
  return rbf_surrogate::from_unit(detail::rbf_variable(v), u);
}

// The Gaussian part of the log posterior in unit coordinates: −½ (u − u0)ᵀ P (u − u0) up to a
// constant, from the regression r(u) ≈ b0 + J (u − u_best) and the noise covariance Σ.
struct GaussianPosterior {
  Eigen::MatrixXd precision;  // P = Jᵀ Σ⁻¹ J
  Eigen::VectorXd linear;     // P u0 (u0 need not exist when P is singular)
  double ssr_min = 0.0;       // min over u (unbounded) of |b0 + J du|², unweighted
};

GaussianPosterior fit_posterior(const RunSample& s, const PosteriorOptions& o, PosteriorEstimate& out) {
  const int m = static_cast<int>(s.unit_points.rows()), n = static_cast<int>(s.unit_points.cols());
  const int N = static_cast<int>(s.residuals.cols());
  Eigen::MatrixXd X(m, n + 1);
  X.col(0).setOnes();
  for (int i = 0; i < m; ++i) X.row(i).tail(n) = s.unit_points.row(i) - s.best_unit.transpose();
  const Eigen::MatrixXd B = X.colPivHouseholderQr().solve(s.residuals);  // (n+1) x N
  const Eigen::MatrixXd E = s.residuals - X * B;
  const Eigen::VectorXd b0 = B.row(0).transpose();
  const Eigen::MatrixXd J = B.bottomRows(n).transpose();  // N x n
  const int dof = std::max(1, m - n - 1);
  // Σ_sim = (1 − λ) EᵀE/dof + λ tr(EᵀE/dof)/N I is N x N for N curve points: a 20,000-point
  // target would need 3 GB and O(N³) work. It is a rank-m update of a multiple of I, so every
  // product below goes through the m x m Woodbury form instead, O(m² N).
  const double sim_trace = E.squaredNorm() / dof;  // tr(EᵀE/dof)
  const double sim_mean = sim_trace / N;
  const double update_scale = (1.0 - o.shrinkage) / dof;
  // Unweighted least squares of the linear surrogate (minimum-norm step for rank-deficient J).
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(J);
  const Eigen::VectorXd step = cod.solve(-b0);
  GaussianPosterior g;
  g.ssr_min = (b0 + J * step).squaredNorm();
  // E[SSR_min] = tr(M Σ_sim) + σ_w² tr(M), M = I − J J⁺ the residual projector: the fit absorbs the
  // part of the smooth simulation noise that looks like a parameter change, so only tr(M Σ_sim) of
  // it is left in SSR_min (subtracting all of tr Σ_sim measured σ_w² = 0 on most seeds).
  // tr(J J⁺ EᵀE) = tr((E J)(J⁺ Eᵀ)).
  const Eigen::MatrixXd EJ = E * J;  // m x n
  const double rank = static_cast<double>(cod.rank());
  const double residual_sim = sim_trace - (EJ * cod.solve(E.transpose())).trace() / dof;
  const double white = std::max(0.0, (g.ssr_min - residual_sim) / std::max(1.0, N - rank));
  out.simulation_noise_variance = sim_mean;
  out.data_noise_variance = white;
  // Σ = a I + s EᵀE, a = λ·mean + σ_w² (+ a floor), s = (1 − λ)/dof.
  // Woodbury: Σ⁻¹ = (I − Eᵀ (a/s I + E Eᵀ)⁻¹ E) / a.
  const double a = o.shrinkage * sim_mean + white + 1e-12 * std::max(sim_mean, 1e-300);
  const Eigen::VectorXd Eb0 = E * b0;
  Eigen::MatrixXd JtSiJ = J.transpose() * J;
  Eigen::VectorXd JtSib0 = J.transpose() * b0;
  if (update_scale > 0.0) {
    Eigen::MatrixXd K = E * E.transpose();
    K.diagonal().array() += a / update_scale;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(K);
    JtSiJ -= EJ.transpose() * ldlt.solve(EJ);
    JtSib0 -= EJ.transpose() * ldlt.solve(Eb0);
  }
  g.precision = JtSiJ / a;
  // −½|a + A(u − u_best)|² = −½ uᵀPu + uᵀ(P u_best − Aᵀa) + const, in whitened terms
  g.linear = g.precision * s.best_unit - JtSib0 / a;
  return g;
}

double quantile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const double pos = p * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

}  // namespace

PosteriorEstimate sample_posterior_from_runs(const RunSample& s, const std::vector<VariableSpec>& variables,
                                             const PosteriorOptions& o) {
  const int m = static_cast<int>(s.unit_points.rows()), n = static_cast<int>(variables.size());
  if (s.unit_points.cols() != n || s.residuals.rows() != m || s.best_unit.size() != n)
    throw std::invalid_argument("posterior: run sample and variables have different sizes");
  if (m < n + 3) throw std::invalid_argument("posterior: needs at least n + 3 runs near the optimum");
  PosteriorEstimate out;
  out.runs_used = m;
  const GaussianPosterior g = fit_posterior(s, o, out);
  // Gibbs sampling: u_j | rest ~ N((linear_j − Σ_{k≠j} P_jk u_k) / P_jj, 1/P_jj) truncated to [0, 1].
  std::mt19937_64 rng(o.seed);
  Eigen::VectorXd u = s.best_unit.cwiseMax(0.0).cwiseMin(1.0);
  std::vector<std::vector<double>> kept(n);
  const int keep_every = std::max(1, o.draws / 2000);
  Eigen::MatrixXd draws(0, n);
  std::vector<Eigen::VectorXd> plotted;
  for (int it = 0; it < o.burn_in + o.draws; ++it) {
    for (int j = 0; j < n; ++j) {
      const double pjj = g.precision(j, j);
      const double rest = g.precision.row(j).dot(u) - pjj * u(j);
      u(j) = pjj > 1e-300 ? truncated_normal_unit((g.linear(j) - rest) / pjj, 1.0 / std::sqrt(pjj), rng)
                          : truncated_normal_unit(0.5, INFINITY, rng);
    }
    if (it < o.burn_in) continue;
    for (int j = 0; j < n; ++j) kept[j].push_back(u(j));
    if ((it - o.burn_in) % keep_every == 0) plotted.push_back(u);
  }
  const double tail = 0.5 * (1.0 - o.confidence);
  Eigen::MatrixXd unit_draws(static_cast<Eigen::Index>(kept[0].size()), n);
  for (int j = 0; j < n; ++j) {
    unit_draws.col(j) = Eigen::Map<const Eigen::VectorXd>(kept[j].data(), static_cast<Eigen::Index>(kept[j].size()));
    const double lo = quantile(kept[j], tail), hi = quantile(kept[j], 1.0 - tail);
    out.lower.push_back(unit_to_physical(variables[j], lo));
    out.upper.push_back(unit_to_physical(variables[j], hi));
    out.median.push_back(unit_to_physical(variables[j], quantile(kept[j], 0.5)));
    out.unidentifiable.push_back(hi - lo > 0.5);
  }
  const Eigen::MatrixXd centred = unit_draws.rowwise() - unit_draws.colwise().mean();
  const Eigen::MatrixXd cov = centred.transpose() * centred / std::max<Eigen::Index>(1, centred.rows() - 1);
  const Eigen::VectorXd sd = cov.diagonal().cwiseMax(1e-300).cwiseSqrt();
  out.correlation = cov.cwiseQuotient(sd * sd.transpose());
  out.draws.resize(static_cast<Eigen::Index>(plotted.size()), n);
  for (std::size_t i = 0; i < plotted.size(); ++i)
    for (int j = 0; j < n; ++j)
      out.draws(static_cast<Eigen::Index>(i), j) = unit_to_physical(variables[j], plotted[i](j));
  return out;
}

std::string write_posterior_pair_plot(const PosteriorEstimate& e, const std::vector<VariableSpec>& variables,
                                      const std::filesystem::path& png) {
  if (!gnuplot_available()) return "gnuplot not found on the PATH; no pair plot";
  const int n = static_cast<int>(variables.size());
  std::ostringstream g;
  g.precision(10);
  // Inline data blocks ($draws), one multiplot panel per pair: histogram on the diagonal, draws
  // below it, the 95 % interval as dashed lines.
  g << "$draws << EOD\n";
  for (Eigen::Index i = 0; i < e.draws.rows(); ++i) {
    for (int j = 0; j < n; ++j) g << (j ? " " : "") << e.draws(i, j);
    g << "\n";
  }
  g << "EOD\n";
  g << "set multiplot layout " << n << "," << n << " title 'posterior draws (95 % intervals dashed)'\n";
  g << "set key off\nset tics font ',7'\n";
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      g << "unset arrow\nset xlabel " << gnuplot_quote(variables[c].name) << " font ',8'\n";
      if (c > r) {
        g << "unset border\nunset tics\nunset xlabel\nunset ylabel\nplot [0:1][0:1] NaN notitle\nset border\nset "
             "tics\n";
        continue;
      }
      // Panels span the draws (padded 5 %), not the bounds: a well-pinned parameter would be a spike.
      const auto span = [&](int j, double& lo, double& hi) {
        lo = e.draws.col(j).minCoeff();
        hi = e.draws.col(j).maxCoeff();
        const double pad = 0.05 * std::max(hi - lo, 1e-12 * std::max(1.0, std::abs(hi)));
        lo -= pad;
        hi += pad;
      };
      double lo = 0, hi = 0, ylo = 0, yhi = 0;
      span(c, lo, hi);
      span(r, ylo, yhi);
      g << "set tics font ',7'\nset xrange [" << lo << ":" << hi << "]\n";
      if (r == c) {
        const double width = (hi - lo) / 40.0;
        g << "set ylabel 'draws' font ',8'\nset yrange [*:*]\n"
          << "set arrow from " << e.lower[c] << ", graph 0 to " << e.lower[c] << ", graph 1 nohead dt 2\n"
          << "set arrow from " << e.upper[c] << ", graph 0 to " << e.upper[c] << ", graph 1 nohead dt 2\n"
          << "plot $draws using (" << width << "*floor(($" << c + 1 << ")/" << width << ")+" << width / 2
          << "):(1.0) smooth frequency with boxes\n";
      } else {
        g << "set ylabel " << gnuplot_quote(variables[r].name) << " font ',8'\n"
          << "set yrange [" << ylo << ":" << yhi << "]\n"
          << "plot $draws using " << c + 1 << ":" << r + 1 << " with dots\n";
      }
    }
  g << "unset multiplot\n";
  return gnuplot_png(png, g.str());
}

}  // namespace demfit::identify
