#include "endatsim/master/careful_policy.hpp"

namespace endatsim::master {

CarefulPolicy::CarefulPolicy(const CarefulMaster& params, bool delay_compensation)
    : params_(params), delay_compensation_(delay_compensation) {}

void CarefulPolicy::line_changed() {
  if (params_.remeasure_after_line_change && delay_compensation_) remeasure_due_ = true;
}

void CarefulPolicy::power_interrupted(bool additional_data_selected) {
  if (params_.remeasure_after_power_interruption && delay_compensation_) remeasure_due_ = true;
  if (params_.reselect_after_power_interruption && additional_data_selected) reselect_due_ = true;
}

void CarefulPolicy::frame_done(const FrameResult& f) {
  if (f.measurement) return;
  const auto o = f.outcome;
  const bool failed = o == FrameOutcome::CrcError || o == FrameOutcome::NoStartBit || o == FrameOutcome::Type1Error ||
                      o == FrameOutcome::EchoMismatch || o == FrameOutcome::TooFewClocks;
  failures_in_a_row_ = failed ? failures_in_a_row_ + 1 : 0;
  const unsigned k = params_.remeasure_after_crc_errors;
  if (k != 0 && failures_in_a_row_ >= k && delay_compensation_) {
    remeasure_due_ = true;
    failures_in_a_row_ = 0;
  }
}

bool CarefulPolicy::retry(const FrameResult& f, bool position_read) {
  const bool failed = f.outcome != FrameOutcome::Ok && f.outcome != FrameOutcome::Type2Error;
  if (!position_read || f.measurement || !failed || retries_left_ == 0) {
    retries_left_ = params_.retries;
    return false;
  }
  --retries_left_;
  ++retries_done_;
  return true;
}

CarefulPolicy::Interruption CarefulPolicy::take_interruption() {
  const Interruption due{.remeasure = remeasure_due_, .reselect = reselect_due_};
  if (due.remeasure) ++remeasurements_;
  remeasure_due_ = reselect_due_ = false;
  return due;
}

}  // namespace endatsim::master
