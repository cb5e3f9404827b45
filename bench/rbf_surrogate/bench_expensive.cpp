// Evaluations needed to reach a target accuracy: demfit SRSM + RBF, demfit adaptive infill, demfit
// kriging expected improvement, and
// baselines from scipy (differential evolution, Nelder-Mead) and scikit-learn (GP expected improvement)
// run by baselines.py. Prints one table with ratios. Usage:
//   bench_rbf_surrogate [seeds (default 5)] [baseline seeds (default 5, 0 = skip python)] [results file] [batch]
// batch (default 1): 1 = sequential runs through minimise_expensive (the loop stops at the run that
// meets the target); q > 1 = the ask/tell strategies asked for q points at a time, every asked point
// evaluated (as q parallel workers would) and counted: evaluations to target = runs up to the end of
// the ask that contains the first hit. SRSM uses q as its batch size too.
// With a results file (RESULT lines saved from an earlier `python3 baselines.py N` run) the python
// baselines are read instead of re-run (the GP loop takes tens of minutes on Rosenbrock-4).
// Environment (development only; the reported table uses none): DEMFIT_BENCH_CLIP=1 turns on
// clip_above_median; DEMFIT_BENCH_ONLY=<method substring>, DEMFIT_BENCH_PROBLEM=<name> restrict the
// demfit runs; DEMFIT_BENCH_VERBOSE=1 prints each run; DEMFIT_BENCH_{EXPLOIT,MAXLEN,WARP,KERNEL,
// SELECT,STALL,RADIUS,CAND,STARTS,BATCH_EXPLOIT,LIAR,TRUST,TRUST_WIDTH} override the expected_improvement options of
// the same meaning. Targets (on the TRUE value of the incumbent = best observed point): Branin f* + 1e-3, Hartmann-6
// within 1 %, Rosenbrock-4 on [-2,2]^4 f <= 0.1, noisy Branin (1 % multiplicative Gaussian noise) f* + 1e-2.
#include "demfit/rbf_surrogate/design.hpp"
#include "demfit/rbf_surrogate/expensive.hpp"
#include "demfit/rbf_surrogate/strategy.hpp"
#include "test_functions.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace demfit::rbf_surrogate;

namespace {

struct Problem {
  std::string name;
  std::function<double(const VectorXd&)> f;
  std::vector<Variable> vars;
  double target;
  int budget;
  bool noisy;
};

std::vector<Problem> problems() {
  std::vector<Variable> h6, r4;
  for (int i = 0; i < 6; ++i) h6.push_back({"x", 0.0, 1.0});
  for (int i = 0; i < 4; ++i) r4.push_back({"x", -2.0, 2.0});
  const std::vector<Variable> br{{"x1", -5.0, 10.0}, {"x2", 0.0, 15.0}};
  return {{"branin", testfn::branin, br, testfn::kBraninMinimum + 1e-3, 100, false},
          {"hartmann6", testfn::hartmann6, h6, 0.99 * testfn::kHartmann6Minimum, 300, false},
          {"rosenbrock4", testfn::rosenbrock, r4, 0.1, 300, false},
          {"branin_noisy", testfn::branin, br, testfn::kBraninMinimum + 1e-2, 100, true}};
}

// Batch mode: drive the ask/tell strategy, q points per ask, every asked point evaluated.
void run_batches(const std::function<double(const VectorXd&)>& f, const Problem& p, const ExpensiveOptions& o,
                 const int& hit) {
  const auto strategy = make_strategy(static_cast<int>(p.vars.size()), o);
  while (strategy->history().size() < p.budget && hit < 0) {
    const MatrixXd asked = strategy->ask(o.points_per_iteration);
    VectorXd values(asked.rows());
    for (Eigen::Index i = 0; i < asked.rows(); ++i) values[i] = f(from_unit(p.vars, asked.row(i).transpose()));
    strategy->tell(asked, values);
  }
}

// Evaluations until the incumbent's true value meets the target (-1: never), and run time.
std::pair<int, double> run_demfit(const Problem& p, InfillStrategy strategy, std::uint64_t seed, int batch) {
  std::mt19937_64 rng(1000 + seed);
  int n = 0, hit = -1;
  double best_observed = INFINITY;
  auto wrapped = [&](const VectorXd& x) {
    const double truth = p.f(x);
    double obs = truth;
    if (p.noisy) {  // Box-Muller with the library's reproducible uniform mapping
      const double u1 = 1.0 - uniform01(rng), u2 = uniform01(rng);
      obs = truth * (1 + 0.01 * std::sqrt(-2 * std::log(u1)) * std::cos(6.283185307179586 * u2));
    }
    ++n;
    if (obs < best_observed) {
      best_observed = obs;
      if (hit < 0 && truth <= p.target) hit = n;
    }
    return obs;
  };
  ExpensiveOptions o;
  o.strategy = strategy;
  o.max_evaluations = p.budget;
  o.seed = seed;
  o.rbf.smoothing = p.noisy;
  o.clip_above_median = std::getenv("DEMFIT_BENCH_CLIP") != nullptr;
  if (!p.noisy) o.target = p.target;
  if (const char* e = std::getenv("DEMFIT_BENCH_EXPLOIT")) o.exploit_every = std::atoi(e);
  if (const char* e = std::getenv("DEMFIT_BENCH_MAXLEN")) o.kriging.max_length = std::atof(e);
  if (const char* e = std::getenv("DEMFIT_BENCH_WARP")) o.output_warp = static_cast<OutputWarp>(std::atoi(e));
  if (const char* e = std::getenv("DEMFIT_BENCH_KERNEL")) o.kriging.kernel = static_cast<KrigingKernel>(std::atoi(e));
  if (const char* e = std::getenv("DEMFIT_BENCH_SELECT")) o.select_kernel = std::atoi(e) != 0;
  if (const char* e = std::getenv("DEMFIT_BENCH_STALL")) o.stall_evaluations = std::atoi(e);
  if (const char* e = std::getenv("DEMFIT_BENCH_CAND")) o.acquisition.candidates = std::atoi(e);
  if (const char* e = std::getenv("DEMFIT_BENCH_STARTS")) o.acquisition.local_starts = std::atoi(e);
  if (const char* e = std::getenv("DEMFIT_BENCH_BATCH_EXPLOIT")) o.batch_exploit = std::atoi(e) != 0;
  if (const char* e = std::getenv("DEMFIT_BENCH_LIAR")) o.constant_liar = std::atoi(e) != 0;
  if (const char* e = std::getenv("DEMFIT_BENCH_TRUST")) o.batch_trust_regions = std::atoi(e);
  if (const char* e = std::getenv("DEMFIT_BENCH_TRUST_WIDTH")) o.trust_region_half_width = std::atof(e);
  if (const char* e = std::getenv("DEMFIT_BENCH_RADIUS")) o.stall_exclusion_radius = std::atof(e);
  const auto t0 = std::chrono::steady_clock::now();
  if (batch > 1) {
    o.points_per_iteration = batch;
    run_batches(wrapped, p, o, hit);
    if (hit > 0) hit = std::max(hit, n);  // the whole ask containing the hit was run
  } else {
    minimise_expensive(wrapped, p.vars, o);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return {hit, seconds};
}

// Median with failures counted as infinite; -1 when at least half the runs failed.
double median_evals(std::vector<int> v) {
  if (v.empty()) return -1.0;
  for (auto& x : v)
    if (x < 0) x = 1 << 30;
  std::sort(v.begin(), v.end());
  const double m = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  return m >= (1 << 29) ? -1.0 : m;
}

using BaselineResults = std::map<std::pair<std::string, std::string>, std::vector<int>>;

// One "RESULT <method> <problem> <seed> <evaluations>" line of baselines.py's output into `out`.
void add_baseline_line(const std::string& line, BaselineResults& out) {
  std::istringstream is(line);
  std::string tag, method, problem;
  int seed = 0, evals = -1;
  is >> tag;
  if (tag == "SKIPPED") std::cout << "python baselines skipped: " << line << "\n";
  if (tag != "RESULT") return;
  is >> method >> problem >> seed >> evals;
  out[{method, problem}].push_back(evals);
}

BaselineResults run_baselines(int seeds, const char* saved) {
  BaselineResults out;
  if (saved) {  // read directly: a saved file's path never reaches a shell
    std::ifstream in(saved);
    if (!in) std::cout << "cannot read saved baselines " << saved << "\n";
    for (std::string line; std::getline(in, line);) add_baseline_line(line, out);
    return out;
  }
  // A fixed command line (interpreter, script path from the build, an integer): nothing from the user.
  const std::string cmd = std::string("/usr/bin/python3 ") + DEMFIT_BASELINES_SCRIPT + " " + std::to_string(seeds);
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return out;
  char line[512];
  while (fgets(line, sizeof line, pipe)) add_baseline_line(std::string(line), out);
  pclose(pipe);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 5;
  const int baseline_seeds = argc > 2 ? std::atoi(argv[2]) : 5;  // as many seeds as demfit by default
  std::map<std::pair<std::string, std::string>, std::vector<int>> results;
  std::map<std::pair<std::string, std::string>, double> seconds;
  const int batch = argc > 4 ? std::atoi(argv[4]) : 1;
  if (batch > 1) std::printf("batch %d: evaluations counted to the end of the ask containing the hit\n", batch);
  const char* only = std::getenv("DEMFIT_BENCH_ONLY");  // e.g. "demfit_ei" (substring match)
  const char* only_problem = std::getenv("DEMFIT_BENCH_PROBLEM");
  for (const Problem& p : problems())
    for (auto [name, strategy] :
         {std::pair{"demfit_srsm", InfillStrategy::srsm}, std::pair{"demfit_adaptive", InfillStrategy::adaptive},
          std::pair{"demfit_ei", InfillStrategy::expected_improvement}}) {
      if (seeds <= 0) continue;
      if (only && std::string(name).find(only) == std::string::npos) continue;
      if (only_problem && p.name != only_problem) continue;
      for (int s = 1; s <= seeds; ++s) {
        const auto [hit, secs] = run_demfit(p, strategy, static_cast<std::uint64_t>(s), batch);
        results[{name, p.name}].push_back(hit);
        if (std::getenv("DEMFIT_BENCH_VERBOSE"))
          std::cerr << name << " " << p.name << " seed " << s << ": " << hit << " (" << secs << " s)\n";
        seconds[{name, p.name}] += secs / seeds;
      }
      std::cerr << name << " " << p.name << " done\n";
    }
  const char* saved = argc > 3 ? argv[3] : nullptr;
  const bool have_python =
      saved || (baseline_seeds > 0 && std::system("/usr/bin/python3 -c 'import scipy, sklearn' 2>/dev/null") == 0);
  if (have_python)
    for (auto& [key, v] : run_baselines(baseline_seeds, saved)) results[key] = v;
  else
    std::cout << "python baselines skipped (install python3-scipy python3-sklearn: scripts/setup --bench)\n";
  const std::vector<std::string> methods{"demfit_srsm", "demfit_adaptive",   "demfit_ei",
                                         "scipy_de",    "scipy_nelder_mead", "sklearn_gp_ei"};
  // ratio = median / best baseline median (< 1: fewer evaluations than every baseline).
  std::printf("%-13s %-18s %8s %8s %10s %16s %10s\n", "problem", "method", "success", "budget", "median_ev",
              "ratio_vs_best_bl", "s/run");
  for (const Problem& p : problems()) {
    double best_baseline = -1.0, best_demfit = -1.0;
    for (const auto& m : methods) {
      const auto it = results.find({m, p.name});
      if (it == results.end() || it->second.empty()) continue;
      const double med = median_evals(it->second);
      if (med <= 0) continue;
      double& best = m.rfind("demfit", 0) == 0 ? best_demfit : best_baseline;
      if (best < 0 || med < best) best = med;
    }
    for (const auto& m : methods) {
      const auto it = results.find({m, p.name});
      if (it == results.end() || it->second.empty()) {
        std::printf("%-13s %-18s %8s\n", p.name.c_str(), m.c_str(), "skipped");
        continue;
      }
      const auto& v = it->second;
      const int ok = static_cast<int>(std::count_if(v.begin(), v.end(), [](int x) { return x > 0; }));
      const double med = median_evals(v);
      const int budget = (m.rfind("scipy", 0) == 0) ? 20 * p.budget : p.budget;
      char ratio[32] = "-", median[32] = "fail", secs[32] = "-";
      if (med > 0) std::snprintf(median, sizeof median, "%.1f", med);
      if (med > 0 && best_baseline > 0) std::snprintf(ratio, sizeof ratio, "%.2f", med / best_baseline);
      if (seconds.count({m, p.name})) std::snprintf(secs, sizeof secs, "%.2f", seconds[{m, p.name}]);
      std::printf("%-13s %-18s %5d/%-2zu %8d %10s %16s %10s\n", p.name.c_str(), m.c_str(), ok, v.size(), budget, median,
                  ratio, secs);
    }
    if (best_demfit > 0 && best_baseline > 0)
      std::printf("%-13s best demfit / best baseline = %.1f / %.1f = %.2f\n", p.name.c_str(), best_demfit,
                  best_baseline, best_demfit / best_baseline);
  }
  return 0;
}
