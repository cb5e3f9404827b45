// Space-filling designs: maximin Latin hypercube and sequential maximin augmentation
// (docs/spec.md section 3: iteration 0 is a space-filling design, later iterations add points by maximin
// distance to all points already run in the current subregion).
#include "demfit/rbf_surrogate/design.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace demfit::rbf_surrogate {

double uniform01(std::mt19937_64& rng) {
  // The top 53 bits scaled by 2^-53: exactly reproducible, unlike std::uniform_real_distribution.
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

double normal01(std::mt19937_64& rng) {
  // Box-Muller from two uniform01 draws: deterministic across platforms (std distributions are not).
  const double u1 = 1.0 - uniform01(rng), u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

std::uint64_t uniform_index(std::mt19937_64& rng, std::uint64_t n) {
  // Lemire's multiply-high mapping; the bias (< n / 2^64) is irrelevant for design sizes.
  return static_cast<std::uint64_t>((static_cast<unsigned __int128>(rng()) * n) >> 64);
}

double minimum_distance(const MatrixXd& points) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    for (Eigen::Index j = i + 1; j < points.rows(); ++j)
      best = std::min(best, (points.row(i) - points.row(j)).squaredNorm());
  return std::sqrt(best);
}

namespace {

void check_design_arguments(int points, int dims, const Box& region) {
  if (points < 1) throw std::invalid_argument("design: number of points must be at least 1");
  if (dims < 1) throw std::invalid_argument("design: number of dimensions must be at least 1");
  validate(region);
  if (region.dims() != dims)
    throw std::invalid_argument("design: region has " + std::to_string(region.dims()) + " dimensions, expected " +
                                std::to_string(dims));
}

// Integer LHS: column c is a random permutation of 0..n-1 (Fisher-Yates with our own mapping).
Eigen::MatrixXi random_permutations(int n, int dims, std::mt19937_64& rng) {
  Eigen::MatrixXi strata(n, dims);
  for (int c = 0; c < dims; ++c) {
    for (int i = 0; i < n; ++i) strata(i, c) = i;
    for (int i = n - 1; i > 0; --i) {
      const auto j = static_cast<int>(uniform_index(rng, static_cast<std::uint64_t>(i) + 1));
      std::swap(strata(i, c), strata(j, c));
    }
  }
  return strata;
}

MatrixXd strata_to_region(const Eigen::MatrixXi& strata, const Box& region) {
  const auto n = static_cast<double>(strata.rows());
  MatrixXd x(strata.rows(), strata.cols());
  for (Eigen::Index i = 0; i < strata.rows(); ++i)
    for (Eigen::Index c = 0; c < strata.cols(); ++c)
      x(i, c) = region.lower[c] + (strata(i, c) + 0.5) / n * (region.upper[c] - region.lower[c]);
  return x;
}

// Morris-Mitchell term (1 / d_ij)^p with d in stratum units: any two LHS points differ by at least
// one stratum in every coordinate, so d >= 1 and the term never overflows.
constexpr int kPhiHalfPower = 10;  // p = 20
double phi_term(double d2) {
  const double inv = 1.0 / d2;
  double r = 1.0;
  for (int k = 0; k < kPhiHalfPower; ++k) r *= inv;
  return r;
}

// Greedy pair-swap improvement of phi_p = sum_{i<j} d_ij^-p; only pairs touching the swapped rows
// change, so a trial costs O(n·dims).
void improve_maximin(Eigen::MatrixXi& s, std::mt19937_64& rng) {
  const int n = static_cast<int>(s.rows()), dims = static_cast<int>(s.cols());
  if (n < 3) return;
  MatrixXd d2 = MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) d2(i, j) = d2(j, i) = (s.row(i) - s.row(j)).cast<double>().squaredNorm();
  const long trials = std::min<long>(60000, std::max<long>(4000, 150L * n * dims));
  std::vector<double> new_i(n), new_j(n);
  for (long t = 0; t < trials; ++t) {
    const int c = static_cast<int>(uniform_index(rng, dims));
    const int i = static_cast<int>(uniform_index(rng, n));
    int j = static_cast<int>(uniform_index(rng, n - 1));
    if (j >= i) ++j;
    const double xi = s(i, c), xj = s(j, c);
    double delta = 0.0;
    for (int k = 0; k < n; ++k) {
      if (k == i || k == j) continue;
      const double xk = s(k, c);
      new_i[k] = d2(i, k) - (xi - xk) * (xi - xk) + (xj - xk) * (xj - xk);
      new_j[k] = d2(j, k) - (xj - xk) * (xj - xk) + (xi - xk) * (xi - xk);
      delta += phi_term(new_i[k]) + phi_term(new_j[k]) - phi_term(d2(i, k)) - phi_term(d2(j, k));
    }
    if (delta >= 0.0) continue;
    std::swap(s(i, c), s(j, c));
    for (int k = 0; k < n; ++k) {
      if (k == i || k == j) continue;
      d2(i, k) = d2(k, i) = new_i[k];
      d2(j, k) = d2(k, j) = new_j[k];
    }
  }
}

}  // namespace

MatrixXd latin_hypercube_random(int points, int dims, std::uint64_t seed, const Box& region) {
  check_design_arguments(points, dims, region);
  std::mt19937_64 rng(seed);
  return strata_to_region(random_permutations(points, dims, rng), region);
}

MatrixXd latin_hypercube_maximin(int points, int dims, std::uint64_t seed, const Box& region) {
  check_design_arguments(points, dims, region);
  std::mt19937_64 rng(seed);
  Eigen::MatrixXi strata = random_permutations(points, dims, rng);
  improve_maximin(strata, rng);
  return strata_to_region(strata, region);
}

namespace {

double min_d2_to_rows(const VectorXd& x, const MatrixXd& rows, Eigen::Index skip = -1) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < rows.rows(); ++i)
    if (i != skip) best = std::min(best, (rows.row(i).transpose() - x).squaredNorm());
  return best;
}

}  // namespace

MatrixXd space_filling_augment(const MatrixXd& existing, int points, const Box& region, std::uint64_t seed) {
  validate(region);
  const int dims = region.dims();
  if (points < 0) throw std::invalid_argument("space_filling_augment: number of points must be >= 0");
  if (existing.rows() > 0 && existing.cols() != dims)
    throw std::invalid_argument("space_filling_augment: existing points have the wrong number of columns");
  if (points == 0) return MatrixXd(0, dims);
  // Work in region-local coordinates so every direction of a narrow subregion counts equally.
  const VectorXd width = region.width().cwiseMax(1e-300);
  MatrixXd all(existing.rows() + points, dims);
  for (Eigen::Index i = 0; i < existing.rows(); ++i)
    all.row(i) = (existing.row(i).transpose() - region.lower).cwiseQuotient(width).transpose();
  std::mt19937_64 rng(seed);
  const int pool_size = std::clamp(200 * points, 2000, 20000);
  MatrixXd pool(pool_size, dims);
  for (int p = 0; p < pool_size; ++p)
    for (int c = 0; c < dims; ++c) pool(p, c) = uniform01(rng);
  // Greedy maximin: each new point is the candidate farthest from everything chosen so far.
  std::vector<double> pool_d2(pool_size);
  for (int p = 0; p < pool_size; ++p) pool_d2[p] = min_d2_to_rows(pool.row(p), all.topRows(existing.rows()));
  Eigen::Index filled = existing.rows();
  for (int k = 0; k < points; ++k) {
    const auto best = std::distance(pool_d2.begin(), std::max_element(pool_d2.begin(), pool_d2.end()));
    all.row(filled) = pool.row(best);
    for (int p = 0; p < pool_size; ++p)
      pool_d2[p] = std::min(pool_d2[p], (pool.row(p) - all.row(filled)).squaredNorm());
    ++filled;
  }
  // Exchange pass: move each new point to the pool candidate farthest from all other points when
  // that raises its own nearest-neighbour distance (never lowers the design's minimum distance).
  const double exchange_cost = static_cast<double>(points) * pool_size * static_cast<double>(all.rows()) * dims;
  const int sweeps = exchange_cost < 3e8 ? 2 : 0;  // skip for very large batches (greedy is already good)
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for (Eigen::Index r = existing.rows(); r < all.rows(); ++r) {
      double current = min_d2_to_rows(all.row(r), all, r);
      for (int p = 0; p < pool_size; ++p) {
        const double d = min_d2_to_rows(pool.row(p), all, r);
        if (d > current) {
          current = d;
          all.row(r) = pool.row(p);
        }
      }
    }
  }
  MatrixXd result(points, dims);
  for (int k = 0; k < points; ++k)
    result.row(k) = region.from_local(all.row(existing.rows() + k).transpose()).transpose();
  return result;
}

}  // namespace demfit::rbf_surrogate
