// The encoder's side of memory access (D297403 2.4 .. 2.6): the memory area selected (2.4.1;
// with a block address, 2.4.2.1), the words a frame reads and writes there, a 2.2 access that
// runs while Busy is set and then shows in additional data 1 (2.5.1, 2.6.1; its acknowledgment,
// inverted for an error, A2 type II), and the word being programmed into the NVM, for what a
// power interruption leaves of it. What a 2.1 frame decides is carried out by the frame engine
// when the frame ends (encoder.hpp); what a completed write means beyond the memory (EIB
// commissioning, the bus address, the RM reset) the encoder hears through Client.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>

#include "endatsim/sim/kernel.hpp"
#include "endatsim/slave/additional_data.hpp"
#include "endatsim/slave/memory.hpp"

namespace endatsim::slave {

using sim::Time;

class MemoryAccess {
 public:
  class Client {
   public:
    virtual void written(const Selection& s, std::uint8_t address) = 0;

   protected:
    ~Client() = default;
  };

  MemoryAccess(sim::Kernel& kernel, Memory& memory, AdditionalData& additional_data, Client& client);
  MemoryAccess(const MemoryAccess&) = delete;
  MemoryAccess& operator=(const MemoryAccess&) = delete;

  // 2.5.1 / 2.6.1: Busy is set while a 2.2 access, or a 2.1 access whose t_ac runs after its
  // frame, is in progress.
  bool busy() const { return kernel_.now() < busy_until_; }
  std::optional<Selection> selection() const { return area_selected_ ? std::optional{selection_} : std::nullopt; }

  // ---- what a frame does at once, or when it ends ---------------------------------------------
  void select(const Selection& s);
  // A word of the selected area; "impermissible memory area" without a selection (A2 cause 7).
  std::optional<ErrorCause> check_write(std::uint8_t address, std::uint16_t value) const;
  Memory::WordRead read(std::uint8_t address) const;
  // Writes the word and tells the client; the NVM write begun for it is complete.
  void write(const Selection& s, std::uint8_t address, std::uint16_t value);
  // A 2.1 write whose programming ends at `done_at` (begun when its frame answers), or one that
  // was discarded before it reached the memory.
  void begin_nvm_write(const Selection& s, std::uint8_t address, std::uint16_t value, Time done_at);
  void discard_nvm_write() { nvm_.discard(); }
  // A 2.1 access whose t_ac runs after its frame (MemoryAccessPlacement::AfterFrame).
  void busy_until(Time t) { busy_until_ = std::max(busy_until_, t); }

  // ---- a 2.2 access: it completes after t_ac, with Busy set meanwhile --------------------------
  void start_selection(const Selection& s, std::uint8_t mrs, std::uint16_t parameter, Time t_ac);
  std::optional<ErrorCause> start_write(std::uint8_t address, std::uint16_t value, Time t_ac);
  std::optional<ErrorCause> start_read(std::uint8_t address, std::uint16_t parameter, Time t_ac);
  // A selection whose frame was disrupted (too many clock pulses, 2.4.2.1) does not take place.
  void cancel_selection();

  // 2.7: a reset (or switching on) ends any access and the selection.
  void restart();
  // The supply fails (NvmProgramming::interrupt).
  void power_interrupted(bool torn) { nvm_.interrupt(memory_, kernel_.now(), torn); }

 private:
  struct InProgress {
    enum class Kind : std::uint8_t { None, Select, Write } kind = Kind::None;
    Selection selection;
    std::uint8_t address = 0;
    std::uint16_t value = 0;
    bool error = false;  // acknowledged inverted (A2 type II)
  };
  void start(const InProgress& access, Time t_ac);
  void on_access_done();

  sim::Kernel& kernel_;
  Memory& memory_;
  AdditionalData& additional_data_;
  Client& client_;
  sim::Timer timer_;
  Selection selection_;
  bool area_selected_ = false;
  Time busy_until_{0};
  InProgress in_progress_;
  NvmProgramming nvm_;
};

}  // namespace endatsim::slave
