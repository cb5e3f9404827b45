#pragma once
// Internal to rbf_surrogate (not installed API): the evaluation bookkeeping shared by the loops of
// minimise_expensive (expensive.cpp, expected_improvement_loop.cpp).
#include "demfit/rbf_surrogate/design.hpp"
#include "demfit/rbf_surrogate/expensive.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace demfit::rbf_surrogate::detail {

constexpr double kDuplicateTolerance = 1e-5;  // unit coordinates, as adaptive_infill

// The stall rule of every loop: `now` improves on `before` by more than 0.1 % of |before|.
inline bool improved(double now, double before) { return now < before - 1e-3 * std::max(std::abs(before), 1e-12); }

// Seed of the candidate search of iteration `iteration` (0-based): distinct per iteration, fixed per run.
inline std::uint64_t iteration_seed(std::uint64_t seed, int iteration) {
    return seed + 7919ULL * static_cast<std::uint64_t>(iteration + 1);
}

// Upper median (element n/2 of the sorted values).
inline double upper_median(std::vector<double> values) {
    std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2), values.end());
    return values[values.size() / 2];
}

class Run {
public:
    Run(const std::function<double(const VectorXd&)>& f, const std::vector<Variable>& variables,
        const ExpensiveOptions& options)
        : f_(f), variables_(variables), options_(options) {}

    bool done() const {
        return static_cast<int>(values_.size()) >= options_.max_evaluations ||
               (options_.target && best_ <= *options_.target);
    }
    bool is_new(const VectorXd& x) const {
        for (const auto& p : points_)
            if ((p - x).norm() < kDuplicateTolerance) return false;
        return true;
    }
    int count() const { return static_cast<int>(values_.size()); }
    double best() const { return best_; }
    VectorXd best_point() const {
        const auto it = std::min_element(values_.begin(), values_.end());
        return points_[static_cast<std::size_t>(it - values_.begin())];
    }
    // When an iteration produced nothing new (subregion collapsed onto run points), one maximin point
    // over the whole domain keeps the loop moving and the budget honest.
    void unstall(int before, std::uint64_t seed) {
        if (count() == before && !done())
            evaluate_rows(space_filling_augment(points(), 1, Box::unit(static_cast<int>(variables_.size())), seed));
    }
    void evaluate(const VectorXd& unit) {
        if (done() || !is_new(unit)) return;
        const double y = f_(from_unit(variables_, unit));
        if (!std::isfinite(y)) throw std::runtime_error("minimise_expensive: the function returned NaN or infinity");
        points_.push_back(unit);
        values_.push_back(y);
        best_ = std::min(best_, y);
        best_so_far_.push_back(best_);
    }
    void evaluate_rows(const MatrixXd& rows) {
        for (Eigen::Index i = 0; i < rows.rows(); ++i) evaluate(rows.row(i).transpose());
    }
    MatrixXd points() const {
        MatrixXd x(static_cast<Eigen::Index>(points_.size()), static_cast<Eigen::Index>(variables_.size()));
        for (std::size_t i = 0; i < points_.size(); ++i) x.row(static_cast<Eigen::Index>(i)) = points_[i].transpose();
        return x;
    }
    VectorXd values() const { return Eigen::Map<const VectorXd>(values_.data(), static_cast<Eigen::Index>(values_.size())); }
    // The width is searched (around the previous one) whenever the design has grown by 10 % since the
    // last search and reused in between (~20x cheaper per fit). Searching at every fit was measured:
    // Branin adaptive 5/5 instead of 4/5 runs within 1e-3, but Hartmann-6 adaptive 1/3 instead of
    // 2/3 on seeds 1-3, at 10x the time, so the cheaper schedule stays.
    RbfNetwork fit() {
        RbfOptions o = options_.rbf;
        const bool reuse = width_ > 0.0 && !o.fixed_width && count() < (11 * searched_at_) / 10;
        if (reuse) o.fixed_width = width_;
        else if (width_ > 0.0) o.width_hint = width_;
        VectorXd y = values();
        if (options_.clip_above_median) {
            y = y.cwiseMin(upper_median(values_));
        }
        RbfNetwork net = RbfNetwork::fit(points(), y, o);
        if (!reuse && !options_.rbf.fixed_width) {
            width_ = net.width();
            searched_at_ = count();
        }
        return net;
    }
    ExpensiveResult result() const;

private:
    const std::function<double(const VectorXd&)>& f_;
    const std::vector<Variable>& variables_;
    const ExpensiveOptions& options_;
    std::vector<VectorXd> points_;
    std::vector<double> values_;
    std::vector<double> best_so_far_;
    double best_ = std::numeric_limits<double>::infinity();
    double width_ = 0.0;
    int searched_at_ = 0;
};

void expected_improvement_loop(Run& run, const ExpensiveOptions& options, int dims);

}  // namespace demfit::rbf_surrogate::detail
