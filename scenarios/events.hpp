// Carries out a scenario's events: changes and faults of the line and the encoder at a
// time, at a frame or at a clock edge of a frame. It tells the master model (if the run has one)
// and the checker what the installation would tell them (2.1.2: a new delay measurement is due
// after a change of the transmission path or a power interruption). A master outside endatsim
// (an HDL master in co-simulation) is told nothing; its frames are announced by whoever finds
// them on the wires, through frame_started.
#pragma once

#include <boost/random/mersenne_twister.hpp>

#include "endatsim/scenarios/scenario.hpp"

namespace endatsim::scenarios {

class EventDriver final : public master::MasterObserver {
 public:
  // `bit_period`: a bit flip's default width and a random bit error's, one period of the
  // master's clock. `master` may be null.
  EventDriver(sim::Kernel& kernel, line::Line& line, slave::Encoder& encoder, master::Master* master,
              checker::TimingChecker& checker, const std::vector<Event>& events, std::uint64_t seed, Time bit_period);
  EventDriver(const EventDriver&) = delete;
  EventDriver& operator=(const EventDriver&) = delete;

  void on_frame_start(const master::FrameResult& frame) override { frame_started(frame.index); }
  // The master's frame `index` (delay-measurement frames included, from 0) begins now.
  void frame_started(std::uint64_t index);
  void on_sample(const master::FrameResult&, unsigned, bool, bool) override {}
  bool wants_samples() const override { return false; }
  void on_frame_end(const master::FrameResult&) override {}

  std::uint64_t random_bit_errors() const { return random_bit_errors_; }  // bits flipped at random
  // No event is set off by a frame from `frame` on or by a clock edge (events at a time are in
  // the kernel's queue).
  bool quiet_from(std::uint64_t frame) const;
  // How many times an event has acted so far (applied, ended, its supply or probe back): a frame
  // recorded while one acted is not the frame before it, even where the event changed nothing.
  std::uint64_t actions() const { return actions_; }
  // The events (their indices in the list) that have not acted yet: at the end of a run, those
  // the run ended before (a time or a frame past its end).
  std::vector<EventNotActed> not_acted() const;

 private:
  struct Armed {
    std::size_t event;
    unsigned edges = 0;
  };
  void apply(std::uint64_t index);
  void end_of(std::uint64_t index);
  void release_probe() {
    ++actions_;
    encoder_.set_probe_deflected(false);
  }
  void power_back() {
    ++actions_;
    if (master_ != nullptr) master_->encoder_power_interrupted();
  }
  // A run whose encoder has no run-up models neither the first switch-on nor this one (2.3.3).
  void supply_back() {
    ++actions_;
    checker_.on_switched_on(encoder_.params().startup_time > sim::Time::zero());
  }
  void on_master_clock(std::uint64_t level) { on_rising_edge(line::ObservationPoint::MasterPins, level); }
  void on_encoder_clock(std::uint64_t level) { on_rising_edge(line::ObservationPoint::EncoderPins, level); }
  void on_rising_edge(line::ObservationPoint end, std::uint64_t level);
  void apply_to_line(const Event& e, std::uint64_t index);
  void apply_to_encoder(const Event& e);

  sim::Kernel& kernel_;
  line::Line& line_;
  slave::Encoder& encoder_;
  master::Master* master_;
  checker::TimingChecker& checker_;
  const std::vector<Event>& events_;
  Time period_;
  boost::random::mt19937_64 rng_;
  std::vector<Armed> armed_[2];                 // frame events waiting for their clock edge, per end
  std::vector<std::size_t> random_[2];          // random_bit_errors events in force, per end
  std::uint64_t random_bit_errors_ = 0;
  std::uint64_t actions_ = 0;
  std::vector<bool> acted_;  // per event
  bool counts_edges_ = false;
};

}  // namespace endatsim::scenarios
