#pragma once
// A small surrogate-based minimisation driver: design -> fit -> optimise -> infill, with SRSM
// domain reduction (LS-OPT-like), adaptive (stochastic-RBF) infill or kriging expected improvement.
// It is a thin in-memory driver over the ask/tell strategies of strategy.hpp (the same objects
// identify's study loop drives). Used by tests and bench.
#include "demfit/rbf_surrogate/expected_improvement.hpp"
#include "demfit/rbf_surrogate/kriging.hpp"
#include "demfit/rbf_surrogate/multi_fidelity.hpp"
#include "demfit/rbf_surrogate/optimize.hpp"
#include "demfit/rbf_surrogate/rbf_network.hpp"
#include "demfit/rbf_surrogate/srsm.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace demfit::rbf_surrogate {

// srsm: LS-OPT-like domain reduction; adaptive: stochastic-RBF candidates (Regis & Shoemaker 2007);
// expected_improvement: one point per iteration maximising the kriging expected improvement, with
// model selection, output warping and basin exclusion (README; expected_improvement.hpp) — the
// fewest evaluations on every bench_rbf_surrogate problem.
enum class InfillStrategy { srsm, adaptive, expected_improvement };

// Transform of the values before the kriging fit (expected_improvement strategy): none, log
// (w = log(y − min y + δ), δ = 10 % of median − min) or automatic (the one with the larger
// likelihood of the raw values, Jacobian included; chosen again at every fit).
enum class OutputWarp { none, log, automatic };

struct ExpensiveOptions {
  InfillStrategy strategy = InfillStrategy::srsm;
  int max_evaluations = 100;
  int initial_points = 0;        // 0: 2(n+1); expected_improvement n+1
  int points_per_iteration = 0;  // batch size; 0: srsm 1.5(n+1)+1 rounded up (docs/spec.md 3), others 1
  std::uint64_t seed = 1;
  RbfOptions rbf;
  SrsmSettings srsm;
  MinimizeOptions minimize{.global_evaluations = 600, .local_starts = 3};
  std::optional<double> target;  // stop once a value <= target has been evaluated
  // Fit the surrogate to min(y, median(y)) (Regis & Shoemaker 2007): large values far from the
  // optimum (Rosenbrock-like ranges) otherwise dominate the fit and its width.
  bool clip_above_median = false;
  // SRSM strategy: centre the next subregion on the best point run so far (the predicted optimum
  // when it is the best, which is the usual case); false = always the predicted optimum (LS-OPT).
  bool recentre_on_best = true;
  // expected_improvement strategy. The nugget is estimated when kriging.estimate_noise or
  // rbf.smoothing is set (noisy values); the incumbent is then the lowest predicted mean at a run point.
  KrigingOptions kriging;
  AcquisitionOptions acquisition;
  // Every exploit_every-th point is the minimiser of the kriging mean instead of the EI maximiser
  // (pure exploitation); 0: EI only (k = 2, 3, 4 measured no better on Hartmann-6).
  int exploit_every = 0;
  OutputWarp output_warp = OutputWarp::automatic;
  // Runs of a cheaper level of the same response (unit points, values; ≥ 2 runs, else ignored):
  // the expected_improvement strategy then models the values as ρ·m_cheap(x) + a kriging
  // correction (multi_fidelity.hpp; ρ by maximum likelihood at every fit) and proposes points by
  // EI on that model. The output warp, when allowed, is log y on both levels (all values
  // positive; otherwise none), chosen by likelihood as for one level. Told points are of the
  // expensive level only.
  FidelityLevel lower_fidelity;
  // Fit both kriging kernels (Matérn-5/2 and Gaussian) and use the more likely one at each fit.
  bool select_kernel = true;
  // After stall_evaluations points without a 0.1 % improvement the incumbent's basin (a ball of
  // radius stall_exclusion_radius·√n, unit coordinates) is excluded and EI continues on the rest of
  // the domain against the best value found there; a basin there that stalls is excluded too.
  // The exclusions are dropped after 7 stall lengths without improvement. 0: never.
  int stall_evaluations = 12;
  double stall_exclusion_radius = 0.35;
  // Batches of q > 1 expected-improvement points (kriging believer) without trust regions: the last
  // point of each batch is the minimiser of the believer-updated kriging mean when batch_exploit is set (bench, q = 4,
  // 5 seeds: Hartmann-6 median 53 instead of 67 evaluations, Branin 31 instead of 32; the constant
  // liar instead of the believer: Hartmann-6 67, one run failing).
  bool batch_exploit = true;
  // Value assumed at a chosen batch point: the kriging mean (believer) or the lowest value so far
  // (constant liar "min", Ginsbourger et al. 2010).
  bool constant_liar = false;
  // Batches: the last min(q − 1, batch_trust_regions) points maximise the believer-updated EI inside
  // boxes around the incumbent of half-width trust_region_half_width·2^j, j = 0, 1, … (unit coordinates;
  // batch_exploit is then unused): several step lengths of the local descent tried at once (bench,
  // q = 4, 20 seeds: Hartmann-6 median 39 instead of 51 with batch_exploit). 0: off.
  int batch_trust_regions = 3;
  double trust_region_half_width = 0.05;
};

struct ExpensiveResult {
  VectorXd x;          // best evaluated point, physical units
  double value = 0.0;  // best evaluated value
  int evaluations = 0;
  MatrixXd points;                  // all evaluated points, physical units (rows)
  VectorXd values;                  // all evaluated values, in evaluation order
  std::vector<double> best_so_far;  // best value after each evaluation
  std::string stop_reason;          // "target reached" or "evaluation budget reached"
};

// f receives physical coordinates (see Variable). Deterministic for a given seed.
ExpensiveResult minimise_expensive(const std::function<double(const VectorXd&)>& f,
                                   const std::vector<Variable>& variables, const ExpensiveOptions& options = {});

}  // namespace demfit::rbf_surrogate
