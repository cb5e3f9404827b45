#pragma once
// The rows of one chunk (stream_chunk, contact_loops_streamed.hpp) with the Hertz–Mindlin pair
// law computed kPairLanes touching pairs at a time (hertz_pair_lanes.hpp). Touching pairs are
// queued in pair order, rows after rows; when kPairLanes of them wait, their laws run together and
// every queued load (theirs and the crossing pairs' between them) is added in pair order. Each
// particle therefore receives the same values in the same order as the scalar rows give it:
// the row member's sum runs in memory instead of a register, which changes no bit, and a pair's
// second member only ever receives loads from earlier rows and earlier pairs of the same row.
#include <cstdint>

#include "hertz_pair_lanes.hpp"

namespace demfit::dem_core {

/// Loads waiting to be added, in pair order: a laned pair (its batch lane) or a crossing pair's
/// first-member share (computed before the chunks, contact_loops_streamed.hpp).
class LanedRowQueue {
 public:
  LanedRowQueue(const HertzMindlinLaw& law, ContactHistory* history, ParticleState& p, const StepInputs& step)
      : law_(law), history_(history), p_(p), step_(step) {}

  void push_pair(std::uint32_t first, std::uint32_t second, std::uint32_t pair) {
    const int lane = batch_.count++;
    batch_.first[lane] = first;
    batch_.second[lane] = second;
    batch_.pair[lane] = pair;
    waiting_[waiting_count_++] = {first, second, lane, nullptr};
    if (batch_.count == kPairLanes || waiting_count_ == kWaiting) flush();
  }
  void push_crossing(std::uint32_t first, const PairLoads* loads) {
    waiting_[waiting_count_++] = {first, 0, -1, loads};
    if (waiting_count_ == kWaiting) flush();
  }
  /// Computes the queued laws and adds every waiting load, in the order queued.
  void flush() {
    if (batch_.count > 0) hertz_pair_lanes(law_, history_, p_, step_, batch_);
    for (int w = 0; w < waiting_count_; ++w) {
      const Waiting& e = waiting_[w];
      if (e.crossing != nullptr) {
        p_.force[e.first] += e.crossing->force;
        p_.torque[e.first] += e.crossing->torque_first;
        continue;
      }
      const PairLoads& loads = batch_.loads[e.lane];
      p_.force[e.first] += loads.force;
      p_.torque[e.first] += loads.torque_first;
      p_.force[e.second] -= loads.force;
      p_.torque[e.second] += loads.torque_second;
    }
    batch_.count = 0;
    waiting_count_ = 0;
  }

 private:
  struct Waiting {
    std::uint32_t first, second;
    int lane;                     ///< batch lane of a laned pair
    const PairLoads* crossing;  ///< loads of a crossing pair, else nullptr
  };
  static constexpr int kWaiting = 64;
  const HertzMindlinLaw& law_;
  ContactHistory* history_;
  ParticleState& p_;
  const StepInputs& step_;
  PairLaneBatch batch_{};
  Waiting waiting_[kWaiting]{};
  int waiting_count_ = 0;
};

/// The rows [begin, end) of stream_chunk with laned laws (requires hertz_lanes_apply): `pairs`
/// the StreamedPairSide of HertzMindlinLaw, `own` the CrossingCursor that yields the crossing
/// pairs of these rows in pair order.
template <class PairSide, class Cursor>
void stream_rows_laned(const PairSide& pairs, ParticleState& p, const StepInputs& step, std::size_t begin,
                       std::size_t end, Cursor& own) {
  const auto rows = pairs.list.row_offsets();
  const auto second = pairs.list.second();
  LanedRowQueue queue(pairs.law, pairs.history, p, step);
  for (std::size_t i = begin; i < end; ++i) {
    const Vec3 position = p.position[i];
    const double radius = p.radius[i];
    for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
      const std::uint32_t j = second[k];
      if (j >= end) {  // computed before the barrier (only the touching ones are in the buffers)
        if (const CrossingPairLoads* c = own.take(k)) queue.push_crossing(static_cast<std::uint32_t>(i), &c->loads);
        continue;
      }
      // pair_geometry's contact test
      const double r_sum = radius + p.radius[j];
      if (norm2(p.position[j] - position) >= r_sum * r_sum) {
        if (pairs.touching[k]) {
          pairs.history[k] = {};
          pairs.touching[k] = 0;
        }
        continue;
      }
      pairs.touching[k] = 1;
      queue.push_pair(static_cast<std::uint32_t>(i), j, k);
    }
  }
  queue.flush();
}

}  // namespace demfit::dem_core
