#include "endatsim/checker/delay_measurements.hpp"

#include <algorithm>
#include <cstdlib>

#include "endatsim/protocol/timing.hpp"

namespace endatsim::checker {

void DelayMeasurements::measured(std::uint64_t frame, sim::Time t_d) {
  if (closed_) {  // a new round of measurements after compensated frames: a new line, or power
    run_.clear();
    judged_period_.reset();
    closed_ = false;
  }
  run_.push_back({frame, t_d});
  ever_ = true;
}

namespace {

enum class Agreement : std::uint8_t { Pass, Fail, Undecided };

// The latest n measurements against T/8 of their mean (2.1.2), kept exact: |n d_i - sum| / n <= T / 8
// is 8 |n d_i - sum| <= n T. Each t_D is known to within r, so the deviation is to within 2r.
template <typename Run>
Agreement agree(const Run& run, std::size_t n, sim::Time period, sim::Time resolution, std::size_t* worst) {
  const auto first = run.end() - static_cast<std::ptrdiff_t>(n);
  std::int64_t sum = 0;
  for (auto it = first; it != run.end(); ++it) sum += it->t_d.count();
  const auto count = static_cast<std::int64_t>(n);
  const std::int64_t limit = count * period.count();
  constexpr std::int64_t kDivisor = protocol::limit::kMeasurementSpreadPeriodDivisor;
  const std::int64_t margin = 2 * kDivisor * count * resolution.count();
  std::int64_t worst_scaled = -1;
  for (auto it = first; it != run.end(); ++it) {
    const std::int64_t scaled = kDivisor * std::llabs(count * it->t_d.count() - sum);
    if (scaled > worst_scaled) {
      worst_scaled = scaled;
      if (worst != nullptr) *worst = static_cast<std::size_t>(it - run.begin());
    }
  }
  if (worst_scaled + margin <= limit) return Agreement::Pass;
  if (worst_scaled - margin > limit) return Agreement::Fail;
  return Agreement::Undecided;
}

}  // namespace

std::optional<DelayMeasurements::Judgement> DelayMeasurements::compensated(sim::Time period, sim::Time resolution) {
  if (run_.empty() || (judged_period_ && period >= *judged_period_)) {
    closed_ = closed_ || !run_.empty();
    return std::nullopt;
  }
  closed_ = true;
  judged_period_ = period;
  Judgement j;
  j.measurements = run_.size();
  j.first_frame = run_.front().frame;
  j.enough = run_.size() >= protocol::limit::kMeasurementsMin;
  j.limit = period / protocol::limit::kMeasurementSpreadPeriodDivisor;
  // The latest three (or all there are) are reported; any latest three or more may carry it.
  const std::size_t shown = std::min<std::size_t>(run_.size(), protocol::limit::kMeasurementsMin);
  const Agreement latest = agree(run_, shown, period, resolution, &j.worst);
  std::int64_t sum = 0;
  for (std::size_t i = run_.size() - shown; i < run_.size(); ++i) sum += run_[i].t_d.count();
  const auto n = static_cast<std::int64_t>(shown);
  j.deviation = sim::Time{(std::llabs(n * run_[j.worst].t_d.count() - sum) + n / 2) / n};
  j.worst_frame = run_[j.worst].frame;
  bool undecided = latest == Agreement::Undecided;
  j.consistent = latest == Agreement::Pass;
  for (std::size_t k = protocol::limit::kMeasurementsMin + 1; k <= run_.size() && !j.consistent; ++k) {
    const Agreement a = agree(run_, k, period, resolution, nullptr);
    j.consistent = a == Agreement::Pass;
    undecided = undecided || a == Agreement::Undecided;
  }
  j.undecided = !j.consistent && undecided;
  return j;
}

}  // namespace endatsim::checker
