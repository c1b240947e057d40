#include "endatsim/scenarios/declarations.hpp"

#include <algorithm>

#include "endatsim/protocol/additional_data.hpp"

namespace endatsim::scenarios {

checker::EncoderDeclaration declared_encoder(const slave::EncoderParams& e) {
  checker::EncoderDeclaration d;
  d.position_bits = e.position_bits;
  d.output_delay = e.output_delay;
  d.t_cal = e.t_cal;
  d.t_cal_22 = e.t_cal_22;
  d.t_cal_energy_saving = e.t_cal_energy_saving;
  d.t_ac = std::max(e.t_ac_read, e.t_ac_write);
  d.t_m = e.t_m;
  d.t_m_short = e.t_m_short;
  d.short_t_m_selected = e.short_t_m_selected;
  d.t_r = e.t_r;
  d.t_st_max = e.t_st_max;
  d.t_lo_max = e.t_lo_max;
  d.endat21_only = e.version == protocol::EndatVersion::V2_1;
  d.switched_on_in_run = e.startup_time > sim::Time::zero();
  d.supplement_ignore_clocks = e.supplement_ignore_clocks;
  // Word 25 of the EnDat 2.2 area (3.9.19), in kHz; 0 states nothing.
  const auto image = e.memory ? *e.memory : slave::default_memory_image(e);
  const auto bd = image.areas.find(protocol::MemoryArea::ManufacturerEndat22);
  if (bd != image.areas.end() && bd->second.size() > protocol::word::kMaxClockFrequency &&
      bd->second[protocol::word::kMaxClockFrequency] != 0)
    d.f_c_max = sim::kHz(bd->second[protocol::word::kMaxClockFrequency]);
  return d;
}

checker::MasterDeclaration declared_master(const master::MasterParams& m) {
  return {.position_bits = m.position_bits, .f_c = m.f_c, .f_e = m.measurement.f_e, .measurements = m.measurement.count};
}

checker::DeclaredFrame declared_frame(const master::FrameResult& f) {
  checker::DeclaredFrame d;
  d.index = f.index;
  d.start = f.start;
  d.end = f.end;
  d.command = f.command;
  d.mode_bits = f.mode_bits;
  d.payload = f.payload;
  d.supplement = f.supplement;
  d.answer_bits = f.answer_bits;
  d.position_bits = f.position_bits;
  d.f_c = f.f_c;
  d.measurement = f.measurement;
  d.compensated = f.compensated;
  d.t_d_used = f.t_d_used;
  d.error_handling = f.outcome == master::FrameOutcome::Type1Error || f.outcome == master::FrameOutcome::NoStartBit;
  d.ok = f.outcome == master::FrameOutcome::Ok;
  const auto ai1 = std::find_if(f.additional_data.begin(), f.additional_data.end(), [](const master::AdditionalDatum& a) {
    return !protocol::is_additional_data_2(a.information());
  });
  if (ai1 != f.additional_data.end()) d.busy = ai1->busy();
  d.start_bit_clock = f.start_bit_clock;
  return d;
}

}  // namespace endatsim::scenarios
