// Expected-improvement ask/tell strategy (InfillStrategy::expected_improvement): kriging model
// chosen by likelihood among kernels and output warps, EI infill (Jones, Schonlau & Welch 1998),
// exclusion of basins the loop has stalled in, and batches of q points by the kriging believer
// (Ginsbourger, Le Riche & Carraro 2010).
#include "demfit/rbf_surrogate/expected_improvement.hpp"
#include "demfit/rbf_surrogate/kriging.hpp"
#include "strategy_internal.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace demfit::rbf_surrogate::detail {

namespace {

// Kriging fits along the run: hyperparameters re-searched (warm-started from the previous ones)
// at every point while the design is small and after 5 % growth later, reused in between (the
// likelihood search dominates the cost at a few hundred points).
class KrigingSchedule {
 public:
  explicit KrigingSchedule(const ExpensiveOptions& options) : options_(options.kriging) {
    options_.estimate_noise = options.kriging.estimate_noise || options.rbf.smoothing;
  }
  KrigingModel fit(const MatrixXd& x, const VectorXd& y, const KrigingTrend& trend) {
    KrigingOptions o = options_;
    o.trend = trend;
    const auto n = static_cast<int>(x.rows());
    if (length_.size() > 0) {
      o.length_hint = length_;
      o.nugget_hint = nugget_;
      o.fixed_hyperparameters = n > 50 && n < searched_at_ + std::max(1, searched_at_ / 20);
    }
    KrigingModel model = KrigingModel::fit(x, y, o);
    if (!o.fixed_hyperparameters) searched_at_ = n;
    length_ = model.length_scales();
    nugget_ = model.nugget();
    return model;
  }
  bool noisy() const { return options_.estimate_noise; }

 private:
  KrigingOptions options_;
  VectorXd length_;
  double nugget_ = 0.0;
  int searched_at_ = 0;
};

// Output warping: the model is fitted to y or to w(y) = log(y − min y + δ), δ = 0.1·(median y − min y),
// which spreads out the values near the minimum and compresses the far-away large ones (the
// surrogate then resolves the minimum's basin instead of the range). `automatic` takes the one with
// the larger likelihood of the raw values, −log L(y) = −log L(w(y)) − Σ log w'(y_i)
// (Box & Cox 1964: a transform is chosen by the likelihood including its Jacobian).
struct WarpedModel {
  KrigingModel model;
  VectorXd values;  // the values the model was fitted to
  bool warped = false;
};

VectorXd log_warp(const VectorXd& y, double& log_jacobian_sum) {
  const double lo = y.minCoeff();
  const double median = upper_median(std::vector<double>(y.data(), y.data() + y.size()));
  const double delta = std::max(0.1 * (median - lo), 1e-12 * std::max(1.0, std::abs(lo)));
  const Eigen::ArrayXd shifted = (y.array() - lo) + delta;
  log_jacobian_sum = -shifted.log().sum();  // Σ log w'(y_i), w'(y) = 1 / (y − lo + δ)
  return shifted.log().matrix();
}

// Candidate models: the warps allowed by options.output_warp × the kernels (both when
// options.select_kernel), each with its own hyperparameter schedule; the fit with the smallest
// Jacobian-corrected −log L of the raw values is used.
class ModelSelector {
 public:
  explicit ModelSelector(const ExpensiveOptions& options) : multi_fidelity_(options.lower_fidelity.values.size() >= 2) {
    std::vector<KrigingKernel> kernels{options.kriging.kernel};
    if (options.select_kernel) kernels = {KrigingKernel::matern52, KrigingKernel::gaussian};
    if (multi_fidelity_) {
      KrigingOptions cheap = options.kriging;
      cheap.estimate_noise = options.kriging.estimate_noise || options.rbf.smoothing;
      const FidelityLevel& level = options.lower_fidelity;
      cheap_model_ = std::make_shared<const KrigingModel>(KrigingModel::fit(level.points, level.values, cheap));
      if (level.values.minCoeff() > 0.0)
        cheap_log_model_ = std::make_shared<const KrigingModel>(
            KrigingModel::fit(level.points, level.values.array().log().matrix(), cheap));
      scale_options_.kriging = cheap;
    }
    for (bool warp : {false, true}) {
      if ((warp && options.output_warp == OutputWarp::none) || (!warp && options.output_warp == OutputWarp::log))
        continue;
      for (KrigingKernel k : kernels) {
        ExpensiveOptions o = options;
        o.kriging.kernel = k;
        candidates_.push_back({warp, KrigingSchedule(o)});
      }
    }
  }
  WarpedModel fit(const MatrixXd& x, const VectorXd& y) {
    double log_jacobian = 0.0;
    // With a cheaper level both levels share one warp, w(y) = log y (positive values only; the
    // data-dependent shift of log_warp would differ between the levels): ρ and the correction are
    // then fitted on the log scale, where an objective spanning decades is resolved near its minimum.
    const bool log_levels = cheap_log_model_ && y.minCoeff() > 0.0;
    VectorXd w;
    if (!multi_fidelity_) {
      w = log_warp(y, log_jacobian);
    } else if (log_levels) {
      w = y.array().log().matrix();
      log_jacobian = -w.sum();  // Σ log w'(y_i), w'(y) = 1 / y
    }
    std::optional<WarpedModel> best;
    double best_nll = std::numeric_limits<double>::infinity();
    for (auto& [warp, schedule] : candidates_) {
      if (warp && multi_fidelity_ && !log_levels) continue;
      const KrigingTrend trend = cheap_trend(x, warp ? w : y, warp);
      KrigingModel m = schedule.fit(x, warp ? w : y, trend);
      const double nll = m.data_negative_log_likelihood() - (warp ? log_jacobian : 0.0);
      if (!best || nll < best_nll) {
        best_nll = nll;
        best = WarpedModel{std::move(m), warp ? w : y, warp};
      }
    }
    return std::move(*best);
  }
  bool noisy() const { return candidates_.front().second.noisy(); }

 private:
  // The cheaper level as the trend of the expensive runs (x, y), ρ by maximum likelihood; none
  // without a cheaper level.
  // `log_scale`: y and the cheaper level both as log values.
  KrigingTrend cheap_trend(const MatrixXd& x, const VectorXd& y, bool log_scale) const {
    if (!multi_fidelity_) return {};
    const std::shared_ptr<const KrigingModel>& cheap = log_scale ? cheap_log_model_ : cheap_model_;
    FidelityLevel expensive{x, y};
    return {cheap, autoregressive_scale(expensive, cheap->means(x), scale_options_)};
  }

  bool multi_fidelity_ = false;
  std::shared_ptr<const KrigingModel> cheap_model_;
  std::shared_ptr<const KrigingModel> cheap_log_model_;  // of log(values); null unless all are positive
  MultiFidelityOptions scale_options_;
  std::vector<std::pair<bool, KrigingSchedule>> candidates_;
};

// True when `p` is at least 1e-5 (the repeat distance of every strategy) from each row of `rows`.
bool distinct_from(const MatrixXd& rows, const Eigen::RowVectorXd& p) {
  for (Eigen::Index r = 0; r < rows.rows(); ++r)
    if ((rows.row(r) - p).norm() < 1e-5) return false;
  return true;
}

// Index of the incumbent: the lowest value run, or with noise the lowest predicted mean at a run
// point (a lucky noisy draw is not trusted as the best).
// With `keep`, only points for which keep(x) is true count (-1: none).
Eigen::Index incumbent_index(const KrigingModel& model, const MatrixXd& x, const VectorXd& y, bool noisy,
                             double& incumbent_value, const std::function<bool(const VectorXd&)>& keep = {}) {
  Eigen::Index best = -1;
  incumbent_value = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const VectorXd xi = x.row(i).transpose();
    if (keep && !keep(xi)) continue;
    const double v = noisy ? model.mean(xi) : y[i];
    if (v < incumbent_value) {
      incumbent_value = v;
      best = i;
    }
  }
  return best;
}

// Basins the loop has stalled in: their points are excluded from EI's incumbent and candidates
// while stalled, so EI works on the rest of the domain against the best value found there (a tabu
// list of converged basins; plain EI, confident about the incumbent's basin, would keep refining it).
class BasinExclusion {
 public:
  BasinExclusion(double radius, int stall) : radius_(radius), stall_(stall) {}
  bool active() const { return !centres_.empty(); }
  void clear() { centres_.clear(); }
  bool excluded(const VectorXd& x) const {
    for (const auto& c : centres_)
      if ((x - c).norm() < radius_) return true;
    return false;
  }
  void exclude(const VectorXd& centre) {
    if (excluded(centre)) return;
    centres_.push_back(centre);
    outside_best_ = std::numeric_limits<double>::infinity();
    outside_since_ = 0;
  }
  // Best raw value outside the excluded basins; a basin there that stops improving is excluded too.
  void track(const MatrixXd& x, const VectorXd& y, int added, const VectorXd& outside_incumbent) {
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      if (!excluded(x.row(i).transpose())) best = std::min(best, y[i]);
    const bool gained = improved(best, outside_best_);
    outside_since_ = gained || !std::isfinite(outside_best_) ? 0 : outside_since_ + added;
    outside_best_ = std::min(outside_best_, best);
    if (outside_since_ >= stall_ && outside_incumbent.size() > 0) exclude(outside_incumbent);
  }
  AcquisitionOptions acquisition(AcquisitionOptions o) const {
    o.excluded_centres = centres_;
    o.excluded_radius = radius_;
    return o;
  }

 private:
  double radius_;
  int stall_;
  std::vector<VectorXd> centres_;
  double outside_best_ = std::numeric_limits<double>::infinity();
  int outside_since_ = 0;
};

// Efficient global optimisation (Jones et al. 1998): each point maximises EI; every exploit_every-th
// point is the minimiser of the kriging mean instead. After stall_evaluations points without a 0.1 %
// improvement the incumbent's basin is excluded (BasinExclusion) until the best value improves again.
// A point that would repeat a run point is replaced by a maximin point.
// Batches (q > 1): kriging believer — the chosen point is added to the model with its predicted mean
// as value (hyperparameters kept), and EI of the updated model picks the next point; the believed
// value lowers the incumbent when it is below it. The believer's variance collapses at the chosen
// point, so the next point goes elsewhere without any tuning constant.
class ExpectedImprovementStrategy final : public AskTellStrategy {
 public:
  ExpectedImprovementStrategy(int dims, const ExpensiveOptions& options)
      : AskTellStrategy(dims, options.seed),
        options_(options),
        schedule_(options),
        basins_(options.stall_exclusion_radius * std::sqrt(static_cast<double>(dims)), options.stall_evaluations) {}
  // EI spends the evaluations better than a space-filling design does, so its design is the smallest
  // that fixes a linear trend: n + 1 points (Hartmann-6: median 35 vs 44+ evaluations with 2(n+1)).
  int initial_points() const override {
    return options_.initial_points > 0 ? options_.initial_points : history_.dims() + 1;
  }

 protected:
  int minimum_fit_points() const override { return std::max(2, std::min(initial_points(), history_.dims() + 1)); }
  MatrixXd propose(int batch) override;
  void told(int before) override {
    if (stalled_)
      basins_.track(history_.fit_points(), history_.fit_values(), history_.size() - before, outside_incumbent_);
    const bool gained = improved(history_.best(), last_best_);
    since_improvement_ = gained ? 0 : since_improvement_ + (history_.size() - before);
    last_best_ = std::min(last_best_, history_.best());
    ++iteration_;
  }

 private:
  MatrixXd believer_batch(const WarpedModel& warped, MatrixXd rows, double best, const VectorXd& incumbent,
                          const AcquisitionOptions& acquisition, int batch, std::uint64_t seed) const;
  Box slot_region(const VectorXd& incumbent, Eigen::Index chosen, int batch) const;

  ExpensiveOptions options_;
  ModelSelector schedule_;
  BasinExclusion basins_;
  int iteration_ = 0, since_improvement_ = 0;
  bool stalled_ = false;
  VectorXd outside_incumbent_;
  double last_best_ = std::numeric_limits<double>::infinity();
};

MatrixXd ExpectedImprovementStrategy::propose(int batch) {
  const int dims = history_.dims();
  const Box bounds = Box::unit(dims);
  if (iteration_ == 0) last_best_ = history_.best();
  const MatrixXd x = history_.fit_points();
  const VectorXd y = history_.fit_values();
  const WarpedModel warped = schedule_.fit(x, y);
  const KrigingModel& model = warped.model;
  double best = 0.0;
  VectorXd incumbent = x.row(incumbent_index(model, x, warped.values, schedule_.noisy(), best)).transpose();
  const std::uint64_t seed = iteration_seed(options_.seed, iteration_);
  // An exclusion episode lasts 7·stall_evaluations points: a slow but steady descent (a long
  // curved valley) may have been taken for a stall, so plain EI then resumes with what the
  // episode learnt. Measured, 10 seeds: unbounded episodes fail Rosenbrock-4 twice, episodes
  // of 2 or 4 stall lengths fail Hartmann-6 twice; 7 fails neither.
  if (options_.stall_evaluations > 0 && since_improvement_ >= 8 * options_.stall_evaluations) {
    basins_.clear();
    since_improvement_ = 0;
  }
  stalled_ = options_.stall_evaluations > 0 && since_improvement_ >= options_.stall_evaluations;
  if (stalled_) basins_.exclude(incumbent);
  AcquisitionOptions acquisition = options_.acquisition;
  // Balls of 0.1·√n around failed runs (10 % of the unit-box diagonal): Branin with every run at
  // x1 < 0.3 (unit) failing, 60 evaluations: 39 failed runs without them, 18 with them.
  for (int i = 0; i < history_.size(); ++i)
    if (std::isnan(history_.values()[static_cast<std::size_t>(i)]))
      acquisition.failed_points.push_back(history_.point(i));
  acquisition.failed_radius = 0.1 * std::sqrt(static_cast<double>(dims));
  outside_incumbent_ = VectorXd();
  MatrixXd rows(0, dims);
  if (stalled_) {
    const auto outside = [this](const VectorXd& p) { return !basins_.excluded(p); };
    const Eigen::Index i = incumbent_index(model, x, warped.values, schedule_.noisy(), best, outside);
    if (i >= 0)
      outside_incumbent_ = incumbent = x.row(i).transpose();
    else
      best = std::numeric_limits<double>::infinity();  // nothing outside yet: pure exploration
    acquisition = basins_.acquisition(acquisition);
  } else if (options_.exploit_every > 0 && iteration_ % options_.exploit_every == options_.exploit_every - 1) {
    MinimizeOptions mo = options_.minimize;
    mo.seed = seed;
    const Objective mean = [&model](const VectorXd& p, VectorXd* g) { return model.mean(p, g); };
    rows = keep_new(minimize(mean, bounds, mo).x.transpose());
  }
  if (rows.rows() == 0)
    rows = keep_new(maximise_expected_improvement(model, best, incumbent, bounds, seed, acquisition).x.transpose());
  if (batch > 1) rows = believer_batch(warped, rows, best, incumbent, acquisition, batch, seed);
  if (rows.rows() == 0) rows = unstall_point(seed);
  return rows;
}

MatrixXd ExpectedImprovementStrategy::believer_batch(const WarpedModel& warped, MatrixXd rows, double best,
                                                     const VectorXd& incumbent, const AcquisitionOptions& acquisition,
                                                     int batch, std::uint64_t seed) const {
  const Box bounds = Box::unit(history_.dims());
  MatrixXd x = history_.fit_points();
  VectorXd y = warped.values;
  KrigingModel model = warped.model;
  KrigingOptions fixed = options_.kriging;
  fixed.kernel = model.kernel();
  fixed.estimate_noise = schedule_.noisy();
  fixed.length_hint = model.length_scales();
  fixed.nugget_hint = model.nugget();
  fixed.fixed_hyperparameters = true;
  fixed.trend = model.trend();
  for (int k = 1; static_cast<int>(rows.rows()) < batch && k < 2 * batch; ++k) {
    for (Eigen::Index r = x.rows() - history_.successes(); r < rows.rows(); ++r) {
      const VectorXd p = rows.row(r).transpose();
      const double believed = options_.constant_liar ? warped.values.minCoeff() : model.mean(p);
      x.conservativeResize(x.rows() + 1, Eigen::NoChange);
      x.bottomRows(1) = p.transpose();
      y.conservativeResize(y.size() + 1);
      y[y.size() - 1] = believed;
      if (!schedule_.noisy()) best = std::min(best, believed);
    }
    model = KrigingModel::fit(x, y, fixed);
    const std::uint64_t point_seed = seed + 104729ULL * static_cast<std::uint64_t>(k);
    const Box region = slot_region(incumbent, rows.rows(), batch);
    MatrixXd next;
    if (options_.batch_trust_regions <= 0 && options_.batch_exploit && rows.rows() == batch - 1) {
      MinimizeOptions mo = options_.minimize;
      mo.seed = point_seed;
      const Objective mean = [&model](const VectorXd& p, VectorXd* g) { return model.mean(p, g); };
      next = keep_new(minimize(mean, bounds, mo).x.transpose());
    }
    // A point that repeats a run or batch point leaves its slot to EI in the slot's region, then in the
    // whole box (the batch stays q points long).
    // (A slot without a trust region searches the whole box once: a second identical search would
    // return the same point.)
    const bool own_region = region.lower != bounds.lower || region.upper != bounds.upper;
    for (const Box* search : {&region, &bounds})
      if ((search == &region || own_region) && (next.rows() == 0 || !distinct_from(rows, next.row(0))))
        next = keep_new(
            maximise_expected_improvement(model, best, incumbent, *search, point_seed, acquisition).x.transpose());
    if (next.rows() > 0 && distinct_from(rows, next.row(0))) {
      rows.conservativeResize(rows.rows() + 1, Eigen::NoChange);
      rows.bottomRows(1) = next.row(0);
    }
  }
  return rows;
}

// Search region of batch slot `chosen` (0-based). With batch_trust_regions = m the last min(q − 1, m)
// slots maximise EI inside boxes around the incumbent of half-widths w, 2w, 4w, …: the step lengths a
// trust-region method would try one after another (Conn, Gould & Toint 2000, ch. 6), tried at once
// since the batch runs in parallel. With the believer alone a round of 4 points gained about what 2
// sequential EI steps gain in Hartmann-6's basin (12 rounds for 25 steps). Other slots search the whole box.
Box ExpectedImprovementStrategy::slot_region(const VectorXd& incumbent, Eigen::Index chosen, int batch) const {
  const int dims = history_.dims();
  Box region = Box::unit(dims);
  const int trust = std::min(batch - 1, options_.batch_trust_regions);
  if (trust <= 0 || chosen < batch - trust) return region;
  const double half = options_.trust_region_half_width * std::pow(2.0, static_cast<double>(chosen - (batch - trust)));
  for (int i = 0; i < dims; ++i) {
    region.lower[i] = std::max(0.0, incumbent[i] - half);
    region.upper[i] = std::min(1.0, incumbent[i] + half);
  }
  return region;
}

}  // namespace

std::unique_ptr<AskTellStrategy> make_expected_improvement_strategy(int dims, const ExpensiveOptions& options) {
  return std::make_unique<ExpectedImprovementStrategy>(dims, options);
}

}  // namespace demfit::rbf_surrogate::detail
