#pragma once
// Moving the per-pair contact histories to the new pair order of a neighbour-list rebuild, in
// place and in parallel. In place, because holding the old and the new history array
// at once was the peak of a dense bed's memory. In parallel, because the serial version was the
// rebuild's largest serial part on the issue-16 drum: with temporary timers, history sources plus
// carry took 0.49 ms per 2-thread rebuild serially and 0.25 ms in parallel, about 2 % of a
// 2-thread run (bench/dem_core/measured/drum_2026-12-04_nineteenth_ab_parallel_carry.txt).
//
// The moves form chains and cycles: new slot k takes the old content of source[k], and each old
// slot feeds at most one new slot. A list rebuilt with a few pairs more or less early on shifts
// everything after them, so one chain can span the whole array: splitting by chain would leave
// one thread with all the work. Instead each thread owns a contiguous range of destination slots.
// Before any write, each thread saves the old contents it will read from another thread's range
// (few: pairs move far only when particles changed places); after a barrier it moves its own
// range with the serial chain-and-cycle scheme, reading its own slots before overwriting them.
// Every slot ends with the content of its source, whatever the thread count: results are the
// same bit for bit.
#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

namespace demfit::dem_core {

/// Where a new pair's history comes from: an old pair index, with kSwappedPair set when the
/// members swapped roles (the tangential spring is then negated), or kNewPair.
inline constexpr std::uint32_t kNewPair = 0xFFFFFFFFu;
inline constexpr std::uint32_t kSwappedPair = 0x80000000u;

/// An old history as the new pair with source `s` carries it: the tangential spring (and an
/// epsd2 rolling torque) is that of the first member relative to the second, so it is negated
/// when the members swapped roles.
template <class History>
History as_carried(History h, std::uint32_t s) {
  if (s & kSwappedPair) {
    h.tangential_displacement = -h.tangential_displacement;
    if constexpr (requires { h.rolling_torque; }) h.rolling_torque = -h.rolling_torque;
  }
  return h;
}

namespace detail {

/// One thread's part of apply_pair_sources: the destination slots [begin, end) of `history`.
template <class History>
class SlotRange {
 public:
  SlotRange(const std::vector<std::uint32_t>& source, std::size_t pairs, std::vector<History>& history,
            std::uint8_t* flags, std::size_t begin, std::size_t end)
      : source_(source), pairs_(pairs), history_(history), flags_(flags), begin_(begin), end_(end) {}

  /// Before any thread writes: marks which own slots an own slot reads, saves the old contents
  /// read from other ranges (ascending destination). False if a source lies past the old pairs.
  bool prepare(std::size_t old_size) {
    std::fill(flags_ + begin_, flags_ + end_, std::uint8_t{0});
    for (std::size_t to = begin_; to < end_; ++to) {
      if (source_[to] == kNewPair) continue;
      const std::size_t from = source_[to] & ~kSwappedPair;
      if (from >= old_size) return false;
      if (own(from))
        flags_[from] |= kNeeded;
      else if (from < pairs_)  // another thread writes it: keep its old content
        foreign_.emplace_back(static_cast<std::uint32_t>(to), history_[from]);
    }
    return true;
  }

  /// After every range is prepared. Returns false if the sources were not a valid carry.
  bool move() {
    // Chains start at a slot that no own slot reads, and end at a new pair or a read outside.
    for (std::size_t k = begin_; k < end_; ++k)
      if (!(flags_[k] & kNeeded)) follow_chain(k);
    for (std::size_t start = begin_; start < end_; ++start)  // cycles: each slot read by the next
      if (!(flags_[start] & kDone) && !close_cycle(start)) return false;
    return true;
  }

 private:
  static constexpr std::uint8_t kNeeded = 1, kDone = 2;

  [[nodiscard]] bool own(std::size_t slot) const { return slot >= begin_ && slot < end_; }

  /// The old content of `to`'s source, negated spring if the members swapped.
  [[nodiscard]] History old_content(std::size_t to, std::uint32_t s) const {
    const std::size_t from = s & ~kSwappedPair;
    // Own and not yet written, or past the new end (nobody writes it): read in place.
    if (own(from) || from >= pairs_) return as_carried(history_[from], s);
    const auto it = std::lower_bound(foreign_.begin(), foreign_.end(), static_cast<std::uint32_t>(to),
                                     [](const auto& entry, std::uint32_t slot) { return entry.first < slot; });
    return as_carried(it->second, s);
  }

  void follow_chain(std::size_t to) {
    while (true) {
      flags_[to] |= kDone;
      const std::uint32_t s = source_[to];
      if (s == kNewPair) {
        history_[to] = History{};
        return;
      }
      history_[to] = old_content(to, s);
      const std::size_t from = s & ~kSwappedPair;
      if (!own(from)) return;
      to = from;  // read, so free: its own new content comes next
    }
  }

  bool close_cycle(std::size_t start) {
    const History saved = history_[start];
    std::size_t to = start;
    while (true) {
      flags_[to] |= kDone;
      const std::uint32_t s = source_[to];
      const std::size_t from = s & ~kSwappedPair;
      if (s == kNewPair || !own(from) || (from != start && (flags_[from] & kDone))) return false;
      history_[to] = as_carried(from == start ? saved : history_[from], s);
      if (from == start) return true;
      to = from;
    }
  }

  const std::vector<std::uint32_t>& source_;
  std::size_t pairs_;
  std::vector<History>& history_;
  std::uint8_t* flags_;
  std::size_t begin_, end_;
  std::vector<std::pair<std::uint32_t, History>> foreign_{};
};

}  // namespace detail

/// history (aligned with the old list, capacity >= pairs) becomes aligned with the new one: new
/// pair k takes the old history of source[k] (size pairs; each old index at most once), negated
/// tangential spring when kSwappedPair is set; a kNewPair slot starts afresh. `threads` share the
/// work; the result does not depend on them. Throws std::logic_error if the sources are not such
/// a map (history is then unspecified).
template <class History>
void apply_pair_sources_in_place(const std::vector<std::uint32_t>& source, std::size_t pairs,
                                 std::vector<History>& history, int threads) {
  if (source.size() != pairs || pairs > history.capacity())
    throw std::logic_error("pair history carry: sources and history do not match");
  const std::size_t old_size = history.size();
  if (pairs > old_size) history.resize(pairs);  // within capacity: no reallocation
  // One byte per slot, written only by the slot's owner (default-initialised: each owner clears
  // its own range, so no serial pass over all of them).
  const std::unique_ptr<std::uint8_t[]> flags(new std::uint8_t[std::max<std::size_t>(pairs, 1)]);
  const int team = pairs >= 8192 ? std::max(threads, 1) : 1;  // small lists: not worth a team
  std::vector<std::uint8_t> valid(static_cast<std::size_t>(team), 1), closed(static_cast<std::size_t>(team), 1);
#pragma omp parallel num_threads(team) if (team > 1)
  {
    const auto parts = static_cast<std::size_t>(omp_get_num_threads());
    const auto part = static_cast<std::size_t>(omp_get_thread_num());
    detail::SlotRange<History> range(source, pairs, history, flags.get(), pairs * part / parts,
                                     pairs * (part + 1) / parts);
    valid[part] = range.prepare(old_size) ? 1 : 0;
#pragma omp barrier
    // Every thread sees every range's verdict after the barrier: all move, or none does.
    if (std::find(valid.begin(), valid.end(), 0) == valid.end()) closed[part] = range.move() ? 1 : 0;
  }
  if (std::find(valid.begin(), valid.end(), 0) != valid.end())
    throw std::logic_error("pair history carry: a source past the old pairs");
  if (std::find(closed.begin(), closed.end(), 0) != closed.end())
    throw std::logic_error("pair history carry: a cycle that does not close");
  history.resize(pairs);  // shrinking keeps the capacity for the next rebuild
}

}  // namespace demfit::dem_core
