#pragma once
// The signals of endatsim's waveforms (--vcd): one scope, "endat", and names that are unique on
// their own, because sigrok and PulseView drop a VCD's scopes: master_clock, master_data,
// master_data_driver_enable (levels at the master's pins), encoder_clock, encoder_data,
// encoder_data_driver_enable (at the encoder's), and the master's master_sample (toggles at each
// sampling instant) and master_frame (HIGH while a frame is under way).

#include <string>
#include <string_view>

#include "endatsim/line/line.hpp"
#include "endatsim/sim/vcd.hpp"

namespace endatsim::scenarios {

inline constexpr std::string_view kWaveformScope = "endat";

// "encoder_clock": the end's name before the signal's.
inline std::string pin_wave_name(line::ObservationPoint end, std::string_view signal) {
  return std::string(end == line::ObservationPoint::MasterPins ? "master_" : "encoder_") + std::string(signal);
}

// The name a reader of the file sees: "endat.encoder_clock".
inline std::string full_wave_name(line::ObservationPoint end, std::string_view signal) {
  return std::string(kWaveformScope) + "." + pin_wave_name(end, signal);
}

// CLOCK, DATA and the DATA driver's enable at both ends, the master's first.
inline void add_pin_waves(sim::VcdWriter& vcd, line::Line& line) {
  for (auto end : {line::ObservationPoint::MasterPins, line::ObservationPoint::EncoderPins}) {
    auto pins = line.pins(end);
    vcd.add(pins.clock, std::string(kWaveformScope), pin_wave_name(end, "clock"));
    vcd.add(pins.data, std::string(kWaveformScope), pin_wave_name(end, "data"));
    vcd.add(pins.driver_enable, std::string(kWaveformScope), pin_wave_name(end, "data_driver_enable"));
  }
}

}  // namespace endatsim::scenarios
