#pragma once
// A small surrogate-based minimisation driver: design -> fit -> optimise -> infill, with either
// SRSM domain reduction (LS-OPT-like) or adaptive (stochastic-RBF) infill. Used by tests and bench;
// identify/ runs its own loop with the same building blocks.
#include "demfit/rbf_surrogate/optimize.hpp"
#include "demfit/rbf_surrogate/rbf_network.hpp"
#include "demfit/rbf_surrogate/srsm.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace demfit::rbf_surrogate {

enum class InfillStrategy { srsm, adaptive };

struct ExpensiveOptions {
    InfillStrategy strategy = InfillStrategy::srsm;
    int max_evaluations = 100;
    int initial_points = 0;          // 0: 2(n+1)
    int points_per_iteration = 0;    // 0: srsm 1.5(n+1)+1 rounded up (SPEC 3), adaptive 1
    std::uint64_t seed = 1;
    RbfOptions rbf;
    SrsmSettings srsm;
    MinimizeOptions minimize{.global_evaluations = 600, .local_starts = 3};
    std::optional<double> target;    // stop once a value <= target has been evaluated
    // Fit the surrogate to min(y, median(y)) (Regis & Shoemaker 2007): large values far from the
    // optimum (Rosenbrock-like ranges) otherwise dominate the fit and its width.
    bool clip_above_median = false;
    // SRSM strategy: centre the next subregion on the best point run so far (the predicted optimum
    // when it is the best, which is the usual case); false = always the predicted optimum (LS-OPT).
    bool recentre_on_best = true;
};

struct ExpensiveResult {
    VectorXd x;                       // best evaluated point, physical units
    double value = 0.0;               // best evaluated value
    int evaluations = 0;
    MatrixXd points;                  // all evaluated points, physical units (rows)
    VectorXd values;                  // all evaluated values, in evaluation order
    std::vector<double> best_so_far;  // best value after each evaluation
};

// f receives physical coordinates (see Variable). Deterministic for a given seed.
ExpensiveResult minimise_expensive(const std::function<double(const VectorXd&)>& f,
                                   const std::vector<Variable>& variables, const ExpensiveOptions& options = {});

}  // namespace demfit::rbf_surrogate
