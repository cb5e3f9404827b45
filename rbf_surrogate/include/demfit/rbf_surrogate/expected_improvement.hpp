#pragma once
// Expected-improvement infill on a kriging model (Jones, Schonlau & Welch 1998):
//   EI(x) = (f_min − m) Φ(z) + s φ(z),  z = (f_min − m) / s,
// with m, s the kriging mean and standard deviation. EI is maximised as log EI (an asymptotic form
// for z < −20 keeps far-away candidates ranked instead of all underflowing to 0).
#include "demfit/rbf_surrogate/kriging.hpp"

#include <cstdint>
#include <vector>

namespace demfit::rbf_surrogate {

double expected_improvement(double mean, double standard_deviation, double best);
double log_expected_improvement(double mean, double standard_deviation, double best);

struct AcquisitionOptions {
  int candidates = 0;           // 0: clamp(400·d, 2000, 4000)
  double local_fraction = 0.5;  // share of candidates perturbing the incumbent (rest uniform)
  int local_starts = 3;         // BOBYQA polishing runs from the best distinct candidates (0: none)
  int local_evaluations = 150;  // per polishing run
  // Points closer than excluded_radius to one of excluded_centres are never proposed.
  std::vector<VectorXd> excluded_centres;
  double excluded_radius = 0.0;
  // Failed runs (no value, so invisible to the model): no point closer than failed_radius to one
  // of them is proposed (the EI strategy sets them; a failure region is otherwise explored as
  // "uncertain" again and again).
  std::vector<VectorXd> failed_points;
  double failed_radius = 0.0;
};

struct AcquisitionResult {
  VectorXd x;  // unit coordinates, inside the region
  double log_ei = 0.0;
};

// Maximises EI of `model` relative to `best` over `region`. Candidates: uniform points of the region
// and Gaussian perturbations of `incumbent` (σ = 20 %, 5 %, 1 %, 0.2 % of the region), then BOBYQA
// from the best ones. Deterministic for a seed.
AcquisitionResult maximise_expected_improvement(const KrigingModel& model, double best, const VectorXd& incumbent,
                                                const Box& region, std::uint64_t seed,
                                                const AcquisitionOptions& options = {});

}  // namespace demfit::rbf_surrogate
