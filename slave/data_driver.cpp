#include "endatsim/slave/data_driver.hpp"

namespace endatsim::slave {

DataDriver::DataDriver(sim::Kernel& kernel, line::Line::EncoderSide pins, sim::Time output_delay)
    : level_(kernel, "encoder_data_logic", false), enabled_(kernel, "encoder_enable_logic", true),
      level_delay_(kernel, level_, pins.data_out, output_delay),
      enabled_delay_(kernel, enabled_, pins.data_enable, output_delay) {}

}  // namespace endatsim::slave
