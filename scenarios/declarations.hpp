// The link between endatsim's own models and the checker, which knows neither: the encoder's
// parameters as a datasheet would declare them, and the project's master declaring its frames.
#pragma once

#include "endatsim/checker/declarations.hpp"
#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/master/master.hpp"
#include "endatsim/slave/encoder.hpp"

namespace endatsim::scenarios {

// What a datasheet of this encoder model would say.
checker::EncoderDeclaration declared_encoder(const slave::EncoderParams& encoder);
// What the project's master says about itself.
checker::MasterDeclaration declared_master(const master::MasterParams& master);
// A master's frame in the checker's terms.
checker::DeclaredFrame declared_frame(const master::FrameResult& frame);

// Forwards the project's master's frames to the checker (attach with Master::add_observer).
class MasterDeclarations final : public master::MasterObserver {
 public:
  explicit MasterDeclarations(checker::TimingChecker& checker) : checker_(checker) {}
  void on_frame_start(const master::FrameResult& frame) override {
    if (!muted_) checker_.on_frame_start(declared_frame(frame));
  }
  void on_sample(const master::FrameResult& frame, unsigned clock, bool, bool) override {
    if (!muted_) checker_.on_sample(declared_frame(frame), clock);
  }
  bool wants_samples() const override { return !muted_; }
  void on_frame_end(const master::FrameResult& frame) override {
    if (!muted_) checker_.on_frame_end(declared_frame(frame));
  }
  // While a frame is played from a recording with the checker's part in it (frame_replay.hpp),
  // the checker is told nothing: it is put where the recorded frame left it.
  void mute(bool muted) { muted_ = muted; }
  checker::TimingChecker& checker() { return checker_; }

 private:
  checker::TimingChecker& checker_;
  bool muted_ = false;
};

}  // namespace endatsim::scenarios
