#pragma once
// Is a residual noise or structure? Noise level from the data itself, normalised residuals,
// sign-runs and lag-1 autocorrelation tests, a variance-ratio test against the noise level, and
// localisation of the misfit along the curve (docs/diagnose.md gives the formulas).
#include <string>
#include <vector>

namespace demfit::diagnose {

// Standard normal CDF.
double normal_cdf(double z);
// Upper-tail p-value of a chi-square with k degrees of freedom (Wilson-Hilferty cube-root
// normal approximation; relative error of the p-value a few % for k >= 10).
double chi_square_upper_p(double statistic, double k);

// Noise standard deviation of y along a smooth curve, from Gasser-Sroka-Jennen-Steinmetz (1986)
// pseudo-residuals e_i = w_i y_{i-1} + (1-w_i) y_{i+1} - y_i, w_i = (x_{i+1}-x_i)/(x_{i+1}-x_{i-1}),
// sigma^2 = mean( e_i^2 / (w_i^2 + (1-w_i)^2 + 1) ). Unbiased for white noise on a locally linear
// curve. Where x does not change monotonically through i (a turning point) w = 1/2.
// Throws std::runtime_error for fewer than 3 points.
double estimate_noise_sigma(const std::vector<double>& x, const std::vector<double>& y);
// Effective degrees of freedom of that estimate for equally spaced points: (n-2)/1.944 (the
// pseudo-residuals are correlated: lag-1 -2/3, lag-2 1/6, so var(sum e^2) = 1.944 n var(e^2)).
double noise_estimate_dof(int points);

struct RunsTest {
  int positive = 0, negative = 0, runs = 0;
  double z = 0.0;        // (runs - mean) / sd under independence
  double p_value = 1.0;  // one-sided, P(runs <= observed): too few runs = structure
};
// Wald-Wolfowitz runs test on the signs of r (zeros skipped).
RunsTest runs_test(const std::vector<double>& r);

struct AutocorrelationTest {
  double lag1 = 0.0;           // sum r_i r_{i+1} / sum r_i^2
  double durbin_watson = 2.0;  // sum (r_i - r_{i-1})^2 / sum r_i^2 (about 2 (1 - lag1))
  double p_value = 1.0;        // one-sided, positive correlation: 1 - Phi((lag1 + 1/n) sqrt(n))
};
AutocorrelationTest autocorrelation_test(const std::vector<double>& r);

// Upper-tail p-value of an F(d1, d2) ratio (Paulson 1942 cube-root normal approximation);
// d2 <= 0 means d2 = infinity (then it is the chi-square / d1 of Wilson-Hilferty).
double f_upper_p(double ratio, double d1, double d2);

struct VarianceTest {
  double ratio = 1.0;  // (sum r^2 / (n - fitted)) / sigma^2
  double dof_residual = 0.0;
  double dof_noise = 0.0;  // 0 = sigma known (chi-square test), else F-like test
  double p_value = 1.0;    // upper tail: residual larger than the noise
};
// ratio ~ F(n - fitted, dof_noise) under "residual = noise" (dof_noise <= 0: sigma known,
// chi-square test).
VarianceTest variance_test(const std::vector<double>& r, double sigma, int fitted, double dof_noise);

struct SmoothStructureTest {
  int basis = 0;           // Legendre polynomials per segment (degree 0 .. basis-1)
  double statistic = 0.0;  // |projection of r/sigma on the basis|^2
  double p_value = 1.0;    // F(basis total, dof_noise) upper tail of statistic / basis total
};
// Lack-of-fit against a smooth alternative: the normalised residual projected on Legendre
// polynomials P_0..P_{K-1} of each segment's abscissa (K = min(8, n/4); x-based when x is
// monotone, index-based on loops). Far more power than runs/lag-1 against slow, smooth misfit
// (e.g. an effect half-absorbed by a wrong candidate). Conservative: the fitted parameters
// already remove part of the basis, so the true dof is below K.
SmoothStructureTest smooth_structure_test(const std::vector<std::vector<double>>& x,
                                          const std::vector<std::vector<double>>& normalised, double dof_noise);

struct RegionStats {
  std::string label;       // e.g. "response: x 0..0.33 (first third)"
  int begin = 0, end = 0;  // index range in the residual vector [begin, end)
  double rms = 0.0, max_abs = 0.0;
  double rms_over_sigma = 0.0, max_over_sigma = 0.0;  // by the noise level of the region's target
  double x_at_max = 0.0;
};

struct ResidualAnalysis {
  double sigma = 0.0;  // noise level used (estimated or given), per-point units
  int points = 0;
  int fitted_parameters = 0;
  double rms = 0.0, max_abs = 0.0;  // pooled in y units: meaningful for one target only
  // Every target normalised by its own noise level (r_i / sigma_target), then pooled: the columns
  // reported for several targets with different units.
  double rms_over_sigma = 0.0, max_over_sigma = 0.0;
  RunsTest runs;
  AutocorrelationTest autocorrelation;
  VarianceTest variance;
  SmoothStructureTest smooth;
  double alpha = 0.01;      // family-wise level; each of the 4 tests at alpha/4 (Bonferroni)
  bool structural = false;  // some test rejects "residual = noise"
  std::vector<RegionStats> regions;
  int worst_region = -1;  // largest rms_over_sigma
};

// A residual segment of one target: residuals (model - data) in y units, the data x, the noise
// level of that target and its name.
struct ResidualSegment {
  std::string target;
  std::vector<double> x;
  std::vector<double> residual;
  double sigma = 1.0;
};

// Tests on the concatenated normalised residuals r/sigma of all segments. Regions: each target is
// split into its branches (where x reverses), each branch into thirds.
ResidualAnalysis analyse_residuals(const std::vector<ResidualSegment>& segments, int fitted_parameters,
                                   double dof_noise, double alpha);

// True when the lag-1 autocorrelation test is the only one of the four that rejects "residual =
// noise" at alpha/4. A right model can fail that test alone when the data are one realisation of a
// flow as chaotic as the model's: the noise model counts one run's scatter, the residual carries two
// (docs/diagnose.md, "What the noise model leaves out").
bool fails_only_autocorrelation(const ResidualAnalysis& analysis);

}  // namespace demfit::diagnose
