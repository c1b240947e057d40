#pragma once
// sim/record_log.hpp — the records a model leaves of a run (its frames), every one counted but
// only a bounded number kept, so that a run of millions of frames keeps its memory flat: the first
// n (what a report shows of how the run began) or the most recent n to 2n (what a new record is
// matched against). Trimming in batches keeps adding a record O(1) amortized.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <utility>
#include <vector>

namespace endatsim::sim {

template <class Record>
class RecordLog {
 public:
  enum class Keep : std::uint8_t { First, Recent };
  explicit RecordLog(Keep keep) : keep_(keep), limit_(keep == Keep::First ? SIZE_MAX : SIZE_MAX / 2) {}

  // Keep at most the first n, or the most recent n to 2n (at least one: the record being written).
  void keep(std::size_t n) { limit_ = keep_ == Keep::Recent ? std::max<std::size_t>(n, 1) : n; }

  // A record that is not kept is not copied.
  template <class R>
  void add(R&& r) {
    ++count_;
    if (keep_ == Keep::First) {
      if (records_.size() < limit_) records_.push_back(std::forward<R>(r));
      return;
    }
    if (records_.size() >= 2 * limit_)
      records_.erase(records_.begin(), records_.end() - static_cast<std::ptrdiff_t>(limit_ - 1));
    records_.push_back(std::forward<R>(r));
  }

  // The records kept, oldest first.
  const std::vector<Record>& records() const { return records_; }
  // The record added last, to be completed (kept by Keep::Recent whatever the limit).
  Record& last() { return records_.back(); }
  // Every record added, kept or not.
  std::uint64_t count() const { return count_; }

 private:
  Keep keep_;
  std::size_t limit_;
  std::vector<Record> records_;
  std::uint64_t count_ = 0;
};

}  // namespace endatsim::sim
