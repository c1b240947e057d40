// `endatsim check`: a waveform recorded elsewhere (an HDL simulator's VCD, a logic analyzer's
// sigrok session or CSV) judged by the same checker as a simulated run, from the wires alone.
// The capture's CLOCK and DATA at the encoder's connector are replayed edge by edge, at their
// recorded times, onto a line without delays; the checker finds the frames on the wires
// (checker/frame_decoder.hpp) and judges every row that needs nothing but wires.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "endatsim/checker/timing_checker.hpp"

namespace endatsim::scenarios {

struct CaptureCheckOptions {
  // Where CLOCK and DATA were recorded. At the master's connector the encoder's bits come one
  // round trip (t_D) after each rising edge, and t_D itself is measured; at the encoder's they
  // come after its own delay, and t_D is not observable.
  enum class At : std::uint8_t { Encoder, Master } at = At::Encoder;
  std::optional<double> cable_m;   // the cable's length: t_D's bound, t_ST, f_c over 100 m
  std::optional<sim::Time> cable_delay_per_m;  // its delay per metre (default the line's 5 ns/m)
  std::optional<sim::Time> t_d;    // at the master: the round trip (default: the encoder's
                                   // delay + twice the cable at 5 ns/m)
  std::string file;
  std::string clock;                        // signal names: full path or an unambiguous suffix
  std::string data;
  std::optional<std::string> data_enable;   // the encoder's DATA driver enable at its pins, if recorded
  // The master's DATA driver enable, if recorded as well (one DATA wire; with data_enable, both
  // drivers on at once is a bus contention). Taken at the same instants as the encoder's: the
  // cable's one-way delay between the two ends is not added (docs/analyzer.md).
  std::optional<std::string> master_data_enable;
  // It was recorded at the master's connector (a master's own enable, endatsim's
  // master_data_driver_enable): it is moved by the cable's one-way delay onto the encoder's.
  bool master_enable_at_master = false;
  // An RTL master's split DATA: `data` is then its data_in, this its data_out and `data_enable`
  // its data_oe (at the master's connector).
  std::optional<std::string> data_out;
  bool enable_active_low = false;
  // The encoder's supply, HIGH while powered, if recorded (a supply monitor or power-good
  // line): each rise from LOW is a switch-on after which 2.3.3 is judged again.
  std::optional<std::string> power;
  // What the encoder declares (a profile or a scenario's encoder): position width, t_m, t_R,
  // and its clock-to-data delay at the connector (receiver and driver included) in output_delay.
  checker::EncoderDeclaration encoder;
  checker::CheckerParams checker;
  // How far each edge may be from its true time. Default: a logic analyzer's sample period for
  // sampled captures (sigrok, CSV), exact for a simulator's VCD; set it for a VCD that a logic
  // analyzer wrote.
  std::optional<sim::Time> resolution;
  // Called now and then with the bytes read and the file's size (progress on a terminal).
  std::function<void(std::uint64_t read, std::uint64_t total)> progress;
  // Called with each frame as soon as it is decoded (a log streamed while the capture is read).
  std::function<void(const checker::WireFrame&)> on_frame;
};

// Decoded frames kept in a result (for --json); all are counted, and all reach `on_frame`.
inline constexpr std::size_t kMaxFramesKept = 10000;

struct CaptureCheckResult {
  std::string file;
  sim::Time resolution{0};   // the capture's timescale (at least 1 ps) or sample period
  std::string timescale;     // a VCD's timescale as the file gives it ("1 fs")
  sim::Time uncertainty{0};  // what the checker allowed each edge (0: exact)
  CaptureCheckOptions::At at = CaptureCheckOptions::At::Encoder;
  sim::Time end{0};  // the last change
  std::uint64_t changes = 0;
  std::vector<checker::WireFrame> frames;  // the first kMaxFramesKept
  std::uint64_t frames_decoded = 0;
  std::uint64_t frames_clean = 0;       // with a complete answer and a good CRC
  std::uint64_t words_bad_crc = 0;      // further continuous-clock words whose CRC failed
  unsigned position_bits = 0;           // as declared, or as the last read of word 13 showed
  checker::EncoderDeclaration declared;  // the encoder as judged (--encoder, --clock-to-data, --t-d)
  std::optional<std::uint64_t> position_bits_learnt_at;  // the frame that read word 13
  double cable_m = 0;                   // the cable the limits assume (0 m unless given)
  bool cable_given = false;
  bool both_enables = false;            // the master's DATA enable was given as well as the encoder's
  std::vector<checker::Violation> violations;
  std::vector<checker::RowConformance> conformance;  // counts every finding
  checker::Conclusion conclusion;                     // over every finding
  std::uint64_t findings_not_kept = 0;                // beyond kMaxFindingsPerCheck of a check
  std::uint64_t edges_before_first_frame = 0;         // CLOCK edges of a frame the capture began inside
  std::uint64_t clock_unknown = 0;                    // times CLOCK went unknown (x) after its first level
  sim::Time clock_unknown_first{0};                      // ... the first of them
  bool round_trip_given = true;                        // at the master's connector: --t-d given
  std::uint64_t data_unknown_bits = 0;                // bits of frames read while DATA was unknown (x)
  std::uint64_t data_unknown_first_frame = 0;         // ... the first frame with one
  std::optional<std::uint64_t> frame_cut_by_end;      // the last frame, if the capture's end cut it
  std::optional<sim::Time> master_enable_delay;  // how far the master's enable was moved (master_enable_at_master)
  bool conforms() const;           // no violation of error severity and nothing undecided
  std::size_t undecided() const;   // findings undecided at the capture's resolution
};

// Findings kept per check of a capture (all are counted in the conformance table).
inline constexpr std::size_t kMaxFindingsPerCheck = 1000;

// Throws capture::CaptureError for unreadable or malformed captures, missing signals, and a
// capture in which no frame has a complete answer with a good CRC and nothing was found wrong
// (wrong signals, or no EnDat traffic: nothing to judge is never a pass).
CaptureCheckResult check_capture(const CaptureCheckOptions& options);

// One line per decoded frame: time, mode command, payload, answer fields, CRC, additional data.
std::string frame_log_line(const checker::WireFrame& f);
// The lines of the frames kept in `r`.
std::string capture_log(const CaptureCheckResult& r);
// The summary `endatsim check` prints.
void write_capture_summary(std::ostream& out, const CaptureCheckResult& r, bool verbose);
nlohmann::json capture_json(const CaptureCheckResult& r);
// Decoded frames as capture_json lists them.
nlohmann::json wire_frames_json(const std::vector<checker::WireFrame>& frames);

}  // namespace endatsim::scenarios
