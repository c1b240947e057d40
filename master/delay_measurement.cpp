#include "endatsim/master/delay_measurement.hpp"

#include <algorithm>

#include <boost/random/uniform_int_distribution.hpp>
#include <cstdlib>

#include "endatsim/protocol/timing.hpp"

namespace endatsim::master {
namespace {

// 2.1.2: the counter starts at each RE after 10 periods, the earliest start bit's.
constexpr unsigned kFirstCounterClock = protocol::frame_position::kEarliestStartBit;

// Ticks of a clock with period `tick` and phase `phase` up to time t: floor((t - phase) / tick).
std::int64_t ticks(Time t, Time phase, Time tick) {
  const std::int64_t d = (t - phase).count();
  return d >= 0 ? d / tick.count() : -((-d + tick.count() - 1) / tick.count());
}

}  // namespace

DelayMeasurement::DelayMeasurement(const DelayMeasurementParams& params, Hertz f_c) : params_(params), f_c_(f_c) {}

Time DelayMeasurement::counter_tick() const { return sim::period_of(params_.f_e != 0 ? params_.f_e : protocol::limit::kMeasurementCounterFactor * f_c_); }

void DelayMeasurement::begin() {
  active_ = true;
  round_ = 1;
  counts_.clear();
}

void DelayMeasurement::frame_started(bool measurement, boost::random::mt19937_64& rng) {
  running_ = false;
  captured_.reset();
  if (measurement && params_.counter_phase == CounterPhase::FreeRunning) {
    boost::random::uniform_int_distribution<std::int64_t> phase(0, counter_tick().count() - 1);
    counter_phase_ = Time{phase(rng)};
  }
}

void DelayMeasurement::clock_rose(Time now, unsigned clock) {
  if (!active_ || clock < kFirstCounterClock || captured_) return;
  counter_start_ = now;
  running_ = true;
}

void DelayMeasurement::data_rose(Time now) {
  if (!active_ || !running_ || captured_) return;
  const Time tick = counter_tick();
  captured_ = params_.counter_phase == CounterPhase::FreeRunning
                  ? ticks(now, counter_phase_, tick) - ticks(counter_start_, counter_phase_, tick)
                  : (now - counter_start_) / tick;
  running_ = false;
}

std::optional<Time> DelayMeasurement::take_count() {
  if (!captured_) return std::nullopt;
  counts_.push_back(*captured_);
  return counter_tick() * *captured_;
}

void DelayMeasurement::frame_recorded(Time start) {
  recent_starts_.push_back(start);
  while (recent_starts_.size() > std::max<std::size_t>(params_.count, 1)) recent_starts_.pop_front();
}

Time DelayMeasurement::round_start(Time now) const {
  return recent_starts_.size() >= params_.count && params_.count != 0 ? recent_starts_.front() : now;
}

const DelayMeasurementResult& DelayMeasurement::finish_round(Time start) {
  const Time tick = counter_tick();
  DelayMeasurementResult r;
  r.start = start;
  r.rounds = round_;
  r.counts = counts_;
  r.counter_period = tick;
  const auto n = static_cast<std::int64_t>(counts_.size());
  std::int64_t sum = 0;
  for (auto c : counts_) sum += c;
  if (counts_.size() < params_.count) {
    r.reason = "only " + std::to_string(counts_.size()) + " of " + std::to_string(params_.count) +
               " measurement frames gave a start bit with a valid CRC";
  } else {
    // 2.1.2: each measured value within 1/8 of the clock period (at the intended f_c) of the mean.
    const Time eighth = sim::period_of(f_c_) / protocol::limit::kMeasurementSpreadPeriodDivisor;
    for (std::size_t i = 0; i < counts_.size() && r.reason.empty(); ++i) {
      const Time deviation = tick * std::abs(n * counts_[i] - sum) / n;
      if (deviation > eighth)
        r.reason = "measurement " + std::to_string(i + 1) + " deviates " + sim::format_time(deviation) +
                   " from the mean (limit T/8 = " + sim::format_time(eighth) + ", 2.1.2)";
    }
  }
  r.accepted = r.reason.empty();
  if (r.accepted) {
    const std::int64_t half = params_.counter_phase == CounterPhase::EdgeAligned ? tick.count() * n / 2 : 0;
    r.t_d = Time{(sum * tick.count() + half + n / 2) / n};
  }
  ++results_count_;
  if (results_.size() < keep_) results_.push_back(r);
  last_ = std::move(r);
  return *last_;
}

bool DelayMeasurement::next_round() {
  if (last_ && !last_->accepted && round_ < params_.max_rounds) {
    ++round_;
    counts_.clear();
    return true;
  }
  active_ = false;
  return false;
}

}  // namespace endatsim::master
