#include "endatsim/scenarios/capture_check.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "endatsim/capture/capture.hpp"
#include "endatsim/line/line.hpp"
#include "endatsim/protocol/additional_data.hpp"
#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/report.hpp"
#include "endatsim/sim/text.hpp"

namespace endatsim::scenarios {
namespace {

using sim::Time;

// The cable's one-way delay, by which the master's enable recorded at its own connector reaches
// the encoder's (the line's own delay per metre).
Time master_enable_delay(const CaptureCheckOptions& o) {
  line::LineParams cable;
  cable.cable_length_m = o.cable_m.value_or(0);
  if (o.cable_delay_per_m) cable.cable_delay_per_m = *o.cable_delay_per_m;
  return cable.cable_delay();
}

// The capture's changes, one at a time at their recorded times, onto the pins of a line
// without delays: CLOCK from the master; DATA from the encoder while its recorded enable is on,
// from the master otherwise (without a recorded enable, always from the master: the checker
// then knows the enables are not observable). 'x' releases DATA.
//
// Changes at one instant: CLOCK's first, and the others once its edge has reached the encoder's
// pins, as a clocked circuit sees them (a flip-flop takes the level before its edge). So an
// encoder that releases DATA at FE1 itself or drives it at FE9 itself (t_z = 0, t_OE = 0) does
// it after that edge, not before it, whatever order the lines of a VCD time step or the hops of
// the line would give. (The bits on DATA are taken by time, not by this order: a change at the
// instant of the rising edge that takes a bit counts for it, as the model's encoder takes it.)
class Replay {
 public:
  Replay(sim::Kernel& kernel, line::Line& line, capture::Reader& reader, const CaptureCheckOptions& o,
         checker::TimingChecker& checker, checker::FrameDecoder& log_decoder, CaptureCheckResult& result)
      : kernel_(kernel),
        checker_(checker),
        master_(line.master()),
        encoder_(line.encoder()),
        reader_(reader),
        decoder_(log_decoder),
        result_(result),
        active_low_(o.enable_active_low),
        progress_(o.progress),
        on_frame_(o.on_frame),
        simulator_(!reader.sampled() && !o.resolution),
        timer_(kernel, sim::bind<&Replay::step>(this)) {
    clock_written_ = master_.clock_out.read();
    // After the checker's own listener there, which is already in place.
    line.pins(line::ObservationPoint::EncoderPins).clock.on_change(sim::bind<&Replay::after_clock>(this));
    clock_ = capture::find_signal(reader, o.clock);
    data_ = capture::find_signal(reader, o.data);
    std::vector<std::uint32_t> wanted{clock_, data_};
    if (o.data_enable) {
      enable_ = capture::find_signal(reader, *o.data_enable);
      wanted.push_back(*enable_);
    }
    if (o.data_out) {
      out_ = capture::find_signal(reader, *o.data_out);
      wanted.push_back(*out_);
    }
    if (o.master_data_enable) {
      master_enable_ = capture::find_signal(reader, *o.master_data_enable);
      wanted.push_back(*master_enable_);
      if (o.master_enable_at_master) master_enable_delay_ = master_enable_delay(o);
    }
    if (o.power) {
      power_ = capture::find_signal(reader, *o.power);
      wanted.push_back(*power_);
    }
    std::vector<std::uint32_t> distinct = wanted;
    std::sort(distinct.begin(), distinct.end());
    if (std::adjacent_find(distinct.begin(), distinct.end()) != distinct.end())
      throw capture::CaptureError(reader.path() + ": CLOCK, DATA, the enable and the supply must be different signals");
    reader.select(wanted);
    if (reader_.next(next_)) {
      offset_ = next_.time < Time::zero() ? -next_.time : Time::zero();  // pre-trigger samples
      schedule();
    }
  }

 private:
  void schedule() { timer_.start(next_.time + offset_ - kernel_.now()); }

  void step() {
    // The log's decoder takes the encoder's bits where the checker's does (a measured round trip).
    if (const auto rt = checker_.measured_round_trip()) decoder_.set_clock_to_data(*rt);
    do {
      checker_.raise_resolution(reader_.uncertainty());
      if (next_.signal == clock_) apply(next_);
      else held_.push_back(next_);
      if ((++result_.changes & 0xFFFF) == 0) {
        if (const int signal = interrupt_signal(); signal != 0)
          throw Interrupted(reader_.path() + ": interrupted by " + signal_name(signal) + ": not judged", signal);
        if (progress_) progress_(reader_.bytes_read(), reader_.bytes_total());
      }
      result_.end = next_.time + offset_;
      if (!reader_.next(next_)) {
        release_held();
        drain();
        return;
      }
    } while (next_.time + offset_ == kernel_.now());
    release_held();
    drain();
    schedule();
  }

  // The instant's other changes: now if CLOCK does not move (also when it changed and changed back:
  // a pulse of no width commits nothing), else from after_clock().
  void release_held() {
    clock_moved_ = clock_written_ != master_.clock_out.read();
    if (clock_moved_) return;
    for (const capture::Change& c : held_) apply(c);
    held_.clear();
  }

  void after_clock() {
    if (!clock_moved_) return;
    clock_moved_ = false;
    release_held();
    drain();
  }

 public:
  // The capture's last instant, on the kernel's time line.
  Time end() const { return std::max(reader_.end() + offset_, result_.end); }

  // The frames the decoder has finished: counted, passed on, the first few kept.
  void drain() {
    for (auto& f : decoder_.take_finished()) {
      ++result_.frames_decoded;
      if (f.clean()) ++result_.frames_clean;
      result_.words_bad_crc += f.bad_words;
      if (f.unknown_bits != 0 && result_.data_unknown_bits == 0) result_.data_unknown_first_frame = f.index;
      result_.data_unknown_bits += f.unknown_bits;
      if (f.learnt_position_bits != 0) {
        result_.position_bits = f.learnt_position_bits;
        result_.position_bits_learnt_at = f.index;
      }
      if (on_frame_) on_frame_(f);
      if (result_.frames.size() < kMaxFramesKept) result_.frames.push_back(std::move(f));
    }
  }

 private:

  void apply(const capture::Change& c) {
    const Time now = kernel_.now();
    if (power_ && c.signal == *power_) {
      // Switched on: a rise from LOW. A supply HIGH from the capture's start shows no switch-on.
      if (c.value == '1' && power_level_ == '0') checker_.on_switched_on();
      power_level_ = c.value;
      return;
    }
    if (c.signal == clock_) {
      // An unknown clock level changes nothing; one after CLOCK had a level is a master's fault
      // the summary names (an RTL master's X before its reset is not).
      if (c.value == 'x') {
        if (clock_known_ && result_.clock_unknown++ == 0) result_.clock_unknown_first = now;
        if (!clock_known_ && c.time == Time::zero()) unknown_from_start_ = true;
        return;
      }
      if (!clock_known_) begin(c);
      clock_written_ = c.value == '1';
      master_.clock_out.write(clock_written_);
      decoder_.on_clock(now, c.value == '1');
      return;
    }
    if (out_) {
      apply_split(c);
      return;
    }
    if (c.signal == data_) {
      data_level_ = c.value;
    } else if (master_enable_ && c.signal == *master_enable_) {
      if (master_enable_delay_ != Time::zero()) {  // recorded at the master's connector: it arrives later
        master_enable_in_flight_.push_back(c.value);
        kernel_.schedule(master_enable_delay_, sim::bind<&Replay::master_enable_arrives>(this));
        return;
      }
      master_on_ = on(c.value);
    } else {
      encoder_on_ = on(c.value);
    }
    drive_data();
    // An x is the encoder's own (driven) while its recorded enable is on, whichever changed last.
    if (c.signal == data_ && data_level_ != 'x') decoder_.on_data(now, data_level_ == '1');
    else if (data_level_ == 'x') decoder_.on_data_unknown(now, enable_ && encoder_on_);
  }

  bool on(char v) const { return v != 'x' && ((v == '1') != active_low_); }

  // The master's enable, recorded at its own connector, one cable delay later at the encoder's.
  void master_enable_arrives() {
    master_on_ = on(master_enable_in_flight_.front());
    master_enable_in_flight_.pop_front();
    drive_data();
  }

  // DATA's level and who drives it, onto the line.
  void drive_data() {
    const bool known = data_level_ != 'x';
    const bool encoder_drives = enable_ && encoder_on_;
    encoder_.data_out.write(data_level_ == '1');
    master_.data_out.write(data_level_ == '1');
    if (master_enable_) {  // both enables recorded: each driver as its enable says, both at once a contention
      encoder_.data_enable.write(encoder_drives && known);
      master_.data_enable.write(master_on_ && known);
    } else if (encoder_drives) {  // the driver that goes off first, so that the line never sees both on
      master_.data_enable.write(false);
      encoder_.data_enable.write(known);
    } else {
      encoder_.data_enable.write(false);
      master_.data_enable.write(known);
    }
  }

  // CLOCK's first level. A simulator's VCD shows its simulation from the start at time 0, where
  // a CLOCK HIGH is the line at rest, also when CLOCK was unknown from time 0 until then (an RTL
  // master in reset); any other capture may begin inside a frame, whose edges the checker skips
  // until CLOCK has been HIGH for t_m (docs/analyzer.md, "Where a capture begins").
  void begin(const capture::Change& c) {
    clock_known_ = true;
    const bool at_rest = simulator_ && (c.time == Time::zero() || unknown_from_start_) && c.value == '1';
    checker_.begin_capture(kernel_.now(), at_rest);
    if (!at_rest) decoder_.begin_capture(kernel_.now());
  }

  // An RTL master's data_out, data_in and data_oe: the line at its connector carries data_out
  // while data_oe is on, else what data_in shows (without data_oe, data_in is taken as the bus:
  // a receiver that hears both directions).
  void apply_split(const capture::Change& c) {
    if (c.signal == data_) in_level_ = c.value;
    else if (c.signal == *out_) out_level_ = c.value;
    else master_on_ = c.value != 'x' && ((c.value == '1') != active_low_);
    const char level = enable_ && master_on_ ? out_level_ : in_level_;
    if (level == data_level_) return;
    data_level_ = level;
    const bool known = level != 'x';
    encoder_.data_enable.write(false);  // the master's connector: one level, put on the line from its side
    master_.data_out.write(level == '1');
    master_.data_enable.write(known);
    if (known) decoder_.on_data(kernel_.now(), level == '1');
    else decoder_.on_data_unknown(kernel_.now());
  }

  sim::Kernel& kernel_;
  checker::TimingChecker& checker_;
  line::Line::MasterSide master_;
  line::Line::EncoderSide encoder_;
  capture::Reader& reader_;
  checker::FrameDecoder& decoder_;
  CaptureCheckResult& result_;
  bool active_low_;
  const std::function<void(std::uint64_t, std::uint64_t)>& progress_;
  const std::function<void(const checker::WireFrame&)>& on_frame_;
  bool simulator_;  // exact event times: a simulator's VCD (no --resolution)
  bool clock_known_ = false;
  bool unknown_from_start_ = false;  // CLOCK was x at time 0
  sim::Timer timer_;
  std::uint32_t clock_ = 0;
  std::uint32_t data_ = 0;
  std::optional<std::uint32_t> enable_;
  std::optional<std::uint32_t> out_;  // an RTL master's data_out (then data_ is its data_in)
  std::optional<std::uint32_t> master_enable_;  // the master's DATA driver enable, with one DATA wire
  std::optional<std::uint32_t> power_;
  char power_level_ = 'x';
  char in_level_ = '1';
  char out_level_ = '1';
  bool master_on_ = false;
  Time master_enable_delay_{0};
  std::deque<char> master_enable_in_flight_;
  capture::Change next_;
  std::vector<capture::Change> held_;  // this instant's changes other than CLOCK's
  bool clock_written_ = true;          // the level last written to CLOCK
  bool clock_moved_ = false;           // CLOCK changes at this instant: held_ waits for its edge
  Time offset_{0};
  char data_level_ = '1';
  bool encoder_on_ = false;
};

using sim::hex_h;

}  // namespace

bool CaptureCheckResult::conforms() const {
  return std::all_of(conformance.begin(), conformance.end(),
                     [](const checker::RowConformance& c) { return c.violations + c.undecided == 0; });
}

std::size_t CaptureCheckResult::undecided() const {
  std::size_t n = 0;
  for (const auto& c : conformance) n += c.undecided;
  return n;
}

CaptureCheckResult check_capture(const CaptureCheckOptions& o) {
  CaptureCheckResult result;
  result.file = o.file;
  const auto reader = capture::open(o.file);
  result.resolution = reader->resolution();
  result.timescale = reader->timescale();

  sim::Kernel kernel;
  line::LineParams lp;
  lp.cable_length_m = 0;
  lp.master = lp.encoder = line::TransceiverParams{Time::zero(), Time::zero(), Time::zero(), Time::zero()};
  line::Line line(kernel, lp);
  checker::CheckerParams params = o.checker;
  params.driver_enables_observable = o.data_enable.has_value() && !o.data_out;
  params.master_enable_observable = o.master_data_enable.has_value() && o.data_enable && !o.data_out;
  params.cable_length_m = o.cable_m.value_or(0);
  result.cable_m = *params.cable_length_m;
  result.position_bits = o.encoder.position_bits;
  result.cable_given = o.cable_m.has_value();
  checker::EncoderDeclaration encoder = o.encoder;
  result.at = o.at;
  result.both_enables = params.master_enable_observable;
  if (o.master_enable_at_master && !o.cable_m)
    throw capture::CaptureError(o.file + ": the master's enable recorded at its connector needs the cable's length");
  if (result.both_enables && o.master_enable_at_master) result.master_enable_delay = master_enable_delay(o);
  if (o.at == CaptureCheckOptions::At::Master) {
    if (!o.cable_m) throw capture::CaptureError(o.file + ": a capture at the master's connector needs the cable's length");
    if (o.data_enable && !o.data_out)
      throw capture::CaptureError(o.file + ": --data-enable names the encoder's driver enable, which a capture at the "
                                           "master's connector does not hold");
    // The encoder's bits show at the master one round trip after the rising edge that sends them.
    const line::LineParams model;
    encoder.output_delay = o.t_d.value_or(o.encoder.output_delay + model.cable_delay_per_m * static_cast<std::int64_t>(
                                                                     std::llround(2 * *o.cable_m)));
  } else {
    params.round_trip_observable = false;
  }
  params.max_findings_per_check = kMaxFindingsPerCheck;
  params.recorded_at = o.at == CaptureCheckOptions::At::Master ? line::ObservationPoint::MasterPins
                                                                : line::ObservationPoint::EncoderPins;
  params.round_trip_given = o.at != CaptureCheckOptions::At::Master || o.t_d.has_value();
  params.resolution = o.resolution.value_or(reader->uncertainty());
  result.uncertainty = params.resolution;
  result.declared = encoder;
  result.round_trip_given = params.round_trip_given;
  checker::TimingChecker checker(kernel, line, encoder, {}, params);
  checker::FrameDecoder log(checker::DecoderParams{
      .position_bits = encoder.position_bits, .clock_to_data = encoder.output_delay, .t_m = encoder.t_m});
  Replay replay(kernel, line, *reader, o, checker, log, result);
  kernel.run();
  checker.end_capture(replay.end());
  checker.finish();
  result.uncertainty = checker.resolution();
  log.finish(replay.end());
  replay.drain();
  result.violations = checker.violations();
  // The replay's line has no delays: both of its ends are the one connector the capture recorded.
  if (o.at == CaptureCheckOptions::At::Master)
    for (auto& v : result.violations) v.where = line::ObservationPoint::MasterPins;
  result.conformance = checker.conformance();
  result.conclusion = checker.conclusion();
  result.findings_not_kept = checker.findings_not_kept();
  result.edges_before_first_frame = checker.edges_before_first_frame();
  result.frame_cut_by_end = checker.frame_cut_by_end();
  const bool found_wrong = std::any_of(result.conformance.begin(), result.conformance.end(),
                                       [](const checker::RowConformance& c) { return c.violations + c.undecided != 0; });
  // A capture in which CLOCK never framed anything judges nothing: almost always the wrong signal or an
  // empty recording, so it is bad input rather than a pass. Frames without a clean answer still had their
  // clock, turnaround and mode bits judged; the summary says so (see capture_summary).
  if (result.frames_decoded == 0 && !found_wrong)
    throw capture::CaptureError(o.file + ": no EnDat frame began on CLOCK '" + o.clock + "' (no falling edge after " +
                                "CLOCK rested HIGH, or DATA '" + (o.data_out ? *o.data_out + "' / '" + o.data : o.data) +
                                "' never answered): nothing to judge; are these the right signals?");
  return result;
}

std::string capture_log(const CaptureCheckResult& r) {
  std::string out;
  for (const auto& f : r.frames) out += frame_log_line(f);
  return out;
}

std::string frame_log_line(const checker::WireFrame& f) {
  std::ostringstream out;
  out << "#" << f.index << " " << sim::format_time(f.fe1) << " ";
  if (!f.command) {
    out << "mode bits " << (f.mode_bits_seen == protocol::frame_position::kModeBits ? hex_h(f.mode_bits, 2) : "incomplete")
        << " (no mode command), " << f.clocks << " clocks\n";
    return out.str();
  }
  const auto& info = protocol::info(*f.command);
  out << info.key;
  if (f.payload) out << " address " << hex_h(protocol::payload_address(*f.payload), 2) << " parameter " << hex_h(protocol::payload_parameter(*f.payload), 4);
  if (f.start_bit_clock == 0) {
    out << ": no start bit, " << f.clocks << " clocks\n";
    return out.str();
  }
  out << ": start bit RE" << f.start_bit_clock;
  if (!f.answer_complete) {
    out << ", answer incomplete after " << f.clocks << " clocks\n";
    return out.str();
  }
  using protocol::Field;
  const auto field = [&](Field x) { return f.fields[static_cast<std::size_t>(x)]; };
  switch (info.answer) {
    case protocol::AnswerFormat::Position:
      out << ", F1 " << field(Field::Error1);
      if (info.version == protocol::EndatVersion::V2_2) out << " F2 " << field(Field::Error2);
      out << ", position " << field(Field::Position);
      break;
    case protocol::AnswerFormat::TestValues: out << ", test value " << hex_h(field(Field::TestValue), 10); break;
    case protocol::AnswerFormat::Parameter:
      out << ", echo " << hex_h(field(Field::Address), 2) << " " << hex_h(field(Field::Parameter), 4);
      if (f.refused()) out << " (type II, A2: the address returned inverted, the access refused)";
      break;
  }
  out << ", CRC " << (f.crc_ok ? "ok" : "BAD");
  if (f.unknown_bits != 0)
    out << " (" << f.unknown_bits << " bit(s) read while DATA was unknown (x), the first on clock " << f.first_unknown_clock
        << ": not to be trusted)";
  for (const auto& d : f.additional_data)
    out << ", additional data I=" << (d.status & protocol::AdditionalDataStatus::kInformation) << " status " << hex_h(d.status, 2) << " data " << hex_h(d.data, 4)
        << " CRC " << (d.crc_ok ? "ok" : "BAD");
  if (f.supplement) out << ", supplement " << hex_h(protocol::payload_address(*f.supplement), 2) << " " << hex_h(protocol::payload_parameter(*f.supplement), 4);
  if (f.continuous_words != 0) {
    out << ", " << f.continuous_words << " further continuous-clock word(s)";
    if (f.bad_words != 0) out << " (" << f.bad_words << " with a BAD CRC)";
    out << ":";
    for (std::size_t k = 0; k < f.words.size(); ++k)
      out << (k == 0 ? " " : "; ") << "position " << f.words[k].fields[static_cast<std::size_t>(Field::Position)] << " CRC "
          << (f.words[k].crc_ok ? "ok" : "BAD");
    if (f.continuous_words > f.words.size()) out << "; " << f.continuous_words - f.words.size() << " more not listed";
  }
  if (f.learnt_position_bits != 0)
    out << "; word 13" << (f.command == protocol::ModeCommand::EncoderReceiveReset ? " as written, now active" : "")
        << ": the position has " << f.learnt_position_bits << " bits";
  out << "\n";
  return out.str();
}

namespace {

// A VCD's own timescale beside the resolution; one finer than the picosecond is why the
// resolution is a picosecond.
std::string timescale_note(const std::string& timescale) {
  if (timescale.empty()) return "";
  const bool rounded = timescale.size() >= 2 && timescale.compare(timescale.size() - 2, 2, "fs") == 0;
  return " (timescale " + timescale + (rounded ? ", times rounded to the picosecond" : "") + ")";
}

}  // namespace

void write_capture_summary(std::ostream& out, const CaptureCheckResult& r, bool verbose) {
  const bool failed = std::any_of(r.conformance.begin(), r.conformance.end(),
                                  [](const checker::RowConformance& c) { return c.violations != 0; });
  out << (failed ? "FAIL " : r.undecided() != 0 ? "UNDECIDED " : "PASS ") << r.file << "\n";
  out << "  " << r.changes << " level changes over " << sim::format_time(r.end) << "; ";
  const std::string timescale = r.timescale.empty() ? sim::format_time(r.resolution) : r.timescale;
  if (r.uncertainty == Time::zero())
    out << "event times exact (timescale " << timescale << ")";
  else
    out << "resolution " << sim::format_time(r.uncertainty) << timescale_note(r.timescale)
        << ": limits closer than that to a measured value are undecided";
  out << "; frames decoded: " << r.frames_decoded << " (" << r.frames_clean << " with a complete answer and a good CRC"
      << (r.data_unknown_bits != 0 ? ", every bit known" : "") << ")\n";
  if (r.words_bad_crc != 0)
    out << "  " << r.words_bad_crc << " further continuous-clock word(s) with a BAD CRC (2.3.1; listed in the log)\n";
  if (r.clock_unknown != 0)
    out << "  CLOCK unknown (x) " << r.clock_unknown << " time(s) after it had a level, first at "
        << sim::format_time(r.clock_unknown_first)
        << ": read as the level before; a master must drive CLOCK at a known level throughout (2.3)\n";
  if (r.data_unknown_bits != 0)
    out << "  DATA unknown (x) where " << r.data_unknown_bits << " bit(s) of the frames were read, first in frame #"
        << r.data_unknown_first_frame << ": read as the level before; those frames are not counted as clean\n";
  if (r.edges_before_first_frame != 0)
    out << "  capture begins inside a frame: " << r.edges_before_first_frame
        << " edges before the first frame not judged (a frame begins once CLOCK has been HIGH for t_m)\n";
  if (r.frame_cut_by_end)
    out << "  capture ends inside frame #" << *r.frame_cut_by_end
        << ": its clock count and start-bit polling not judged (CLOCK was not HIGH for t_m after its last pulse)\n";
  if (r.frames_clean == 0 && r.data_unknown_bits != 0)
    out << "  no frame was clean: the ones with a complete answer and a good CRC had bits read while DATA was unknown "
           "(x, above), so position, CRC, additional data and the rows timed from them were not judged\n";
  else if (r.frames_clean == 0)
    out << "  no frame had a complete answer with a good CRC: position, CRC, additional data and the rows timed "
           "from them were not judged; are these the right signals, and is --encoder's position width right?"
        << (r.at == CaptureCheckOptions::At::Master && !r.round_trip_given
                ? " At the master's connector the encoder's bits are looked for one round trip after their edges: "
                  "without a delay measurement in the capture, give it with --t-d."
                : "")
        << "\n";
  out << "  position " << r.position_bits << " bits";
  if (r.position_bits_learnt_at)
    out << ", from word 13 in frame #" << *r.position_bits_learnt_at << " (read there, or written and activated "
        << "by that reset; frames before it with the declared width)\n";
  else
    out << " as declared (--encoder); a read of word 13 in the capture would show the encoder's own\n";
  if (r.cable_given)
    out << "  cable " << r.cable_m << " m: t_D's bound, t_ST beyond 100 m and f_c without compensation follow it\n";
  else
    out << "  cable not given (--cable): taken as 0 m, so f_c without compensation is held to 2 MHz only, not to "
           "1 / (2 t_D) of a longer cable\n";
  out << "  judged from the wires at the " << (r.at == CaptureCheckOptions::At::Master ? "master's" : "encoder's")
      << " connector; rows that need the master's declaration (sampling window, t_D used, measurement frames) are not "
         "observable in a capture\n";
  if (r.master_enable_delay)
    out << "  the master's DATA enable, recorded at its connector, judged " << sim::format_time(*r.master_enable_delay)
        << " later at the encoder's (the cable's one-way delay)\n";
  else if (r.both_enables && r.cable_m > 0)
    out << "  both DATA enables are judged as at the " << (r.at == CaptureCheckOptions::At::Master ? "master's" : "encoder's")
        << " connector: an enable recorded at the other end is off by the cable's delay, and floating_data or "
           "bus_contention around a turnaround may come from that rather than from the drivers\n";
  if (verbose) {
    out << capture_log(r);
    if (r.frames_decoded > r.frames.size())
      out << "  " << r.frames_decoded - r.frames.size() << " further frame(s) decoded, not listed (--log lists all)\n";
  }
  write_violations(out, r.violations, r.conformance, verbose);
  if (r.findings_not_kept != 0)
    out << "  " << r.findings_not_kept << " further finding(s) beyond the first " << kMaxFindingsPerCheck
        << " of a check are counted in the conformance table, not listed\n";
  write_verdict(out, r.conclusion, r.violations);
  write_relaxations(out, r.conformance);
  write_conformance(out, r.conformance);
}

nlohmann::json wire_frames_json(const std::vector<checker::WireFrame>& wire_frames) {
  using nlohmann::json;
  json frames = json::array();
  for (const auto& f : wire_frames) {
    json j{{"index", f.index}, {"fe1_ps", f.fe1.count()}, {"clocks", f.clocks}};
    if (f.command) j["command"] = std::string(protocol::info(*f.command).key);
    if (f.payload) j["payload"] = *f.payload;
    if (f.refused()) j["type2"] = true;
    if (f.start_bit_clock != 0) j["start_bit_clock"] = f.start_bit_clock;
    if (f.answer_complete) {
      j["crc_ok"] = f.crc_ok;
      j["position"] = f.fields[static_cast<std::size_t>(protocol::Field::Position)];
      json ad = json::array();
      for (const auto& d : f.additional_data) ad.push_back({{"status", d.status}, {"data", d.data}, {"crc_ok", d.crc_ok}});
      j["additional_data"] = ad;
      if (f.continuous_words != 0) {
        json words = json::array();
        for (const auto& w : f.words)
          words.push_back({{"position", w.fields[static_cast<std::size_t>(protocol::Field::Position)]}, {"crc_ok", w.crc_ok}});
        j["continuous_words"] = f.continuous_words;
        j["continuous_words_bad_crc"] = f.bad_words;
        j["words"] = words;  // the first WireFrame::kMaxWordsKept
      }
      if (f.learnt_position_bits != 0) j["learnt_position_bits"] = f.learnt_position_bits;
    }
    if (f.supplement) j["supplement"] = *f.supplement;
    if (f.unknown_bits != 0) {
      j["unknown_bits"] = f.unknown_bits;
      j["first_unknown_clock"] = f.first_unknown_clock;
    }
    frames.push_back(j);
  }
  return frames;
}

namespace {

// What the frames were decoded and the rows judged with, for a decoder that reads the same capture.
nlohmann::json declared_json(const checker::EncoderDeclaration& e) {
  using nlohmann::json;
  return {{"position_bits", e.position_bits},
          {"clock_to_data_ps", e.output_delay.count()},
          {"t_m_ps", e.t_m.count()},
          {"t_m_short_ps", e.t_m_short ? json(e.t_m_short->count()) : json(nullptr)},
          {"short_t_m_selected", e.short_t_m_selected},
          {"t_r_ps", e.t_r.count()}};
}

}  // namespace

nlohmann::json capture_json(const CaptureCheckResult& r) {
  using nlohmann::json;
  const json frames = wire_frames_json(r.frames);
  return {{"file", r.file},       {"at", r.at == CaptureCheckOptions::At::Master ? "master" : "encoder"}, {"resolution_ps", r.resolution.count()}, {"timescale", r.timescale}, {"uncertainty_ps", r.uncertainty.count()},
          {"undecided", r.undecided()}, {"end_ps", r.end.count()},
          {"changes", r.changes}, {"conforms", r.conforms()},              {"frames", frames},
          {"frames_decoded", r.frames_decoded}, {"frames_clean", r.frames_clean}, {"words_bad_crc", r.words_bad_crc}, {"position_bits", r.position_bits},
          {"declared", declared_json(r.declared)},
          {"position_bits_learnt_at", r.position_bits_learnt_at ? json(*r.position_bits_learnt_at) : json(nullptr)},
          {"frames_not_kept", r.frames_decoded - r.frames.size()},
          {"edges_before_first_frame", r.edges_before_first_frame},
          {"clock_unknown", r.clock_unknown},
          {"data_unknown_bits", r.data_unknown_bits},
          {"frame_cut_by_end", r.frame_cut_by_end ? json(*r.frame_cut_by_end) : json(nullptr)},
          {"master_enable_delay_ps", r.master_enable_delay ? json(r.master_enable_delay->count()) : json(nullptr)},
          {"cable_m", r.cable_given ? json(r.cable_m) : json(nullptr)},
          {"violations", violations_json(r.violations)}, {"findings_not_kept", r.findings_not_kept},
          {"verdict", verdict_json(r.conclusion)},
          {"conformance", conformance_json(r.conformance)}};
}

}  // namespace endatsim::scenarios
