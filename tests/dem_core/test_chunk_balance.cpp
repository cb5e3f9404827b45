// ChunkBalance: where T threads split the pair rows of PairLoadOrder::
// ascending_first_member. The split never changes results (test_pair_load_order.cpp runs 1, 2
// and 3 threads bit-identically with it); these tests check that it finds equal times.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "demfit/dem_core/chunk_balance.hpp"

using demfit::dem_core::ChunkBalance;

namespace {

/// CSR offsets of `n` rows with `per_row` pairs each.
std::vector<std::uint32_t> uniform_rows(std::size_t n, std::uint32_t per_row) {
  std::vector<std::uint32_t> rows(n + 1);
  for (std::size_t i = 0; i <= n; ++i) rows[i] = static_cast<std::uint32_t>(i) * per_row;
  return rows;
}

/// Runs `steps` steps in which a pair at position x (fraction of the list) costs cost(x) seconds;
/// returns the last split's chunk times.
std::vector<double> settle(ChunkBalance& balance, const std::vector<std::uint32_t>& rows, std::size_t threads,
                           const std::function<double(double)>& cost, int steps) {
  std::vector<double> seconds(threads);
  const double pairs = rows.back();
  for (int s = 0; s < steps; ++s) {
    const std::vector<std::size_t> chunk = balance.chunks(rows, threads);
    for (std::size_t c = 0; c < threads; ++c) {
      seconds[c] = 0.0;
      for (std::uint32_t k = rows[chunk[c]]; k < rows[chunk[c + 1]]; ++k) seconds[c] += cost(k / pairs);
    }
    balance.observe(rows, chunk, seconds);
  }
  return seconds;
}

}  // namespace

TEST_CASE("Before any measurement the chunks hold equal numbers of pairs", "[dem_core][chunk_balance]") {
  const ChunkBalance balance;
  const std::vector<std::size_t> chunk = balance.chunks(uniform_rows(1000, 10), 4);
  CHECK(chunk == std::vector<std::size_t>{0, 250, 500, 750, 1000});
}

TEST_CASE("Two chunks move to the boundary that equalises their measured times", "[dem_core][chunk_balance]") {
  // Pairs in the second half cost 3 times as much: equal halves of the total cost 2 (= 1/2 + 3/2)
  // split at x = 1/2 + (1 - 1/2)/3 = 2/3 of the list.
  ChunkBalance balance;
  const std::vector<std::uint32_t> rows = uniform_rows(3000, 10);
  const std::vector<double> seconds = settle(
      balance, rows, 2, [](double x) { return x < 0.5 ? 1.0 : 3.0; }, 200);
  const double boundary = static_cast<double>(balance.chunks(rows, 2)[1]) / 3000.0;
  CHECK(boundary == Approx(2.0 / 3.0).margin(0.002));
  CHECK(seconds[0] == Approx(seconds[1]).epsilon(0.01));
}

TEST_CASE("Three chunks balance a cost that grows along the list", "[dem_core][chunk_balance]") {
  // cost(x) = 1 + 4x: accumulated 1/3 and 2/3 of the total 3 at x with x + 2x^2 = 1 and 2.
  ChunkBalance balance;
  const std::vector<std::uint32_t> rows = uniform_rows(6000, 8);
  const std::vector<double> seconds = settle(
      balance, rows, 3, [](double x) { return 1.0 + 4.0 * x; }, 300);
  const std::vector<std::size_t> chunk = balance.chunks(rows, 3);
  CHECK(chunk[1] / 6000.0 == Approx((std::sqrt(9.0) - 1.0) / 4.0).margin(0.003));
  CHECK(chunk[2] / 6000.0 == Approx((std::sqrt(17.0) - 1.0) / 4.0).margin(0.003));
  CHECK(seconds[0] == Approx(seconds[2]).epsilon(0.02));
}

TEST_CASE("One step with a preempted thread moves a boundary by at most the largest move",
          "[dem_core][chunk_balance]") {
  ChunkBalance balance;
  const std::vector<std::uint32_t> rows = uniform_rows(1000, 10);
  const std::vector<std::size_t> chunk = balance.chunks(rows, 2);
  const std::vector<double> seconds{1.0, 1000.0};  // the second thread lost the core for a while
  balance.observe(rows, chunk, seconds);
  REQUIRE(balance.pair_fractions().size() == 3);
  CHECK(balance.pair_fractions()[1] == Approx(0.5 + ChunkBalance::kLargestMove).margin(1e-12));
}
