// The in-place, parallel carry of pair histories across a list rebuild
// (pair_history_permutation.hpp) against the obvious out-of-place copy, on source maps shaped
// like a rebuild's: long shifted runs (pairs gained or lost early on), pairs that moved far
// (particles that changed places), swapped members, new pairs, and cycles.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include "demfit/dem_core/contact_geometry.hpp"
#include "demfit/dem_core/pair_history_permutation.hpp"

using demfit::dem_core::apply_pair_sources_in_place;
using demfit::dem_core::ContactHistory;
using demfit::dem_core::kNewPair;
using demfit::dem_core::kSwappedPair;

namespace {

/// Old histories with distinct contents (slot k holds (k, -k, 0.5 k)).
std::vector<ContactHistory> numbered(std::size_t count, std::size_t capacity) {
  std::vector<ContactHistory> h;
  h.reserve(capacity);
  for (std::size_t k = 0; k < count; ++k) {
    const auto x = static_cast<double>(k);
    h.push_back(ContactHistory{{x, -x, 0.5 * x}});
  }
  return h;
}

/// What a copy into a new array gives.
std::vector<ContactHistory> copied(const std::vector<ContactHistory>& old, const std::vector<std::uint32_t>& source) {
  std::vector<ContactHistory> next(source.size());
  for (std::size_t k = 0; k < source.size(); ++k) {
    if (source[k] == kNewPair) continue;
    next[k] = old[source[k] & ~kSwappedPair];
    if (source[k] & kSwappedPair) next[k].tangential_displacement = -next[k].tangential_displacement;
  }
  return next;
}

/// A rebuild-like map from `old_pairs` old slots to `new_pairs` new ones: the old pairs in order
/// with a few dropped and a few new pairs inserted (shifted runs), some exchanged with a far
/// partner (particles that changed places), some with swapped members.
std::vector<std::uint32_t> rebuild_like(std::size_t old_pairs, std::size_t new_pairs, unsigned seed) {
  std::mt19937 random(seed);
  std::vector<std::uint32_t> kept;
  for (std::uint32_t k = 0; k < old_pairs; ++k)
    if (random() % 50 != 0) kept.push_back(k);  // 2 % of the pairs end
  std::vector<std::uint32_t> source;
  std::size_t next_kept = 0;
  while (source.size() < new_pairs) {
    const bool fresh = next_kept == kept.size() || random() % 40 == 0;
    source.push_back(fresh ? kNewPair : kept[next_kept++]);
  }
  for (int moves = 0; moves < static_cast<int>(new_pairs / 100); ++moves)
    std::swap(source[random() % new_pairs], source[random() % new_pairs]);
  for (auto& s : source)
    if (s != kNewPair && random() % 7 == 0) s |= kSwappedPair;
  return source;
}

void require_same(const std::vector<ContactHistory>& a, const std::vector<ContactHistory>& b) {
  REQUIRE(a.size() == b.size());
  std::size_t differing = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (!(a[k].tangential_displacement.x == b[k].tangential_displacement.x &&
          a[k].tangential_displacement.y == b[k].tangential_displacement.y &&
          a[k].tangential_displacement.z == b[k].tangential_displacement.z))
      ++differing;
  CHECK(differing == 0);
}

}  // namespace

TEST_CASE("Histories carried in place on 1 2 and 3 threads equal a copy into a new array", "[dem_core][carry]") {
  for (const auto& [old_pairs, new_pairs] :
       {std::pair<std::size_t, std::size_t>{40000, 40000}, {40000, 41500}, {41500, 38000}, {3000, 3100}}) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const std::vector<std::uint32_t> source = rebuild_like(old_pairs, new_pairs, seed);
      const auto old = numbered(old_pairs, std::max(old_pairs, new_pairs));
      const auto expected = copied(old, source);
      for (int threads = 1; threads <= 3; ++threads) {
        INFO("old " << old_pairs << " new " << new_pairs << " seed " << seed << " threads " << threads);
        auto history = old;
        history.reserve(std::max(old_pairs, new_pairs));
        apply_pair_sources_in_place(source, new_pairs, history, threads);
        require_same(history, expected);
      }
    }
  }
}

TEST_CASE("Pure cycles and a chain across the whole array are carried in place", "[dem_core][carry]") {
  const std::size_t pairs = 20000;
  // A rotation by one (one cycle through every slot, across both threads' ranges), then a shift
  // by one with a new pair in front (one chain through every slot).
  std::vector<std::uint32_t> rotation(pairs), shift(pairs);
  for (std::size_t k = 0; k < pairs; ++k) rotation[k] = static_cast<std::uint32_t>((k + 1) % pairs);
  shift[0] = kNewPair;
  for (std::size_t k = 1; k < pairs; ++k) shift[k] = static_cast<std::uint32_t>(k - 1);
  // Pairwise exchanges inside each half (2-cycles that stay within a thread's range).
  std::vector<std::uint32_t> exchanges(pairs);
  std::iota(exchanges.begin(), exchanges.end(), 0u);
  for (std::size_t k = 0; k + 1 < pairs; k += 2) std::swap(exchanges[k], exchanges[k + 1]);
  for (const auto* source : {&rotation, &shift, &exchanges}) {
    const auto old = numbered(pairs, pairs);
    const auto expected = copied(old, *source);
    for (int threads = 1; threads <= 2; ++threads) {
      auto history = old;
      apply_pair_sources_in_place(*source, pairs, history, threads);
      require_same(history, expected);
    }
  }
}

TEST_CASE("A source past the old pairs is refused before anything moves", "[dem_core][carry]") {
  const std::size_t pairs = 10000;
  std::vector<std::uint32_t> source(pairs);
  std::iota(source.begin(), source.end(), 0u);
  source[pairs / 2] = static_cast<std::uint32_t>(pairs + 5);
  for (int threads = 1; threads <= 2; ++threads) {
    auto history = numbered(pairs, pairs);
    const auto before = history;
    REQUIRE_THROWS_AS(apply_pair_sources_in_place(source, pairs, history, threads), std::logic_error);
    require_same(history, before);
  }
}
