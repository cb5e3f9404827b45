#pragma once
// Curve metrics (docs/spec.md 3) as a map: simulated curves -> fixed-length response vector ->
// residual vector r with objective = |r|^2. Fixed length matters: every run then has the same
// number of RBF outputs, and the objective of a *predicted* response vector is computed by the
// same code as that of a simulated one.
//
// mse target (P points): responses = simulated y interpolated at the target abscissae
//   (linear; the simulated x must be monotone, either direction; outside the simulated x-range
//   the end values are held flat, so a curve that stops short is penalised by its flat tail).
//   r_p = sqrt(w/P) (f_p - G_p)/s,  s = "scale" or max|G|  ->  w * (1/P) sum ((f_p-G_p)/s)^2.
// curve_mapping target (K stations): responses = M = 3(K-1)+1 points at equal arc length along
//   the simulated curve (normalised coordinates: x by the target's x-range, y by s) and its
//   length. The residual
//   matches the K equal-arc-length stations of the target with the segment of the computed
//   curve of equal arc length, starting at the offset that minimises the distance (searched);
//   a computed curve shorter than the target is stretched onto it. r = sqrt(w/K)(dx_k, dy_k),
//   i.e. w times the mean squared distance between matched stations (an area-per-length).
// profile_area target (P points, x increasing; free-surface profiles z(x)): responses = the
//   simulated z at the target abscissae (as mse) plus the simulated x-range [a, b]. On the common
//   x-range [lo, hi] = [max(a, x_1), min(b, x_P)] the simulated profile is taken as linear between
//   the target abscissae and A = integral |f - G| dx (exact for piecewise linear gaps, also
//   where they cross): the area between the profiles (mm^2 for x_mm, z_mm curves).
//   r = sqrt(w) A / ((hi - lo) s): the mean gap over the common range in units of s, so the term
//   w (A / ((hi - lo) s))^2 is comparable to an mse term ((RMS gap / s)^2).
// Several targets: objective = sum of the weighted target terms.
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demfit/identify/model.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::identify {

// Linear interpolation of a monotone curve at the given abscissae, flat outside its range.
// Throws std::runtime_error if x is not monotone or the curve has fewer than 2 points.
std::vector<double> resample_monotone(const Curve& curve, const std::vector<double>& at_x);

// `count` points at equal arc length along the polyline (x_i/x_scale, y_i/y_scale); returns
// them in normalised coordinates, interleaved x0,y0,x1,y1,...
std::vector<double> equal_arc_length_points(const Curve& curve, int count, double x_scale, double y_scale);

// Integral of |f - g| dx over [lower, upper] for f, g given at the abscissae x (increasing) and
// linear in between (exact also where f - g changes sign); segments outside are skipped.
double profile_area_between(const std::vector<double>& x, const double* f, const std::vector<double>& g, double lower,
                            double upper);

class CompositeObjective {
 public:
  explicit CompositeObjective(std::vector<TargetSpec> targets);

  int response_size() const { return offsets_.back(); }
  int residual_size() const { return residual_offsets_.back(); }
  const std::vector<TargetSpec>& targets() const { return targets_; }

  // Simulated curves -> responses. Throws std::runtime_error when a curve is missing,
  // non-finite, too short or (mse) not monotone in x.
  Eigen::VectorXd responses(const CurveSet& curves) const;
  Eigen::VectorXd residuals(const Eigen::VectorXd& responses) const;
  double objective(const Eigen::VectorXd& responses) const { return residuals(responses).squaredNorm(); }
  // Weighted contribution of each target to the objective.
  std::vector<double> target_objectives(const Eigen::VectorXd& responses) const;
  // The part of a response vector that belongs to one target, as a curve in the target's
  // units (for plots of predicted curves).
  Curve response_curve(const Eigen::VectorXd& responses, int target) const;

 private:
  struct Prepared {
    double y_scale = 1.0;
    double x_scale = 1.0;                 // curve mapping: x normalisation
    int stations = 0;                     // curve mapping: target stations K
    std::vector<double> target_stations;  // normalised, interleaved
    std::vector<double> station_arc;      // arc length of each target station
  };
  Eigen::VectorXd mapping_residuals(const Prepared& p, const double* computed, int computed_points) const;
  double profile_area_residual(const TargetSpec& target, const Prepared& p, const double* values) const;

  std::vector<TargetSpec> targets_;
  std::vector<Prepared> prepared_;
  std::vector<int> offsets_{0};
  std::vector<int> residual_offsets_{0};
};

}  // namespace demfit::identify
