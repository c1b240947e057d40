#pragma once
// master/busy_polling.hpp — an await_not_busy operation (D297403 2.5.1, 2.6.1): frames with
// additional data 1 are polled until the busy bit it carries is reset; and how such waits ended.

#include <algorithm>
#include <cstdint>

#include "endatsim/master/frame_result.hpp"
#include "endatsim/protocol/additional_data.hpp"

namespace endatsim::master {

class BusyPolling {
 public:
  // A poll came back; `last`: the operation has no poll left. True when the wait is over: Busy
  // reset, or an answer (without error) that carries no additional data 1, where the busy bit
  // travels, so that polling on could never see it reset. A last poll that still sees Busy set
  // is a timeout.
  bool poll_ends_wait(const FrameResult& f, bool last) {
    const auto& data = f.additional_data;
    const bool ok = f.outcome == FrameOutcome::Ok;
    const auto is_1 = [](const AdditionalDatum& d) { return !protocol::is_additional_data_2(d.information()); };
    if (ok && std::any_of(data.begin(), data.end(), [&](const AdditionalDatum& d) { return is_1(d) && !d.busy(); }))
      return true;
    if (ok && std::none_of(data.begin(), data.end(), is_1)) {
      ++unreadable_;
      return true;
    }
    if (last) ++timeouts_;
    return false;
  }
  std::uint64_t timeouts() const { return timeouts_; }
  std::uint64_t unreadable() const { return unreadable_; }

 private:
  std::uint64_t timeouts_ = 0;
  std::uint64_t unreadable_ = 0;
};

}  // namespace endatsim::master
