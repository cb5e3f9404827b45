#pragma once
// Ask/tell sampling strategies: the one surrogate loop of demfit. A strategy proposes
// points (`ask`), the caller evaluates them however it likes (in memory, a thread pool, MPI workers,
// a study store that survives a restart) and reports the results (`tell`). minimise_expensive
// (expensive.hpp) is a thin driver over these objects, and identify's study loop drives the
// expected-improvement one.
//
// Coordinates: every point asked or told is a row in UNIT coordinates (to_unit/from_unit of
// bounds.hpp); the strategy never sees physical units.
// Failed runs: tell them with a NaN value. They are kept for distances (no point closer than
// 1e-5 to any told point, failed ones included, is ever proposed again) but never enter a fit.
// Determinism: the state after a sequence of tells depends only on the options and that sequence,
// so a caller that replays its stored results through tell() (a resumed study) continues exactly
// as an uninterrupted run.
#include "demfit/rbf_surrogate/expensive.hpp"

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace demfit::rbf_surrogate {

// Every evaluation told to a strategy, in order.
class EvaluationHistory {
 public:
  explicit EvaluationHistory(int dims) : dims_(dims) {}
  void add(const VectorXd& unit, double value);  // value NaN: failed run
  int dims() const { return dims_; }
  int size() const { return static_cast<int>(values_.size()); }
  int successes() const { return static_cast<int>(fit_rows_.size()); }
  // No told point (failed ones included) within `tolerance` (unit coordinates) of x.
  bool is_new(const VectorXd& x, double tolerance = 1e-5) const;
  MatrixXd all_points() const;           // every told point, failed ones included (rows)
  MatrixXd fit_points() const;           // successful points only
  VectorXd fit_values() const;           // their values
  double best() const { return best_; }  // +inf before the first success
  VectorXd best_point() const;           // first successful point with the lowest value
  const std::vector<double>& values() const { return values_; }
  const std::vector<double>& best_so_far() const { return best_so_far_; }  // after each tell, NaN-free
  VectorXd point(int i) const { return points_[static_cast<std::size_t>(i)]; }

 private:
  int dims_;
  std::vector<VectorXd> points_;
  std::vector<double> values_;
  std::vector<int> fit_rows_;
  std::vector<double> best_so_far_;
  double best_ = std::numeric_limits<double>::infinity();
};

// The single stopping rule of the loop: a budget of evaluations (failed ones count: they cost a
// run) and an optional target value (stop once a successful value <= target has been told).
struct StoppingRule {
  int max_evaluations = 100;
  std::optional<double> target;
};
enum class StopReason { none, budget, target };
StopReason stop_reason(const EvaluationHistory& history, const StoppingRule& rule);
std::string to_string(StopReason reason);  // "", "evaluation budget reached", "target reached"

class AskTellStrategy {
 public:
  virtual ~AskTellStrategy() = default;
  // Points to evaluate next (rows, unit coordinates), none closer than 1e-5 to a told point or to
  // each other. While fewer than the initial design's size have been told, the first ask returns
  // the (rest of the) initial maximin design whatever batch_size is. Otherwise at most batch_size
  // rows and at least one: SRSM with recentre_on_best asks in two steps per iteration (the
  // predicted optimum alone, then the batch_size − 1 fill points, because it centres the fill on
  // the better of the optimum and the best run); adaptive and expected improvement return
  // batch_size rows (fewer only when candidates would repeat told points).
  MatrixXd ask(int batch_size);
  // Results of evaluated points, in evaluation order (any subset of what was asked, or points the
  // caller chose itself, e.g. a study's own initial design). NaN = failed run.
  void tell(const MatrixXd& points, const VectorXd& values);
  const EvaluationHistory& history() const { return history_; }
  // Size of the initial design the first ask returns (for reports and budgets).
  virtual int initial_points() const = 0;

 protected:
  AskTellStrategy(int dims, std::uint64_t seed) : history_(dims), seed_(seed) {}
  // The strategy's own proposal, once enough successful runs exist to fit its model.
  virtual MatrixXd propose(int batch_size) = 0;
  // Called after the results of a propose() are told; `before` = history size before the tell.
  virtual void told(int before) = 0;
  // Successful runs needed before propose(); below it ask() returns maximin points.
  virtual int minimum_fit_points() const = 0;
  // Rows of `rows` that are new (against the history and the rows kept before them).
  MatrixXd keep_new(const MatrixXd& rows) const;
  // One maximin point over the whole unit box: keeps the loop moving when a proposal repeated
  // told points only.
  MatrixXd unstall_point(std::uint64_t seed) const;
  EvaluationHistory history_;
  std::uint64_t seed_;

 private:
  enum class Pending { none, design, proposal };
  Pending pending_ = Pending::none;
  bool asked_ = false;
};

// The strategy of options.strategy for `dims` unit-coordinate variables. Batch size of SRSM when
// the caller passes options.points_per_iteration = 0: ⌈1.5(n+1)⌉+1 (docs/spec.md 3); others: 1.
std::unique_ptr<AskTellStrategy> make_strategy(int dims, const ExpensiveOptions& options);
int default_batch_size(int dims, const ExpensiveOptions& options);

}  // namespace demfit::rbf_surrogate
