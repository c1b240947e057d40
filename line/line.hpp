// line/ — the RS-485 link between master (subsequent electronics) and encoder, spec 2.1:
// CLOCK from master to encoder, DATA both ways (half duplex). Each end has a transceiver
// with driver, driver-enable/disable and receiver delays; the cable adds a delay per metre.
//
//   master logic --driver--> [master pins] --cable--> [encoder pins] --receiver--> encoder logic
//
// Defaults make the round trip seen by the master (clock edge out -> data edge back)
// equal the spec's bound t_D = 0.2 us + 0.01 us/m x L (2.3.2) together with the encoder's
// own clock-to-data delay (slave::EncoderParams::output_delay, 20 ns):
// 40 (master driver) + 20 (encoder receiver) + 20 (encoder logic) + 20 (encoder driver)
// + 100 (master receiver) = 200 ns, plus 2 x 5 ns/m of cable. The encoder turns DATA around
// (falling edge at its pins -> its driver on or off there: receiver + logic + enable or disable
// delay) in 60 ns, within one clock period up to 16 MHz (t_z, t_OE, 2.3.2 note 6).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "endatsim/sim/parameter.hpp"
#include "endatsim/sim/sim.hpp"

namespace endatsim::line {

using sim::Time;

struct TransceiverParams {
  Time driver_delay;    // logic input -> level on the pins
  Time enable_delay;    // driver enable -> pins driven
  Time disable_delay;   // driver disable -> pins released (high impedance)
  Time receiver_delay;  // level on the pins -> logic output
};

struct LineParams {
  // Cable length in metres and one-way propagation delay per metre (docs/model.md §11:
  // 0.01 us/m in the t_D formula is the round trip, so ~5 ns/m one way).
  double cable_length_m = 1.0;
  Time cable_delay_per_m = sim::ns(5);
  TransceiverParams master{sim::ns(40), sim::ns(30), sim::ns(30), sim::ns(100)};
  TransceiverParams encoder{sim::ns(20), sim::ns(20), sim::ns(20), sim::ns(20)};
  // Level a true fail-safe receiver reads on undriven DATA (docs/model.md §11: HIGH).
  bool failsafe_level = true;

  static constexpr double kMaxCableLengthM = 300.0;  // 2.1.2: "up to 300 m on request"
  static constexpr Time kMaxCableDelayPerM = sim::ns(20);
  static constexpr Time kMaxTransceiverDelay = sim::us(1);

  Time cable_delay() const;
  // Throws std::invalid_argument naming the parameter and its limit.
  void validate() const;
};

// The scalar keys of "line" and of its transceiver objects, one row each (sim/parameter.hpp):
// the loader reads them, validate() checks their ranges, the schema and docs/parameters.md come
// from them.
std::span<const sim::Parameter<LineParams>> line_parameters();
std::span<const sim::Parameter<TransceiverParams>> transceiver_parameters();

enum class ObservationPoint : std::uint8_t { MasterPins, EncoderPins };
enum class Wire : std::uint8_t { Clock, Data };
std::string_view to_string(ObservationPoint p);

// Two drivers on DATA at once, as seen at one end's pins: both ends, or (several encoders on
// one bus, 2.10) two encoders at the encoder end.
struct Contention {
  ObservationPoint where;
  Time start;
  Time end;  // Time::max() while still going on
  bool between_encoders = false;
  std::uint64_t sequence = 0;  // 0, 1, 2 ... in the order the line's contentions began
};
// Told of each contention twice: as it begins (end Time::max()) and as it ends.
using ContentionListener = std::function<void(const Contention&)>;

class PinFault;

class Line {
 public:
  Line(sim::Kernel& kernel, const LineParams& params);
  ~Line();
  Line(const Line&) = delete;
  Line& operator=(const Line&) = delete;

  // What the master logic drives and sees.
  struct MasterSide {
    sim::Signal& clock_out;
    sim::Signal& data_out;
    sim::Signal& data_enable;
    sim::Signal& data_in;
  };
  // What the encoder logic drives and sees.
  struct EncoderSide {
    sim::Signal& clock_in;
    sim::Signal& data_out;
    sim::Signal& data_enable;
    sim::Signal& data_in;
  };
  // Levels on the connector pins at each end: the spec's timing is "with respect to the encoder".
  struct Pins {
    sim::Signal& clock;
    sim::Signal& data;
    sim::Signal& driver_enable;  // this end's DATA driver active on its pins
    sim::Signal& data_driven;    // some driver (this end's or the far end's) drives DATA here
  };

  MasterSide master();
  EncoderSide encoder();
  // Another encoder on the same bus (2.10), at the encoder end of the cable with its own
  // transceiver (the line's encoder_transceiver delays); their drivers meet at the encoder pins.
  // Its driver starts off; the encoder turns it on if it drives the bus.
  EncoderSide add_encoder();
  Pins pins(ObservationPoint where);

  const LineParams& params() const { return params_; }
  // params().cable_delay(), kept as the cable changes (asked for on every sample and start bit).
  Time cable_delay() const { return cable_delay_; }
  // Clock edge at the master logic -> data edge back at the master logic, for an encoder
  // whose logic needs `encoder_output_delay` from its clock input to its data output.
  Time round_trip(Time encoder_output_delay) const;
  // The same between the master's pins (what the master's connector sees).
  Time pin_round_trip(Time encoder_output_delay) const;

  // Changes the cable while running (connector swap, temperature). Edges in flight keep their delay.
  void set_cable(double length_m, Time delay_per_m);
  void set_failsafe_level(bool level);

  // Faults, at one end's pins only: what that end's receiver and the checker there
  // see. invert: the level is inverted for `width` (a glitch; one clock period flips a bit);
  // stick: held at a level until stick(nullopt).
  void invert(Wire wire, ObservationPoint end, Time width);
  void stick(Wire wire, ObservationPoint end, std::optional<bool> level);
  // A driver that releases DATA late (turnaround collision): its disable delay from now on.
  void set_driver_disable_delay(ObservationPoint end, Time delay);
  static constexpr Time kMaxLateRelease = sim::us(100);

  // Contentions as they happen: each listener is told of every contention as it begins and as it
  // ends (Contention::sequence pairs the two), however long the run. Listeners are kept for the
  // line's life and must outlive its run.
  void on_contention(ContentionListener listener);
  // The log: the first contention_log_limit() contentions of the run, each with its end once it
  // has ended (later ones are told to the listeners only), so that a run that collides in every
  // frame keeps its memory bounded.
  const std::vector<Contention>& contentions() const { return contentions_; }
  static constexpr std::size_t kContentionLogLimit = 1000;
  std::size_t contention_log_limit() const { return contention_log_limit_; }
  // A new limit applies to the contentions that begin from now on (SIZE_MAX: log every one).
  void set_contention_log_limit(std::size_t limit) { contention_log_limit_ = limit; }
  // Every contention so far, logged or not.
  std::uint64_t contentions_seen() const { return contentions_seen_; }

 private:
  struct Impl;
  friend class ContentionLog;
  PinFault& fault(Wire wire, ObservationPoint end);
  std::uint64_t begin_contention(ObservationPoint where, bool between_encoders);
  void end_contention(std::uint64_t sequence);
  sim::Kernel& kernel_;
  LineParams params_;
  Time cable_delay_{0};
  std::unique_ptr<Impl> impl_;
  std::vector<Contention> contentions_;
  std::size_t contention_log_limit_ = kContentionLogLimit;
  std::uint64_t contentions_seen_ = 0;
  std::vector<Contention> open_contentions_;  // at most one per end and one on the encoders' bus
  std::vector<ContentionListener> contention_listeners_;
};

}  // namespace endatsim::line
