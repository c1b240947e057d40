// What a live run and a check of its capture must agree on: the findings of every row that is
// judged from the wires and observable in the capture, counted per check.
#pragma once

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "endatsim/checker/timing_checker.hpp"

namespace endatsim::test_support {

// floating_data is left out: its samples are the master's, which a capture does not hold.
inline std::map<std::string, std::size_t> wire_rows(const std::vector<checker::Violation>& violations,
                                                    const std::vector<checker::RowConformance>& observable) {
  std::map<std::string, std::size_t> counts;
  for (const auto& v : violations) {
    const auto row = protocol::timing_row(v.check);
    const bool seen = std::any_of(observable.begin(), observable.end(), [&](const auto& c) {
      return c.check == v.check && c.status != checker::RowConformance::Status::NotObservable;
    });
    if (row && row->evidence == protocol::Evidence::Wires && seen && v.check != checker::check::kFloatingData)
      ++counts[v.check];
  }
  return counts;
}

}  // namespace endatsim::test_support
