// endatsim_vpi: an HDL EnDat master (Verilog in Icarus, VHDL in GHDL, or any simulator with the
// IEEE 1364 VPI) on endatsim's line, encoders, scripted events and checker.
//
// The simulator owns time. The bridge follows the master's CLOCK, data_out and data_enable with
// value-change callbacks, moves the bench to each change's instant and drives the pin there; it
// asks the bench when it next needs to run and sets an after-delay callback for that instant, at
// which DATA towards the master (data_in) is written with no delay. So every edge reaches the
// master at the instant the line delivers it, in the simulator's own time precision (a precision
// coarser than 1 ps delivers DATA at the next tick, and the report says so).
//
// Configuration (docs/cosim.md): plusargs, or a JSON file named by +endatsim_config=FILE whose
// keys are the plusargs' names without the prefix (its "bench" relative to the file); a plusarg
// overrides the file.
//   +endatsim_bench=FILE            the bench scenario: line, encoders, events, expectations
//   +endatsim_clock=PATH            the master's CLOCK output
//   +endatsim_data_out=PATH         its DATA driver input
//   +endatsim_data_enable=PATH      its DATA driver enable (+endatsim_enable_active_low inverts it)
//   +endatsim_data=PATH             or: its DATA as one inout net, onto which the testbench puts
//                                   data_in weakly (a strong level is the master's, a weak one the line's)
//   +endatsim_data_in=PATH          the reg or signal endatsim writes with DATA at its receiver
//   +endatsim_position=PATH +endatsim_position_valid=PATH      a watched position port (VHDL)
//   +endatsim_parameter=PATH +endatsim_parameter_valid=PATH    a watched parameter port
//   +endatsim_json=FILE +endatsim_junit=FILE +endatsim_log=FILE +endatsim_vcd=FILE +endatsim_verbose
//   +endatsim_seed=N
//   +endatsim_max_time=TIME +endatsim_max_kernel_events=N +endatsim_max_records=N   limits, as
//                                   endatsim run's --max-* (a run that reaches one ends, incomplete)
// System tasks for Verilog: $endatsim_position(value) and $endatsim_parameter(value) report
// what the master decoded. At the end of simulation the report is printed and written, and the
// simulator exits with status 1 when an expectation failed (2 for bad configuration, 3 when a limit
// ended the run, 128 + N when SIGINT or SIGTERM did: the simulator's own handler still runs, and
// the outputs say incomplete).
#include <vpi_user.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "endatsim/cosim/bench.hpp"
#include "endatsim/cosim/report.hpp"
#include "endatsim/input/json_input.hpp"
#include "endatsim/scenarios/capture_check.hpp"
#include "endatsim/scenarios/exit_status.hpp"
#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/limits.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/output_file.hpp"

namespace {

using endatsim::sim::Time;
namespace cosim = endatsim::cosim;

constexpr int kExitBadInput = endatsim::scenarios::exit_status::kBadInput;
// GHDL reports the end of time (TIME'HIGH) when a simulation ran out of events.
constexpr std::uint64_t kEndOfTime = std::uint64_t{1} << 62;

[[noreturn]] void bad_configuration(const std::string& message) {
  std::fflush(stdout);
  std::cerr << "endatsim_vpi: " << message << std::endl;
  std::exit(kExitBadInput);
}

// ---- configuration ------------------------------------------------------------------------

const std::set<std::string>& known_keys() {
  static const std::set<std::string> keys{
      "bench", "clock", "data", "data_out", "data_enable", "data_in", "enable_active_low", "position", "position_valid",
      "parameter", "parameter_valid", "json", "junit", "log", "vcd", "verbose", "seed", "config",
      "max_time", "max_kernel_events", "max_records"};
  return keys;
}

std::string key_list() {
  std::string out;
  for (const auto& k : known_keys()) out += (out.empty() ? "+endatsim_" : ", +endatsim_") + k;
  return out;
}

class Config {
 public:
  Config() {
    s_vpi_vlog_info info{};
    if (vpi_get_vlog_info(&info) != 0)
      for (PLI_INT32 i = 1; i < info.argc; ++i) take_plusarg(info.argv[i] != nullptr ? info.argv[i] : "");
    if (const auto file = plusargs_.find("config"); file != plusargs_.end()) read_file(file->second);
    for (const auto& [k, v] : plusargs_) values_[k] = v;
    for (const char* required : {"bench", "clock", "data_in"})
      if (!has(required)) missing(required);
    if (has("data") && (has("data_out") || has("data_enable")))
      bad_configuration("+endatsim_data names DATA as one inout, +endatsim_data_out and +endatsim_data_enable as the "
                        "split of driver and enable: give one or the other");
    if (!has("data") && !has("data_out")) missing("data_out");
    if (has("enable_active_low") && !has("data_enable"))
      bad_configuration("+endatsim_enable_active_low inverts +endatsim_data_enable, which is not given");
    for (const char* output : {"json", "junit", "log", "vcd"}) {
      if (!has(output)) continue;
      if (get(output).empty()) bad_configuration(std::string("+endatsim_") + output + " needs a file: +endatsim_" + output + "=FILE");
      try {  // refused now rather than after the whole simulation
        endatsim::scenarios::StreamedFile probe(get(output));
      } catch (const std::exception& e) {
        bad_configuration(std::string("+endatsim_") + output + ": " + e.what());
      }
    }
    for (const char* pair : {"position", "parameter"})
      if (has(pair) != has(std::string(pair) + "_valid"))
        bad_configuration(std::string("+endatsim_") + pair + " and +endatsim_" + pair + "_valid go together");
  }
  bool has(const std::string& key) const { return values_.count(key) != 0; }
  [[noreturn]] static void missing(const std::string& key) {
    bad_configuration("missing +endatsim_" + key + "=... (or \"" + key + "\" in the +endatsim_config file); known: " +
                      key_list());
  }
  std::string get(const std::string& key) const { return has(key) ? values_.at(key) : std::string(); }
  bool flag(const std::string& key) const {
    const auto v = get(key);
    if (!has(key)) return false;
    if (v.empty() || v == "1" || v == "true") return true;
    if (v == "0" || v == "false") return false;
    bad_configuration("+endatsim_" + key + ": expected nothing, 1/0 or true/false, got \"" + v + "\"");
  }

 private:
  void take_plusarg(const std::string& arg) {
    static const std::string prefix = "+endatsim_";
    if (arg.rfind("+endatsim", 0) == 0 && arg.rfind(prefix, 0) != 0)
      bad_configuration("unknown plusarg " + arg + " (the prefix is +endatsim_); known: " + key_list());
    if (arg.rfind(prefix, 0) != 0) return;
    const auto eq = arg.find('=');
    const std::string key = arg.substr(prefix.size(), eq == std::string::npos ? std::string::npos : eq - prefix.size());
    if (known_keys().count(key) == 0) bad_configuration("unknown plusarg " + arg + "; known: " + key_list());
    plusargs_[key] = eq == std::string::npos ? std::string() : arg.substr(eq + 1);
  }
  void read_file(const std::string& path) {
    nlohmann::json j;
    try {
      j = endatsim::input::parse(endatsim::input::read_file(path, {"co-simulation configuration", "a"}), path);
    } catch (const endatsim::input::InputError& e) {
      bad_configuration(e.what());
    }
    if (!j.is_object()) bad_configuration(path + ": at /: expected an object of +endatsim_ keys without the prefix");
    for (const auto& [k, v] : j.items()) {
      if (known_keys().count(k) == 0 || k == "config")
        bad_configuration(path + ": at /" + k + ": unknown key; known: " + key_list());
      const bool flag = k == "enable_active_low" || k == "verbose";
      if (flag && v.is_boolean()) values_[k] = v.get<bool>() ? "true" : "false";
      else if (k == "seed" && v.is_number_unsigned()) values_[k] = std::to_string(v.get<std::uint64_t>());
      else if (!flag && k != "seed" && v.is_string()) values_[k] = v.get<std::string>();
      else bad_configuration(path + ": at /" + k + ": expected " +
                             (flag ? "true or false" : k == "seed" ? "a whole number" : "a string (a path or a file)") +
                             ", got " + v.dump());
    }
    // The bench is found beside the configuration that names it, wherever the simulator runs.
    if (const auto bench = values_.find("bench"); bench != values_.end() && !bench->second.empty() &&
                                                  bench->second[0] != '/')
      bench->second = (std::filesystem::path(path).parent_path() / bench->second).lexically_normal().string();
  }
  std::map<std::string, std::string> plusargs_;
  std::map<std::string, std::string> values_;
};

// ---- time ---------------------------------------------------------------------------------

// The simulator's ticks (10^precision s) and endatsim's picoseconds.
class TimeScale {
 public:
  TimeScale() {
    const PLI_INT32 precision = vpi_get(vpiTimePrecision, nullptr);
    if (precision > 0 || precision < -18) bad_configuration("the simulator reports a time precision of 1e" +
                                                            std::to_string(precision) + " s, outside 1 as .. 1 s");
    if (precision >= -12) ps_per_tick_ = pow10(precision + 12);
    else ticks_per_ps_ = pow10(-12 - precision);
  }
  // A tick finer than 1 ps lands on the picosecond before it.
  Time to_ps(std::uint64_t ticks) const {
    return Time{static_cast<std::int64_t>(ticks_per_ps_ > 1 ? ticks / ticks_per_ps_ : ticks * ps_per_tick_)};
  }
  // An instant between two ticks is delivered at the later one, never early.
  std::uint64_t to_ticks_ceil(Time t) const {
    const auto ps = static_cast<std::uint64_t>(t.count());
    return ticks_per_ps_ > 1 ? ps * ticks_per_ps_ : (ps + ps_per_tick_ - 1) / ps_per_tick_;
  }
  bool coarser_than_ps() const { return ps_per_tick_ > 1; }
  std::string tick() const {
    return ps_per_tick_ > 1 ? endatsim::sim::format_time(Time{static_cast<std::int64_t>(ps_per_tick_)})
                            : "1/" + std::to_string(ticks_per_ps_) + " ps";
  }

 private:
  static std::uint64_t pow10(int n) {
    std::uint64_t v = 1;
    for (int i = 0; i < n; ++i) v *= 10;
    return v;
  }
  std::uint64_t ps_per_tick_ = 1;
  std::uint64_t ticks_per_ps_ = 1;
};

std::uint64_t sim_ticks() {
  s_vpi_time t{};
  t.type = vpiSimTime;
  vpi_get_time(nullptr, &t);
  return (static_cast<std::uint64_t>(t.high) << 32) | t.low;
}

// ---- values -------------------------------------------------------------------------------

// Values travel as binary strings, the one format Icarus and GHDL both read and write for
// Verilog nets and regs and VHDL std_logic alike: 0/L and 1/H are levels, anything else (X, Z,
// U, W, -) is unknown.
std::optional<bool> bit_of(char c) {
  if (c == '0' || c == 'L' || c == 'l') return false;
  if (c == '1' || c == 'H' || c == 'h') return true;
  return std::nullopt;
}

std::string bin_string(vpiHandle h) {
  s_vpi_value v{};
  v.format = vpiBinStrVal;
  vpi_get_value(h, &v);
  return v.value.str != nullptr ? std::string(v.value.str) : std::string();
}

// A scalar's level; none when unknown.
std::optional<bool> level_of(vpiHandle h) {
  const std::string s = bin_string(h);
  return s.size() == 1 ? bit_of(s[0]) : std::nullopt;
}

// A vector's value (most significant bit first) up to 64 bits; none when any bit is unknown.
std::optional<std::uint64_t> word_of(vpiHandle h) {
  const std::string s = bin_string(h);
  if (s.empty() || s.size() > 64) return std::nullopt;
  std::uint64_t out = 0;
  for (char c : s) {
    const auto b = bit_of(c);
    if (!b) return std::nullopt;
    out = (out << 1) | (*b ? 1U : 0U);
  }
  return out;
}

vpiHandle by_name(const Config& config, const std::string& key) {
  std::string path = config.get(key);
  vpiHandle h = vpi_handle_by_name(path.data(), nullptr);
  if (h == nullptr)
    bad_configuration("+endatsim_" + key + "=" + path + ": no such signal in the design (give its full hierarchical "
                      "path, e.g. tb.master.clock)");
  return h;
}

bool is_ghdl() {
  s_vpi_vlog_info info{};
  return vpi_get_vlog_info(&info) != 0 && info.product != nullptr && std::string(info.product).find("GHDL") != std::string::npos;
}

// A signal (a net, a reg, a bit of either, or a VHDL signal), not a module, a task or a parameter.
vpiHandle signal_by_name(const Config& config, const std::string& key) {
  vpiHandle h = by_name(config, key);
  const PLI_INT32 type = vpi_get(vpiType, h);
  if (type != vpiNet && type != vpiReg && type != vpiNetBit && type != vpiRegBit && type != vpiPort)
    bad_configuration("+endatsim_" + key + "=" + config.get(key) + ": names a " + vpi_get_str(vpiType, h) +
                      ", not a signal");
  return h;
}

// A pin of the master: a signal of one bit.
vpiHandle pin_by_name(const Config& config, const std::string& key) {
  vpiHandle h = signal_by_name(config, key);
  if (const PLI_INT32 size = vpi_get(vpiSize, h); size != 1)
    bad_configuration("+endatsim_" + key + "=" + config.get(key) + ": a pin of one bit, got " + std::to_string(size) +
                      " bits");
  return h;
}

// ---- the bridge ---------------------------------------------------------------------------

class Bridge {
 public:
  explicit Bridge(const Config& config)
      : config_(config), bench_file_(load(config.get("bench"))), bench_(bench_file_, options(config)) {
    clock_ = pin_by_name(config, "clock");
    if (config.has("data")) {
      data_ = pin_by_name(config, "data");
      strength_by_std_logic_ = is_ghdl();
    } else {
      data_out_ = pin_by_name(config, "data_out");
    }
    data_in_ = pin_by_name(config, "data_in");
    if (!is_ghdl() && vpi_get(vpiType, data_in_) != vpiReg && vpi_get(vpiType, data_in_) != vpiRegBit)
      bad_configuration("+endatsim_data_in=" + config.get("data_in") + ": a " + vpi_get_str(vpiType, data_in_) +
                        "; endatsim writes DATA into a reg the testbench declares for it");
    if (config.has("data_enable")) data_enable_ = pin_by_name(config, "data_enable");
    active_low_ = config.flag("enable_active_low");
    if (config.has("position"))
      watch_port(signal_by_name(config, "position"), pin_by_name(config, "position_valid"), &position_);
    if (config.has("parameter"))
      watch_port(signal_by_name(config, "parameter"), pin_by_name(config, "parameter_valid"), &parameter_);
    if (scale_.coarser_than_ps())
      bench_.note("the simulator's time precision is " + scale_.tick() + ": DATA towards the master is delivered at "
                  "the next tick after the line delivers it");
    if (!data_enable_ && !data_)
      bench_.note("no +endatsim_data_enable: the master drives DATA at all times (its enable taken as on)");
    bench_.on_data_in([this](Time, bool level) { put_data_in(level); });
    for (vpiHandle h : {clock_, data_out_, data_enable_, data_})
      if (h != nullptr) watch(h, &Bridge::pin_changed);
    put_data_in(bench_.data_in());
    enter([this] {
      bench_.drive(cosim::MasterPin::Clock, level_of(clock_).value_or(true));  // CLOCK rests HIGH (2.3)
      clock_level_ = level_of(clock_).value_or(true);
      drive_data();
    });
    at_max_time();
    poll_interval_ = scale_.to_ticks_ceil(kPollFirst);
    poll();
    running_ = true;
  }

  void report_position(std::uint64_t value) {
    enter([this, value] {
      sync();
      bench_.report_position(value);
    });
  }
  void report_parameter(std::uint64_t value) {
    enter([this, value] {
      sync();
      bench_.report_parameter(static_cast<std::uint16_t>(value));
    });
  }
  void note(const std::string& text) { bench_.note(text); }

  int finish() {
    // The bench ends with the simulator, and at its max_time at the latest (the simulator was
    // stopped there). GHDL ends a simulation that ran out of events at the end of time: the bench
    // then ends at the last instant it was moved to.
    // A pin that was unknown from the start and never changed gave the bridge no call to note it.
    if (!clock_went_unknown_ && !level_of(clock_))
      bench_.unknown_level("CLOCK is unknown (X or Z) at the end of the simulation");
    if (!enable_went_unknown_ && data_enable_ != nullptr && !level_of(data_enable_))
      bench_.unknown_level("DATA's driver enable is unknown (X or Z) at the end of the simulation");
    const std::uint64_t ticks = sim_ticks();
    if (ticks < kEndOfTime) {
      const Time end = std::min(scale_.to_ps(ticks), bench_.max_time());
      if (end > bench_.now()) bench_.advance_to(end);
    }
    cosim::OutputPaths outputs;
    for (auto [key, slot] : {std::pair{"json", &outputs.json}, {"junit", &outputs.junit}, {"log", &outputs.log}})
      if (config_.has(key)) *slot = config_.get(key);
    return cosim::report(bench_.finish(), outputs, config_.flag("verbose"), std::cout, std::cerr);
  }

 private:
  using Handler = void (Bridge::*)(vpiHandle, const s_vpi_value&);
  struct Watch {
    Bridge* bridge;
    Handler handler;
    vpiHandle handle;
  };

  static endatsim::scenarios::Scenario load(const std::string& path) {
    try {
      return endatsim::scenarios::load_scenario_file(path, endatsim::scenarios::ScenarioKind::Bench);
    } catch (const std::exception& e) {
      bad_configuration(e.what());
    }
  }
  static cosim::BenchOptions options(const Config& config) {
    cosim::BenchOptions o;
    if (config.has("vcd")) o.vcd_path = config.get("vcd");
    // Before the bench opens its VCD: no output may be the bench file or another output.
    cosim::OutputPaths outputs;
    for (auto [key, slot] : {std::pair{"json", &outputs.json}, {"junit", &outputs.junit}, {"log", &outputs.log}})
      if (config.has(key)) *slot = config.get(key);
    try {
      cosim::check_outputs(config.get("bench"), outputs, o.vcd_path, "+endatsim_");
    } catch (const std::exception& e) {
      bad_configuration(e.what());
    }
    if (config.has("seed")) {
      const std::string s = config.get("seed");
      std::uint64_t seed = 0;
      const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), seed);
      if (ec != std::errc{} || end != s.data() + s.size() || s.empty())
        bad_configuration("+endatsim_seed=" + s + ": expected a whole number");
      o.seed = seed;
    }
    for (const char* key : {"max_time", "max_kernel_events", "max_records"}) {
      if (!config.has(key)) continue;
      std::string option = key;
      std::replace(option.begin(), option.end(), '_', '-');
      try {
        endatsim::scenarios::set_limit(o.limits, option, config.get(key));
      } catch (const std::invalid_argument& e) {
        bad_configuration("+endatsim_" + std::string(key) + "=" + endatsim::scenarios::trimmed(config.get(key)) + ": " + e.what());
      }
    }
    return o;
  }

  void watch(vpiHandle h, Handler handler) {
    watches_.push_back(std::make_unique<Watch>(Watch{this, handler, h}));
    s_cb_data cb{};
    s_vpi_time time{};
    s_vpi_value value{};
    time.type = vpiSuppressTime;
    value.format = vpiSuppressVal;
    cb.reason = cbValueChange;
    cb.cb_rtn = &Bridge::on_value_change;
    cb.obj = h;
    cb.time = &time;
    cb.value = &value;
    cb.user_data = reinterpret_cast<PLI_BYTE8*>(watches_.back().get());
    vpi_register_cb(&cb);
  }
  static PLI_INT32 on_value_change(p_cb_data cb) {
    auto* w = reinterpret_cast<Watch*>(cb->user_data);
    (w->bridge->*w->handler)(w->handle, s_vpi_value{});
    return 0;
  }

  // Brings the bench to the simulator's instant.
  void sync() {
    const Time t = scale_.to_ps(sim_ticks());
    if (t > bench_.now()) bench_.advance_to(t);
  }

  // Every call from the simulator goes through here. Icarus carries a data_in written with no
  // delay through continuous assignments at once, so a watched pin may change while the bench is
  // still running: such calls wait, in order, until the outermost one is done.
  void enter(std::function<void()> work) {
    if (inside_) {
      deferred_.push_back(std::move(work));
      return;
    }
    // SIGINT and SIGTERM recorded, then handed to the simulator's own handler, which Icarus sets
    // after the start-of-simulation callbacks: so they are chained at the first call from a
    // running simulation.
    if (running_ && !handlers_chained_) endatsim::scenarios::install_chained_interrupt_handlers();
    handlers_chained_ = running_;
    ++calls_;
    inside_ = true;
    work();
    for (std::size_t i = 0; i < deferred_.size(); ++i) {
      auto next = std::move(deferred_[i]);
      next();
    }
    deferred_.clear();
    inside_ = false;
    // max_time, a limit or SIGINT/SIGTERM: the simulation ends, and the bench with it.
    if (bench_.should_stop()) {
      if (!finish_requested_) vpi_control(vpiFinish, 0);
      finish_requested_ = true;
      return;
    }
    schedule_wakeup();
  }

  void pin_changed(vpiHandle h, const s_vpi_value&) {
    enter([this, h] {
      sync();
      if (h != clock_) return drive_data();
      const auto level = level_of(h);
      if (!level) {
        clock_went_unknown_ = true;
        return bench_.unknown_level("CLOCK went to an unknown level (X or Z); the last known level was kept");
      }
      if (*level == clock_level_) return;
      clock_level_ = *level;
      bench_.drive(cosim::MasterPin::Clock, *level);
    });
  }

  // The master's DATA driver as its pins stand now (both may change in one instant, in any
  // order): on while enabled, or always without an enable, with a known level.
  void drive_data() {
    if (data_ != nullptr) return drive_from_inout();
    const auto enable = data_enable_ != nullptr ? level_of(data_enable_) : std::optional<bool>(true);
    const bool enabled = enable.has_value() && (data_enable_ == nullptr || *enable != active_low_);
    const auto level = level_of(data_out_);
    if (!enable && sim_ticks() != 0) {
      enable_went_unknown_ = true;
      bench_.unknown_level("DATA's driver enable went to an unknown level (X or Z): taken as released");
    }
    if (enabled && !level && sim_ticks() != 0)
      bench_.unknown_level("data_out was unknown (X or Z) while the master drove DATA: taken as released");
    if (level) bench_.drive(cosim::MasterPin::DataOut, *level);
    bench_.drive(cosim::MasterPin::DataEnable, enabled && level.has_value());
  }

  // One inout: the line's level is on it weakly (the testbench's `assign (weak1, weak0)` or
  // std_logic 'L'/'H'), so a strong level is the master's own drive and anything weaker, or Z,
  // means it released DATA.
  void drive_from_inout() {
    std::optional<bool> level;
    bool strong = false;
    if (strength_by_std_logic_) {  // GHDL: std_logic's own letters tell the strength
      const std::string v = bin_string(data_);
      const char c = v.size() == 1 ? v[0] : 'X';
      strong = c == '0' || c == '1';
      level = strong ? std::optional<bool>(c == '1') : std::nullopt;
      if (c != 'L' && c != 'H' && c != 'Z' && !strong) unknown_inout();
    } else {
      s_vpi_value v{};
      v.format = vpiStrengthVal;
      vpi_get_value(data_, &v);
      const PLI_INT32 logic = v.value.strength != nullptr ? v.value.strength->logic : vpiX;
      const PLI_INT32 drive = logic == vpi0 ? v.value.strength->s0 : logic == vpi1 ? v.value.strength->s1 : 0;
      strong = (logic == vpi0 || logic == vpi1) && drive > vpiWeakDrive;
      level = strong ? std::optional<bool>(logic == vpi1) : std::nullopt;
      if (logic == vpiX) unknown_inout();
    }
    if (level) bench_.drive(cosim::MasterPin::DataOut, *level);
    bench_.drive(cosim::MasterPin::DataEnable, strong);
  }
  void unknown_inout() {
    if (sim_ticks() == 0) return;  // signals not yet initialised ('U') before time moves
    bench_.unknown_level("the inout DATA went to an unknown value (X, U, W or -: two strong drivers?); taken as released");
  }

  void watch_port(vpiHandle value, vpiHandle valid, std::optional<vpiHandle>* slot) {
    if (vpi_get(vpiSize, value) > 64) bad_configuration(std::string("a watched position or parameter port has more than 64 bits"));
    *slot = value;
    watch(valid, slot == &position_ ? &Bridge::position_strobe : &Bridge::parameter_strobe);
  }
  void position_strobe(vpiHandle valid, const s_vpi_value&) {
    enter([this, valid] { strobe(valid, *position_, true); });
  }
  void parameter_strobe(vpiHandle valid, const s_vpi_value&) {
    enter([this, valid] { strobe(valid, *parameter_, false); });
  }
  void strobe(vpiHandle valid, vpiHandle value, bool position) {
    if (level_of(valid) != true) return;
    const auto word = word_of(value);
    if (!word) {
      bench_.note(std::string(position ? "a position" : "a parameter") + " with unknown bits was reported; taken as 0");
    }
    sync();
    position ? bench_.report_position(word.value_or(0))
             : bench_.report_parameter(static_cast<std::uint16_t>(word.value_or(0)));
  }

  // DATA into the master's receiver reg as an event of the current time step (a zero inertial
  // delay), as an HDL driver would put it: Icarus carries a vpiNoDelay write through continuous
  // assignments without their value-change callbacks.
  void put_data_in(bool level) {
    char text[2] = {level ? '1' : '0', '\0'};
    s_vpi_value v{};
    v.format = vpiBinStrVal;
    v.value.str = text;
    s_vpi_time now{};
    now.type = vpiSimTime;
    vpi_put_value(data_in_, &v, &now, vpiInertialDelay);
  }

  // An after-delay callback at the bench's next event, unless one is set for that tick already.
  void schedule_wakeup() {
    const auto next = bench_.next_event_time();
    if (!next) return;
    const std::uint64_t now = sim_ticks();
    const std::uint64_t at = std::max(scale_.to_ticks_ceil(*next), now + 1);
    if (!wakeups_.insert(at).second) return;
    after(at - now, &Bridge::on_wakeup);
  }
  // A design that never moves the watched pins (a master held in reset while its system clock
  // runs) never calls the bridge, and GHDL's own SIGINT handler does not stop it: a look now and
  // then, in simulated time, notices SIGINT, SIGTERM and the limits. The look comes sooner while
  // the pins are busy and twice as late each time nothing called between two looks. It keeps the
  // simulation no longer alive than the callback at max_time does.
  static constexpr Time kPollFirst = endatsim::sim::us(1);
  static constexpr Time kPollLongest = endatsim::sim::ms(1);
  void poll() { after(std::max<std::uint64_t>(poll_interval_, 1), &Bridge::on_poll); }
  static PLI_INT32 on_poll(p_cb_data cb) {
    auto* self = reinterpret_cast<Bridge*>(cb->user_data);
    const bool quiet = self->calls_ == self->calls_at_poll_;
    self->poll_interval_ = quiet ? std::min(2 * self->poll_interval_, self->scale_.to_ticks_ceil(kPollLongest))
                                 : self->scale_.to_ticks_ceil(kPollFirst);
    self->enter([self] { self->sync(); });
    self->calls_at_poll_ = self->calls_;
    if (!self->finish_requested_) self->poll();
    return 0;
  }

  // A callback `delay` ticks from now.
  void after(std::uint64_t delay, PLI_INT32 (*routine)(p_cb_data)) {
    s_cb_data cb{};
    s_vpi_time time{};
    time.type = vpiSimTime;
    time.high = static_cast<PLI_UINT32>(delay >> 32);
    time.low = static_cast<PLI_UINT32>(delay & 0xFFFF'FFFFU);
    cb.reason = cbAfterDelay;
    cb.cb_rtn = routine;
    cb.time = &time;
    cb.user_data = reinterpret_cast<PLI_BYTE8*>(this);
    vpi_register_cb(&cb);
  }
  static PLI_INT32 on_wakeup(p_cb_data cb) {
    auto* self = reinterpret_cast<Bridge*>(cb->user_data);
    self->wakeups_.erase(sim_ticks());
    self->enter([self] { self->sync(); });
    return 0;
  }

  // The bench's max_time ends the simulation even when nothing happens on the pins (a master
  // held in reset, a testbench that never calls $finish).
  void at_max_time() { after(scale_.to_ticks_ceil(bench_.max_time()), &Bridge::on_max_time); }
  static PLI_INT32 on_max_time(p_cb_data cb) {
    auto* self = reinterpret_cast<Bridge*>(cb->user_data);
    self->enter([self] { self->sync(); });
    return 0;
  }

  const Config& config_;
  TimeScale scale_;
  endatsim::scenarios::Scenario bench_file_;
  cosim::Bench bench_;
  vpiHandle clock_ = nullptr, data_out_ = nullptr, data_in_ = nullptr, data_enable_ = nullptr, data_ = nullptr;
  bool strength_by_std_logic_ = false;
  std::optional<vpiHandle> position_, parameter_;
  bool active_low_ = false;
  std::set<std::uint64_t> wakeups_;
  std::vector<std::unique_ptr<Watch>> watches_;
  bool inside_ = false;
  std::uint64_t calls_ = 0;          // calls from the simulator (enter), for the polls
  std::uint64_t calls_at_poll_ = 0;  // calls_ after the last poll
  std::uint64_t poll_interval_ = 1;  // in ticks
  bool finish_requested_ = false;
  bool clock_went_unknown_ = false;   // noted as it happened: the end need not note it again
  bool enable_went_unknown_ = false;
  bool handlers_chained_ = false;
  bool running_ = false;  // past the start-of-simulation callback
  std::vector<std::function<void()>> deferred_;
  bool clock_level_ = true;
};

std::unique_ptr<Config> g_config;
std::unique_ptr<Bridge> g_bridge;

// ---- system tasks -------------------------------------------------------------------------

// The one argument of a system task, checked when the design is elaborated.
vpiHandle single_argument(vpiHandle systf, const char* name) {
  vpiHandle args = vpi_iterate(vpiArgument, systf);
  vpiHandle arg = args != nullptr ? vpi_scan(args) : nullptr;
  if (arg == nullptr) bad_configuration(std::string(name) + " takes one argument: the value the master decoded");
  if (vpi_scan(args) != nullptr) bad_configuration(std::string(name) + " takes one argument, not more");
  if (vpi_get(vpiSize, arg) > 64) bad_configuration(std::string(name) + ": the value has more than 64 bits");
  return arg;
}

template <bool Position>
PLI_INT32 report_calltf(PLI_BYTE8*) {
  const char* name = Position ? "$endatsim_position" : "$endatsim_parameter";
  vpiHandle arg = single_argument(vpi_handle(vpiSysTfCall, nullptr), name);
  if (!g_bridge) bad_configuration(std::string(name) + " called before the simulation started");
  const auto word = word_of(arg);
  if (!word) g_bridge->note(std::string(name) + " was given a value with unknown bits; taken as 0");
  Position ? g_bridge->report_position(word.value_or(0)) : g_bridge->report_parameter(word.value_or(0));
  return 0;
}

template <bool Position>
PLI_INT32 report_compiletf(PLI_BYTE8*) {
  single_argument(vpi_handle(vpiSysTfCall, nullptr), Position ? "$endatsim_position" : "$endatsim_parameter");
  return 0;
}

void register_task(const char* name, PLI_INT32 (*calltf)(PLI_BYTE8*), PLI_INT32 (*compiletf)(PLI_BYTE8*)) {
  s_vpi_systf_data tf{};
  tf.type = vpiSysTask;
  tf.tfname = const_cast<PLI_BYTE8*>(name);
  tf.calltf = calltf;
  tf.compiletf = compiletf;
  vpi_register_systf(&tf);
}

PLI_INT32 start_of_simulation(p_cb_data) {
  try {
    g_config = std::make_unique<Config>();
    g_bridge = std::make_unique<Bridge>(*g_config);
  } catch (const std::exception& e) {
    bad_configuration(e.what());
  }
  return 0;
}

int g_status = 0;

// The simulator's own exit status says nothing of endatsim's verdict. Exiting inside the
// end-of-simulation callback would starve other modules' callbacks (cocotb's results), so the
// verdict is handed to Icarus as its return value, or, elsewhere, given at the process's exit
// by a handler registered before the simulator's own, so that it runs after them.
#ifndef ENDATSIM_VPI_ICARUS
void exit_with_verdict() {
  if (g_status == 0) return;
  std::fflush(nullptr);
  std::_Exit(g_status);
}
#endif

PLI_INT32 end_of_simulation(p_cb_data) {
  if (!g_bridge) return 0;
  g_status = g_bridge->finish();
  g_bridge.reset();
  std::fflush(stdout);
#ifdef ENDATSIM_VPI_ICARUS
  if (g_status != 0) vpip_set_return_value(g_status);
#endif
  return 0;
}

void register_callback(PLI_INT32 reason, PLI_INT32 (*routine)(p_cb_data)) {
  s_cb_data cb{};
  cb.reason = reason;
  cb.cb_rtn = routine;
  vpi_register_cb(&cb);
}

void startup() {
#ifndef ENDATSIM_VPI_ICARUS
  std::atexit(&exit_with_verdict);
#endif
  register_task("$endatsim_position", &report_calltf<true>, &report_compiletf<true>);
  register_task("$endatsim_parameter", &report_calltf<false>, &report_compiletf<false>);
  register_callback(cbStartOfSimulation, &start_of_simulation);
  register_callback(cbEndOfSimulation, &end_of_simulation);
}

}  // namespace

extern "C" {
// IEEE 1364 27.36: the simulator calls each routine of this list when it loads the module.
void (*vlog_startup_routines[])() = {&startup, nullptr};
}
