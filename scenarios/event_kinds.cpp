#include "endatsim/scenarios/event_kinds.hpp"

#include <array>
#include <cstdint>

#include "endatsim/line/line.hpp"
#include "endatsim/slave/encoder.hpp"

namespace endatsim::scenarios {
namespace {

using P = sim::Parameter<Event>;
using Body = EventKindRow::Body;

constexpr std::array<std::string_view, 2> kWires{"clock", "data"};  // line::Wire's order
constexpr std::array<std::string_view, 2> kEnds{"master", "encoder"};  // line::ObservationPoint's order
static_assert(static_cast<int>(line::Wire::Clock) == 0 && static_cast<int>(line::Wire::Data) == 1);
static_assert(static_cast<int>(line::ObservationPoint::MasterPins) == 0 &&
              static_cast<int>(line::ObservationPoint::EncoderPins) == 1);
constexpr std::int64_t kMaxSteps = std::int64_t{1} << (protocol::kPositionBitsMax - 1);  // a signed jump
constexpr std::int64_t kMaxFaultTime = slave::Encoder::kMaxFaultTime.count();

const std::array kTrigger{
    P{"at", &Event::at, 0, Scenario::kMaxTime.count(), "",
      "When the event acts; events with \"at\" come in time order. Exactly one of \"at\" and \"frame\"."},
    P{"frame", &Event::frame, 0, UINT32_MAX, "",
      "The master's frame at whose first falling edge the event acts, counted from 0 with the "
      "delay-measurement frames, as the log numbers them."},
    P{"clock", &Event::clock, 1, 10'000, "",
      "With \"frame\": the n-th rising CLOCK edge of that frame at the fault's end (at the master's pins for the "
      "other kinds).",
      false, false, "the frame's first falling edge"},
    P{"offset", &Event::offset, 0, sim::ms(1000).count(), "", "Delays the event further.", false, false, "0"},
};

// Line faults act at one end's pins: what that end's receiver and the timing checker there see;
// the cable carries the undisturbed level.
const P kWire{"wire", sim::enum_choice<Event, &Event::wire, kWires>(), 0, 0, "", "The wire disturbed.", true};
const P kEnd{"end", sim::enum_choice<Event, &Event::end, kEnds>(), 0, 0, "",
             "The end at whose pins the fault acts; the cable carries the undisturbed level.", true};
const P kLevel{"level", &Event::level, 0, 1, "", "The level, 0 or 1.", true};
const P kFor{"duration", &Event::duration, 1, Scenario::kMaxTime.count(), "", "How long.", false, false,
             "to the end of the run"};

const std::array kSetCable{
    P{"cable_length_m", sim::NumberField<Event>{&Event::cable_length_m, " m"}, 0,
      static_cast<std::int64_t>(line::LineParams::kMaxCableLengthM), "2.1.2", "The new cable's length.", true},
    P{"cable_delay_per_m", &Event::cable_delay_per_m, 0, line::LineParams::kMaxCableDelayPerM.count(), "2.3.2 note 2",
      "One-way propagation delay per metre.", false, false, "the line's cable_delay_per_m"},
};
const std::array kBitFlip{
    kWire, kEnd,
    P{"width", &Event::width, 1, sim::ms(1).count(), "", "How long the wire is inverted.", false, false,
      "one period of the master's f_c"},
};
const std::array kGlitch{kWire, kEnd,
                         P{"width", &Event::width, 1, sim::ms(1).count(), "", "How long the wire is inverted.", true}};
const std::array kStuck{kWire, kEnd, kLevel, kFor};
const std::array kRandomBitErrors{
    kEnd, P{"rate", sim::NumberField<Event>{&Event::rate, " (probability per clock period)"}, 0, 1, "",
            "The probability of an error at each rising CLOCK edge.", true},
    kFor};
const std::array kLateDriverRelease{
    kEnd, P{"disable_delay", &Event::width, 0, line::Line::kMaxLateRelease.count(), "",
            "Driver disable to the pins released, from now on.", true}};
const std::array kLossOfFailsafe{kLevel};
const std::array kErrorSources{
    P{"errors", &Event::errors, 0, 0xFFFF, "3.4.1", "Word 0 bits (error sources) set from now on."},
    P{"warnings", &Event::warnings, 0, 0xFFFF, "3.4.2", "Word 1 bits (warnings) set from now on."},
};
const std::array kMemoryAccessTime{
    P{"read", &Event::t_ac_read, 0, kMaxFaultTime, "2.3.2", "t_ac of a read.", true},
    P{"write", &Event::t_ac_write, 0, kMaxFaultTime, "2.3.2", "t_ac of a write.", true},
};
const std::array kTCal{
    P{"t_cal", &Event::t_cal, 0, slave::EncoderParams::kMaxModelTime.count(), "2.3.2", "The calculation time.", true}};
const std::array kSupplyOff{
    P{"duration", &Event::duration, 1, kMaxFaultTime, "", "How long the supply is off.", true}};
const std::array kProbeDeflected{
    P{"duration", &Event::duration, 1, kMaxFaultTime, "", "How long the probe stays deflected.", true}};
const std::array kStuckErrorMessages{
    P{"error_message_1", &Event::error_message_1_stuck, 0, 0, "2.3.1", "Error message 1 (F1) stuck."},
    P{"error_message_2", &Event::error_message_2_stuck, 0, 0, "2.3.1", "Error message 2 (F2) stuck."},
};
const std::array kSlip{P{"steps", &Event::steps, -kMaxSteps, kMaxSteps, "", "The jump in measuring steps.", true}};
const std::array kPosition2Fault{
    P{"deviation", &Event::steps, -kMaxSteps, kMaxSteps, "", "The deviation in measuring steps.", true}};

using K = Event::Kind;

const std::array kKinds{
    EventKindRow{"set_cable", K::SetCable, Body::Object, "2.1.2",
                 "Another cable (a connector swap, temperature); edges on their way keep their delay; the checker "
                 "expects a new delay measurement.",
                 kSetCable},
    EventKindRow{"bit_flip", K::BitFlip, Body::Object, "",
                 "The wire inverted at that end's pins for width: one period of DATA covers exactly one sampling "
                 "instant.",
                 kBitFlip},
    EventKindRow{"glitch", K::Glitch, Body::Object, "",
                 "A short inversion of the wire at that end's pins: on CLOCK, an extra pulse.", kGlitch},
    EventKindRow{"stuck", K::Stuck, Body::Object, "", "The wire held at a level at that end's pins.", kStuck},
    EventKindRow{"random_bit_errors", K::RandomBitErrors, Body::Object, "",
                 "DATA at that end inverted for one clock period with probability rate at each rising CLOCK edge "
                 "there; seeded by the scenario's seed.",
                 kRandomBitErrors},
    EventKindRow{"late_driver_release", K::LateDriverRelease, Body::Object, "",
                 "That end's DATA driver releases this late from now on: the turnaround collides.",
                 kLateDriverRelease},
    EventKindRow{"loss_of_failsafe", K::LossOfFailsafe, Body::Object, "",
                 "Undriven DATA now reads this level: the fail-safe bias is gone.", kLossOfFailsafe},
    EventKindRow{"error_sources", K::ErrorSources, Body::Object, "3.4.1, 3.4.2",
                 "Word 0 and word 1 bits that faults keep setting from now on (F1/F2, WRN).", kErrorSources},
    EventKindRow{"memory_access_time", K::MemoryAccessTime, Body::Object, "2.3.2",
                 "t_ac from now on, also beyond the spec's 12 ms: a busy that outlasts the master's patience.",
                 kMemoryAccessTime},
    EventKindRow{"t_cal", K::TCal, Body::Value, "2.3.2", "t_cal from now on, also beyond the spec's 1 ms.", kTCal},
    EventKindRow{"power_interruption", K::PowerInterruption, Body::Object, "2.3.3, 2.7",
                 "The encoder's supply fails: its driver is off, clocks are ignored, the frame in flight is lost; then "
                 "it runs up for its startup_time, like after switching on (selections and activations as after a "
                 "reset). A memory write still within its t_ac keeps the old word (encoder.interrupted_nvm_write "
                 "keep_old) or is torn (torn: high byte new, low byte old); a write whose t_ac had run out is kept; "
                 "write protection bits already stored are never lost (3.4.3). The checker expects a new delay "
                 "measurement (2.1.2).",
                 kSupplyOff},
    EventKindRow{"corrupt_word", K::CorruptWord, Body::Custom, "3.4.3",
                 "A stored word XORed with a mask, past write protection (a corrupted checksum, a flipped NVM bit).",
                 {},
                 "`area` (a memory area key such as `manufacturer_3`), `block` (of `section2`), `address`, `xor` (a "
                 "word with at least one bit set)"},
    EventKindRow{"probe_trigger", K::ProbeTrigger, Body::Object, "2.3.4.4, 3.9.32",
                 "A touch probe (encoder kind touch_probe) deflected: trigger status 1 in its answer, the switching "
                 "time in its timestamp, bit 0 of operating parameters 2 word 2 (a guess: 3.10.1 names the word "
                 "only).",
                 kProbeDeflected},
    EventKindRow{"stuck_error_messages", K::StuckErrorMessages, Body::Object, "2.3.1",
                 "Error paths that fail (true) or recover (false) from now on.", kStuckErrorMessages},
    EventKindRow{"slip", K::Slip, Body::Object, "", "The coupling slips: the measured position jumps by steps.",
                 kSlip},
    EventKindRow{"position2_fault", K::Position2Fault, Body::Object, "",
                 "The second position sensing is off by deviation steps from now on.", kPosition2Fault},
    EventKindRow{"sensors", K::SensorValues, Body::Custom, "A3, 2.3.5.1",
                 "What the encoder's sensors measure from now on (a motor heating up, a scanning unit getting "
                 "dirty).",
                 {},
                 "`temperature_1`, `temperature_2`, `additional_sensors`, `valuation_numbers` (at least one)"},
};

}  // namespace

std::span<const sim::Parameter<Event>> event_trigger_parameters() { return kTrigger; }

std::span<const EventKindRow> event_kinds() { return kKinds; }

std::string event_kind_list() {
  std::string s;
  for (std::size_t i = 0; i < kKinds.size(); ++i)
    s += (i == 0 ? "" : i + 1 == kKinds.size() ? " or " : ", ") + std::string(kKinds[i].key);
  return s;
}

}  // namespace endatsim::scenarios
