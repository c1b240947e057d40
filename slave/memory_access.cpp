#include "endatsim/slave/memory_access.hpp"

namespace endatsim::slave {

MemoryAccess::MemoryAccess(sim::Kernel& kernel, Memory& memory, AdditionalData& additional_data, Client& client)
    : kernel_(kernel), memory_(memory), additional_data_(additional_data), client_(client),
      timer_(kernel, sim::bind<&MemoryAccess::on_access_done>(this)) {}

void MemoryAccess::select(const Selection& s) {
  selection_ = s;
  area_selected_ = true;
  if (s.area == MemoryArea::AsynchronousPosition) additional_data_.set_asynchronous_time_delay(s.block);  // 2.4.2.3
}

std::optional<ErrorCause> MemoryAccess::check_write(std::uint8_t address, std::uint16_t value) const {
  if (!area_selected_) return ErrorCause::ImpermissibleMemoryArea;
  return memory_.check_write(selection_, address, value);
}

Memory::WordRead MemoryAccess::read(std::uint8_t address) const {
  if (!area_selected_) return {.value = 0, .error = ErrorCause::ImpermissibleMemoryArea};
  return memory_.read(selection_, address);
}

void MemoryAccess::write(const Selection& s, std::uint8_t address, std::uint16_t value) {
  memory_.write(s, address, value);
  nvm_.applied();
  client_.written(s, address);
}

void MemoryAccess::begin_nvm_write(const Selection& s, std::uint8_t address, std::uint16_t value, Time done_at) {
  nvm_.begin(memory_, s, address, value, done_at);
}

// ---- 2.2 -----------------------------------------------------------------------------------------

void MemoryAccess::start(const InProgress& access, Time t_ac) {
  in_progress_ = access;
  busy_until_ = kernel_.now() + t_ac;
  timer_.start(t_ac);
}

void MemoryAccess::start_selection(const Selection& s, std::uint8_t mrs, std::uint16_t parameter, Time t_ac) {
  start({InProgress::Kind::Select, s, mrs, parameter, false}, t_ac);
}

// 2.6.1: the word is written once t_ac has passed; the NVM is programming it until then.
std::optional<ErrorCause> MemoryAccess::start_write(std::uint8_t address, std::uint16_t value, Time t_ac) {
  const auto error = check_write(address, value);
  start({error ? InProgress::Kind::None : InProgress::Kind::Write, selection_, address, value, error.has_value()}, t_ac);
  if (!error) nvm_.begin(memory_, selection_, address, value, busy_until_);
  return error;
}

// 2.5.1: the word read comes back in additional data 1 once Busy is reset; with an error, the
// parameter sent, inverted.
std::optional<ErrorCause> MemoryAccess::start_read(std::uint8_t address, std::uint16_t parameter, Time t_ac) {
  const auto read = this->read(address);
  start({InProgress::Kind::None, selection_, address, read.error ? parameter : read.value, read.error.has_value()}, t_ac);
  return read.error;
}

void MemoryAccess::cancel_selection() {
  if (in_progress_.kind != InProgress::Kind::Select) return;
  in_progress_ = {};
  timer_.cancel();
  busy_until_ = kernel_.now();
}

void MemoryAccess::on_access_done() {
  // 2.5.1 / 2.6.1: the result appears in additional data 1 once the busy bit is reset.
  const InProgress done = in_progress_;
  in_progress_ = {};
  switch (done.kind) {
    case InProgress::Kind::Select:
      select(done.selection);
      return;
    case InProgress::Kind::Write:
      write(done.selection, done.address, done.value);
      break;
    case InProgress::Kind::None:
      break;
  }
  // A2 type II (4.2.2): "the address or parameter is returned inverted", for 2.1 and 2.2 alike:
  // both, as the 2.1 acknowledgment returns them (docs/model.md §3).
  additional_data_.acknowledge_memory_access(protocol::acknowledged_address(done.address, done.error),
                                             protocol::acknowledged_parameter(done.value, done.error));
}

void MemoryAccess::restart() {
  area_selected_ = false;
  timer_.cancel();
  busy_until_ = kernel_.now();
  in_progress_ = {};
}

}  // namespace endatsim::slave
