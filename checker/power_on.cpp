#include "endatsim/checker/power_on.hpp"

#include <algorithm>

#include "endatsim/protocol/timing.hpp"

namespace endatsim::checker {

namespace limit = protocol::limit;
using sim::Time;

namespace {

// More than enough for the pulses of a request before its mode bits show it is one.
constexpr std::size_t kPulsesKept = 16;
const std::string kRequestCycle = "the wake-up request cycle";

// A value within a range: the bound it came nearest to, failed if either fails.
checker::Judgement both(const checker::Judgement& a, const checker::Judgement& b) {
  checker::Judgement nearer = a.margin() <= b.margin() ? a : b;
  if (a.decision == Decision::Fail || b.decision == Decision::Fail)
    nearer.decision = Decision::Fail;
  else if (a.decision == Decision::Undecided || b.decision == Decision::Undecided)
    nearer.decision = Decision::Undecided;
  return nearer;
}

}  // namespace

void PowerOnSequence::switched_on(Time at) {
  due_ = true;
  on_at_ = at;
  fall_.reset();
  pulses_.clear();
  wake_.reset();
  rise_after_low_at_on_.reset();
}

void PowerOnSequence::clock(Time at, bool level) {
  if (!due_) return;
  if (!level) {
    fall_ = at;
    return;
  }
  if (!fall_) {
    // HIGH from a LOW that began before switching on: no pulse of the sequence, but t1 ends and
    // t2 begins here (CLOCK LOW through t1, then HIGH for t2).
    if (!rise_after_low_at_on_) rise_after_low_at_on_ = at;
    return;
  }
  pulses_.push_back({*fall_, at});
  fall_.reset();
  if (pulses_.size() > kPulsesKept) pulses_.pop_front();
}

std::optional<Time> PowerOnSequence::last_rise_before(Time t) const {
  for (auto it = pulses_.rbegin(); it != pulses_.rend(); ++it)
    if (it->rise <= t) return it->rise;
  if (rise_after_low_at_on_ && *rise_after_low_at_on_ <= t) return rise_after_low_at_on_;
  return std::nullopt;
}

std::optional<PowerOnSequence::Judgement> PowerOnSequence::request(std::uint64_t index, Time start) {
  if (!due_) return std::nullopt;
  std::erase_if(pulses_, [&](const Pulse& p) { return p.fall >= start; });
  if (wake_) {  // the request after a wake-up request cycle ends t3
    Judgement j;
    judge_t1_t2(j, wake_->frame, wake_->start, wake_->t2_from, kRequestCycle);
    judge_t3(j, index, last_rise_before(start).value_or(wake_->start), start);
    due_ = false;
    wake_.reset();
    return j;
  }
  if (pulses_.empty()) {  // no pulse: this request is the wake-up, its data not valid
    wake_ = Wake{index, start, last_rise_before(start)};
    return std::nullopt;
  }
  const Pulse pulse = pulses_.back();
  pulses_.pop_back();
  const std::optional<Time> t2_from = last_rise_before(pulse.fall);
  due_ = false;
  return judge_pulse(index, start, pulse, t2_from);
}

std::optional<PowerOnSequence::Judgement> PowerOnSequence::finish() {
  if (!due_ || !wake_) return std::nullopt;
  Judgement j;
  judge_t1_t2(j, wake_->frame, wake_->start, wake_->t2_from, kRequestCycle);
  due_ = false;
  wake_.reset();
  return j;
}

PowerOnSequence::Judgement PowerOnSequence::judge_pulse(std::uint64_t index, Time start, const Pulse& pulse,
                                                        std::optional<Time> t2_from) const {
  Judgement j;
  const Time width = pulse.rise - pulse.fall;
  j.push_back({.frame = index,
               .at = pulse.fall,
               .measured = sim::format_time(width),
               .bound = "> " + sim::format_time(limit::kPowerOnPulseMin),
               .message = "the power-on pulse is too short",
               .decision = more_than(width, limit::kPowerOnPulseMin, resolution_)});
  judge_t1_t2(j, index, pulse.fall, t2_from, "the power-on pulse");
  judge_t3(j, index, pulse.rise, start);
  return j;
}

// The wake-up (pulse or request cycle) comes after t1 and t2. CLOCK HIGH since switching on
// shows no boundary between them; after a LOW phase, the HIGH before the wake-up is t2.
void PowerOnSequence::judge_t1_t2(Judgement& j, std::uint64_t index, Time wake, std::optional<Time> t2_from,
                                  const std::string& what) const {
  j.push_back({.frame = index,
               .at = wake,
               .measured = sim::format_time(wake - on_at_) + " after switching on",
               .bound = ">= t1 + t2 = " + sim::format_time(limit::kPowerOnT1Min) + " + " + sim::format_time(limit::kPowerOnT2Min),
               .message = what + " came before t1 and t2 had passed",
               .decision = at_least(wake - on_at_, limit::kPowerOnT1Min + limit::kPowerOnT2Min, resolution_)});
  if (!t2_from) return;
  const Time t2 = wake - *t2_from;
  j.push_back({.frame = index,
               .at = wake,
               .measured = sim::format_time(t2),
               .bound = "t2 = " + sim::format_time_range(limit::kPowerOnT2Min, limit::kPowerOnT2Max),
               .message = "CLOCK was not HIGH for t2 before " + what,
               .decision = both(at_least(t2, limit::kPowerOnT2Min, resolution_), at_most(t2, limit::kPowerOnT2Max, resolution_))});
}

void PowerOnSequence::judge_t3(Judgement& j, std::uint64_t index, Time from, Time request) const {
  const Time t3 = request - from;
  j.push_back({.frame = index,
               .at = request,
               .measured = sim::format_time(t3),
               .bound = "t3 = " + sim::format_time_range(limit::kPowerOnT3Min, limit::kPowerOnT3Max),
               .message = "the first request does not follow the pulse or request cycle after t3",
               .decision = both(at_least(t3, limit::kPowerOnT3Min, resolution_), at_most(t3, limit::kPowerOnT3Max, resolution_))});
}

}  // namespace endatsim::checker
