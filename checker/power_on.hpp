// D297403 2.3.3, the power-on conditions as CLOCK shows them at the encoder ("the information
// refers to measurements at the encoder"). The figure is lost; the reading used (docs/model.md
// §8): after the supply comes up, CLOCK at a valid level for t1 >= 800 ms, HIGH for t2 = 80 ..
// 120 ms, then at least one LOW pulse longer than 125 ns *or one request cycle*
// (whose data are not valid), then HIGH for t3 = 380 .. 420 ms before the first request.
//
// Judged once per switch-on: at the start of a run or capture that shows it, and again after
// every power interruption. A request is a frame that carries a mode command; a wake-up by a
// request cycle is judged when the next request comes, which ends t3.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "endatsim/checker/decision.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::checker {

class PowerOnSequence {
 public:
  struct Finding {
    std::uint64_t frame = 0;  // the request it concerns
    sim::Time at{0};
    std::string measured;
    std::string bound;
    std::string message;
    checker::Judgement decision;  // the measured value against the limit it came nearest to
  };
  using Judgement = std::vector<Finding>;

  explicit PowerOnSequence(sim::Time resolution) : resolution_(resolution) {}

  // The encoder's supply came up (or the run begins with switching on) at `at`.
  void switched_on(sim::Time at);
  // A CLOCK edge at the encoder's pins.
  void clock(sim::Time at, bool level);
  // A request (frame `index`) whose FE1 reached the encoder's pins at `start`; a judgement when
  // this request ends the power-on sequence.
  std::optional<Judgement> request(std::uint64_t index, sim::Time start);
  // The run ended while a wake-up request cycle waited for the request after it: t1 and t2
  // are judged, t3 was not seen.
  std::optional<Judgement> finish();
  bool due() const { return due_; }
  // The wake-up request cycle waiting for the request after it, which its judgement names.
  std::optional<std::uint64_t> waiting_request() const {
    return wake_ ? std::optional<std::uint64_t>(wake_->frame) : std::nullopt;
  }

 private:
  struct Pulse {
    sim::Time fall;
    sim::Time rise;
  };
  // The wake-up by a request cycle, waiting for the request that ends t3.
  struct Wake {
    std::uint64_t frame;
    sim::Time start;
    std::optional<sim::Time> t2_from;
  };
  Judgement judge_pulse(std::uint64_t index, sim::Time start, const Pulse& pulse, std::optional<sim::Time> t2_from) const;
  void judge_t1_t2(Judgement& j, std::uint64_t index, sim::Time wake, std::optional<sim::Time> t2_from,
                   const std::string& what) const;
  void judge_t3(Judgement& j, std::uint64_t index, sim::Time from, sim::Time request) const;
  std::optional<sim::Time> last_rise_before(sim::Time t) const;

  sim::Time resolution_;
  bool due_ = false;
  sim::Time on_at_{0};
  std::optional<sim::Time> fall_;
  // The latest LOW pulses since switching on: a request's own pulses come before it is known
  // to be one (its mode bits), so a few are kept and the request's dropped.
  std::deque<Pulse> pulses_;
  std::optional<Wake> wake_;
  // CLOCK's first rise after switching on from a LOW it had then: the start of t2.
  std::optional<sim::Time> rise_after_low_at_on_;
};

}  // namespace endatsim::checker
