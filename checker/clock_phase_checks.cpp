// The rows on the clock's phases inside a frame (2.3.2): t_HI, t_LO and the on-off ratio, at the
// encoder pins.
#include <string>
#include <tuple>

#include "endatsim/checker/timing_checker.hpp"

namespace endatsim::checker {
namespace {

using sim::format_time;
namespace limit = protocol::limit;

// The worst phase of a frame that fails its limit, or else the worst one undecided at the
// resolution; `count` counts the phases of that decision.
struct WorstPhase {
  Time width{0};
  unsigned clock = 0;
  Time at{0};
  unsigned count = 0;
  Decision decision = Decision::Pass;
  const char* phase = "";
  void add(Decision d, Time w, unsigned k, Time t, bool shorter_is_worse, const char* which = "") {
    if (d == Decision::Pass || (decision == Decision::Fail && d == Decision::Undecided)) return;
    if (d == Decision::Fail && decision != Decision::Fail) count = 0;
    const bool worse = count == 0 || (shorter_is_worse ? w < width : w > width);
    ++count;
    decision = d;
    if (worse) std::tie(width, clock, at, phase) = std::tuple{w, k, t, which};
  }
};

// The phase of a cut frame that was still going on at the end (WorstPhase::phase).
constexpr const char* kOpenPhase = "open";

// The phases of a frame: LOW k from FE k to RE k, HIGH k from RE k to FE k+1 (k from 1).
template <class Visit>
void for_each_phase(const std::vector<Time>& rising, const std::vector<Time>& falling, Visit visit) {
  for (std::size_t k = 0; k < rising.size() && k < falling.size(); ++k)
    visit(false, static_cast<unsigned>(k + 1), falling[k], rising[k] - falling[k]);
  for (std::size_t k = 0; k + 1 < falling.size() && k < rising.size(); ++k)
    visit(true, static_cast<unsigned>(k + 1), rising[k], falling[k + 1] - rising[k]);
}

}  // namespace

// t_HI and t_LO: the 0.2 us minimum without delay compensation (with it the on-off ratio row takes
// its place: docs/model.md §7), t_HI's 10 us maximum, and t_LO's maximum from this encoder's
// datasheet ("see encoder specifications").
void TimingChecker::check_pulse_widths(const PinFrame& f) {
  if (f.falling.empty()) return;
  // A lone LOW pulse longer than the wake-up pulse's 125 ns while the power-on sequence waits for its
  // request may be that pulse, judged by the power-on row (2.3.3), not by t_LO of a transmission's
  // clock. A shorter one is a runt, and t_LO judges it.
  if (f.rising.size() == 1 && f.falling.size() == 1 && power_on_.due() &&
      f.rising.front() - f.falling.front() > limit::kPowerOnPulseMin)
    return;
  constexpr std::size_t low_row = protocol::check::row_index(check::kPulseLow);
  constexpr std::size_t high_row = protocol::check::row_index(check::kPulseHigh);
  judge(low_row);
  judge(high_row);
  const Time r = params_.resolution;
  const bool minimum = !f.header.compensated;
  WorstPhase low, high, long_high, long_low;
  LeastMargin low_margin, high_margin, long_low_margin;
  for_each_phase(f.rising, f.falling, [&](bool is_high, unsigned k, Time at, Time w) {
    LeastMargin& margin = is_high ? high_margin : low_margin;
    const auto noted = [&](const Judgement& j, LeastMargin& m) {
      m.add(j);
      return j.decision;
    };
    if (minimum) (is_high ? high : low).add(noted(at_least(w, limit::kPulseWidthMin, r), margin), w, k, at, true);
    if (is_high) {
      long_high.add(noted(at_most(w, limit::kPulseHighMax, r), margin), w, k, at, false);
    } else if (encoder_.t_lo_max && (k > 1 || !f.header.compensated)) {
      // With compensation the first LOW phase is t_ST, which has its own row.
      long_low.add(noted(at_most(w, *encoder_.t_lo_max, r), long_low_margin), w, k, at, false);
    }
  });
  // A frame that the end of the run or capture cut with CLOCK LOW: that LOW phase lasted at least
  // until the end, so it fails a maximum it already exceeds (a master hung mid-frame); shorter, it
  // is not judged (its length is not known).
  // A lone LOW while the power-on sequence waits may be its wake-up pulse, as above.
  const bool wake_up = f.falling.size() == 1 && power_on_.due();
  if (frame_cut_by_end_ == f.header.index && f.falling.size() > f.rising.size() && encoder_.t_lo_max && !wake_up &&
      (f.falling.size() > 1 || !f.header.compensated)) {
    const Time w = cut_at_ - f.falling.back();
    if (at_most(w, *encoder_.t_lo_max, r).decision == Decision::Fail)
      long_low.add(Decision::Fail, w, static_cast<unsigned>(f.falling.size()), f.falling.back(), false, kOpenPhase);
  }
  low_margin.note_to(margins_, low_row);
  high_margin.note_to(margins_, high_row);
  long_low_margin.note_to(margins_, low_row, LimitOf::ThisEncoder);
  // What is reported is worded only when something is (every frame passes in a clean run).
  if (low.decision == Decision::Pass && high.decision == Decision::Pass && long_high.decision == Decision::Pass &&
      long_low.decision == Decision::Pass)
    return;
  const auto emit = [&](const WorstPhase& w, std::string_view name, const std::string& bound, const std::string& spec,
                        const char* what, Verdict verdict = Verdict::Both) {
    report_unless_passed(w.decision,
        {.check = std::string(name),
         .spec = spec,
         .where = ObservationPoint::EncoderPins,
         .time = w.at,
         .frame = f.header.index,
         .clock = w.clock,
         .measured = (w.phase == kOpenPhase ? ">= " : "") + format_time(w.width),
         .limit = bound,
         .severity = Severity::Error,
         .message = std::string(what) + " (" + std::to_string(w.count) + " pulse(s) in this frame; worst shown" +
                    (w.phase == kOpenPhase ? ": still LOW where the run or capture ended inside the frame)" : ")"),
         .verdict = verdict});
  };
  const std::string at_least_min = ">= " + format_time(limit::kPulseWidthMin);
  emit(low, check::kPulseLow, at_least_min, "2.3.2 t_LO minimum 0.2 us (without delay compensation)",
       "CLOCK LOW phase too short");
  emit(high, check::kPulseHigh, at_least_min, "2.3.2 t_HI minimum 0.2 us (without delay compensation)",
       "CLOCK HIGH phase too short");
  emit(long_high, check::kPulseHigh, "<= " + format_time(limit::kPulseHighMax), "2.3.2 t_HI maximum 10 us",
       "CLOCK HIGH phase inside a frame too long: the encoder may end the transfer (t_m)");
  if (encoder_.t_lo_max)
    emit(long_low, check::kPulseLow, "<= " + format_time(*encoder_.t_lo_max) + " (this encoder's t_LO maximum)",
         "2.3.2 t_LO maximum (see encoder specifications)", "CLOCK LOW phase longer than this encoder's datasheet allows",
         Verdict::ThisEncoder);
}

// 2.3.2 "On-off ratio error": 0 % without, +/-10 % with delay compensation. With compensation each
// phase is at least 50 % - 10 % of the frame's period (the first LOW phase is t_ST). Without it
// 2.1.1 allows another duty cycle and reads Figure 2 as f_c = 1/(2 t_min): where the cable, not
// the 2 MHz, bounds f_c, the shorter phase must be at least t_D max for the cable, or data taken
// at the end of a short HIGH phase have not arrived (docs/model.md §7, §9).
void TimingChecker::check_on_off_ratio(const PinFrame& f) {
  if (f.falling.empty() || f.rising.size() < 2) return;
  Time min{0};
  if (f.header.compensated) {
    if (f.header.f_c <= 0) return;
    min = sim::period_of(f.header.f_c) * (50 - limit::kOnOffRatioErrorPercent) / 100;
  } else {
    if (wires_only_ && measurement_seen_) return;  // the wires cannot tell it is uncompensated
    const double cable = cable_length_m();
    const Time period_min = limit::uncompensated_period_min(cable);  // 2 t_D max, or 2 MHz's period
    if (period_min <= sim::period_of(limit::kFcMaxWithoutCompensation)) return;  // 2 MHz bounds f_c: t_HI, t_LO
    // A period shorter than 2 t_D is the f_c row's; this row adds what a 1:1 clock would not show.
    if (f.header.f_c <= 0 || sim::period_of(f.header.f_c) < period_min) return;
    min = limit::data_delay_max(cable);
  }
  constexpr std::size_t row = protocol::check::row_index(check::kOnOffRatio);
  judge(row);
  WorstPhase worst;
  LeastMargin margin;
  for_each_phase(f.rising, f.falling, [&](bool is_high, unsigned k, Time at, Time w) {
    if (!is_high && k == 1 && f.header.compensated) return;  // t_ST
    const Judgement j = at_least(w, min, params_.resolution);
    margin.add(j);
    worst.add(j.decision, w, k, at, true, is_high ? "HIGH" : "LOW");
  });
  margin.note_to(margins_, row);
  if (worst.decision == Decision::Pass) return;  // worded only when reported
  std::string bound, spec;
  if (f.header.compensated) {
    bound = ">= " + format_time(min) + " (50 % - 10 % of T = " + format_time(sim::period_of(f.header.f_c)) + ")";
    spec = "2.3.2 on-off ratio error (+/-10 % with delay compensation)";
  } else {
    bound = ">= t_D max = " + format_time(min) + " for the cable";
    spec = "2.3.2 note 4 and 2.1.1, Figure 2 (another duty cycle: f_c <= 1 / (2 t_min), without delay compensation)";
  }
  report_unless_passed(worst.decision,
      {.check = std::string(check::kOnOffRatio),
       .spec = spec,
       .where = ObservationPoint::EncoderPins,
       .time = worst.at,
       .frame = f.header.index,
       .clock = worst.clock,
       .measured = format_time(worst.width),
       .limit = bound,
       .severity = Severity::Error,
       .message = "CLOCK " + std::string(worst.phase) + " phase too short for the clock's period ("
                  + std::to_string(worst.count) + " phase(s) in this frame; worst shown)"});
}

}  // namespace endatsim::checker
