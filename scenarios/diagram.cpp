#include "endatsim/scenarios/diagram.hpp"

#include "endatsim/protocol/timing.hpp"
#include "endatsim/scenarios/xml.hpp"
#include "endatsim/sim/text.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <map>

#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/runner.hpp"
#include "endatsim/scenarios/vcd_reader.hpp"

namespace endatsim::scenarios {
namespace {

using T64 = std::int64_t;
constexpr T64 kNone = -1;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}


// A 1-bit waveform read back from the VCD. Its changes are in time order: each lookup starts with
// a binary search, so that a window over thousands of frames is drawn in N log N, not N^2.
struct Wave {
  const VcdVariable* v = nullptr;
  // The first change after `t`.
  std::size_t after(T64 t) const {
    return static_cast<std::size_t>(
        std::upper_bound(v->changes.begin(), v->changes.end(), t, [](T64 x, const auto& c) { return x < c.time; }) -
        v->changes.begin());
  }
  bool at(T64 t) const {
    const std::size_t i = after(t);
    return i != 0 && v->changes[i - 1].value == '1';
  }
  bool is_edge(std::size_t i, int kind) const {
    const auto& c = v->changes[i];
    const bool rising = c.value == '1' && v->changes[i - 1].value == '0';
    const bool falling = c.value == '0' && v->changes[i - 1].value == '1';
    return (kind == 1 && rising) || (kind == 0 && falling) || (kind == -1 && (rising || falling));
  }
  // Times of edges in (from, to]: rising (1), falling (0) or both (-1).
  std::vector<T64> edges(T64 from, T64 to, int kind) const {
    std::vector<T64> out;
    for (std::size_t i = std::max<std::size_t>(1, after(from)); i < v->changes.size() && v->changes[i].time <= to; ++i)
      if (is_edge(i, kind)) out.push_back(v->changes[i].time);
    return out;
  }
  T64 first(T64 from, T64 to, int kind) const {
    for (std::size_t i = std::max<std::size_t>(1, after(from)); i < v->changes.size() && v->changes[i].time <= to; ++i)
      if (is_edge(i, kind)) return v->changes[i].time;
    return kNone;
  }
};

// Time -> x, with long stretches without any edge drawn as short axis breaks.
class Axis {
 public:
  struct Segment {
    T64 a, b;
    double v;       // virtual start
    double length;  // virtual length
    bool broken;
  };

  // `forced`: stretches drawn as breaks even though edges (a running clock) lie inside them.
  Axis(T64 from, T64 to, std::vector<T64> edges, const std::vector<std::pair<T64, T64>>& forced, T64 max_gap, double x0,
       double width)
      : x0_(x0) {
    edges.push_back(from);
    edges.push_back(to);
    for (const auto& [a, b] : forced) {
      edges.push_back(a);
      edges.push_back(b);
    }
    // Edges inside a forced break do not split it. The breaks are in time order and apart.
    const auto break_at = [&](T64 t) {  // the last break that begins at or before t
      const auto f = std::upper_bound(forced.begin(), forced.end(), t, [](T64 x, const auto& b) { return x < b.first; });
      return f == forced.begin() ? forced.end() : f - 1;
    };
    std::erase_if(edges, [&](T64 t) {
      const auto f = break_at(t);
      return f != forced.end() && t > f->first && t < f->second;
    });
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    double virtual_length = 0;
    for (std::size_t i = 1; i < edges.size(); ++i) {
      const T64 a = std::max(edges[i - 1], from), b = std::min(edges[i], to);
      if (b <= a) continue;
      const auto f = break_at(a);
      const bool inside_forced = f != forced.end() && a >= f->first && b <= f->second;
      const bool broken = b - a > max_gap || inside_forced;
      const double length = static_cast<double>(broken ? max_gap / 2 : b - a);
      segments_.push_back({a, b, virtual_length, length, broken});
      virtual_length += length;
    }
    scale_ = virtual_length > 0 ? width / virtual_length : 1.0;
  }
  double x(T64 t) const {
    if (segments_.empty()) return x0_;
    if (t <= segments_.front().a) return x0_;
    // The first segment that reaches t.
    const auto s = std::lower_bound(segments_.begin(), segments_.end(), t, [](const Segment& g, T64 x) { return g.b < x; });
    if (s != segments_.end()) {
      const double fraction = static_cast<double>(t - s->a) / static_cast<double>(s->b - s->a);
      return x0_ + (s->v + fraction * s->length) * scale_;
    }
    const auto& last = segments_.back();
    return x0_ + (last.v + last.length) * scale_;
  }
  const std::vector<Segment>& segments() const { return segments_; }

 private:
  double x0_;
  double scale_ = 1.0;
  std::vector<Segment> segments_;
};

}  // namespace

namespace {

// A temporary file in a directory private to this call (mkdtemp: a fresh name, mode 0700), so that
// nobody else can plant a file or a symlink where it is written; both go again.
struct TempFile {
  std::string dir;
  std::string path;
  TempFile() {
    std::string pattern = (std::filesystem::temp_directory_path() / "endatsim_diagram_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr)
      throw std::runtime_error("cannot create a temporary directory in " +
                               std::filesystem::temp_directory_path().string() + ": " + std::strerror(errno));
    dir = pattern;
    path = dir + "/waveform.vcd";
  }
  ~TempFile() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
};

constexpr double kLeft = 190, kWidth = 1380, kRowHeight = 26;

class Svg {
 public:
  std::string out;
  void line(double x1, double y1, double x2, double y2, const std::string& style) {
    out += "<line x1=\"" + num(x1) + "\" y1=\"" + num(y1) + "\" x2=\"" + num(x2) + "\" y2=\"" + num(y2) + "\" " + style +
           "/>\n";
  }
  void text(double x, double y, const std::string& t, const std::string& style = "") {
    out += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\"" + (style.empty() ? "" : " " + style) + ">" + xml_escape(t) +
           "</text>\n";
  }
  void rect(double x, double y, double w, double h, const std::string& style) {
    out += "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) + "\" height=\"" + num(h) + "\" " +
           style + "/>\n";
  }
  // A dimension arrow from x1 to x2 at height y with its label above.
  void dimension(double x1, double x2, double y, const std::string& label, bool bad) {
    const std::string colour = bad ? "#c00000" : "#1f4e9c";
    line(x1, y - 7, x1, y + 7, "stroke=\"" + colour + "\"");
    line(x2, y - 7, x2, y + 7, "stroke=\"" + colour + "\"");
    out += "<path d=\"M" + num(x1) + " " + num(y) + " H" + num(x2) + "\" stroke=\"" + colour +
           "\" marker-start=\"url(#arrow)\" marker-end=\"url(#arrow)\"/>\n";
    text((x1 + x2) / 2, y - 4, label, "text-anchor=\"middle\" fill=\"" + colour + "\" font-size=\"11\"");
  }
  // A labelled box over a bit field; the label shrinks to `short_label` or nothing when narrow.
  void field(double x1, double x2, double y, const std::string& label, const std::string& short_label) {
    rect(x1, y, std::max(x2 - x1, 0.5), 16, "fill=\"#eef3fb\" stroke=\"#7a93bf\" stroke-width=\"0.8\"");
    const double width = x2 - x1;
    const std::string shown = static_cast<double>(label.size()) * 6.2 + 4 < width         ? label
                              : static_cast<double>(short_label.size()) * 6.2 + 2 < width ? short_label
                                                                                           : "";
    if (!shown.empty()) text((x1 + x2) / 2, y + 12, shown, "text-anchor=\"middle\" font-size=\"10\"");
    // Too narrow for any label inside (a one-bit field at a high clock): the short label above it.
    else if (!short_label.empty()) text((x1 + x2) / 2, y - 2, short_label, "text-anchor=\"middle\" font-size=\"8\"");
  }
  // Numbers over the rising edges of a CLOCK row (RE1 the first after FE1), as violations cite
  // them ("clock 9"); where they would crowd, every fifth.
  void clock_numbers(const std::vector<double>& xs, double y) {
    double spacing = 1e9;
    for (std::size_t i = 1; i < xs.size(); ++i) spacing = std::min(spacing, xs[i] - xs[i - 1]);
    const std::size_t every = spacing >= 14 ? 1 : 5;
    for (std::size_t i = 0; i < xs.size(); ++i)
      if ((i + 1) % every == 0 || i == 0)
        text(xs[i], y, std::to_string(i + 1), "text-anchor=\"middle\" fill=\"#666\" font-size=\"8\"");
  }
};

struct Row {
  std::string name;   // variable in the VCD
  std::string label;  // shown at the left
  double y;           // top of the HIGH level
  bool strobe;        // drawn as ticks (a toggle per event)
};

}  // namespace

Diagram frame_diagram(const Scenario& scenario, const DiagramOptions& options) {
  TempFile vcd;
  RunOptions ro;
  ro.vcd_path = vcd.path;
  ro.seed = options.seed;
  ro.limits = options.limits;
  const ScenarioResult r = run_scenario(scenario, ro);
  if (r.interrupted != 0) throw Interrupted(scenario.file + ": " + r.incomplete, r.interrupted);
  if (!r.incomplete.empty()) throw LimitReached(scenario.file + ": " + r.incomplete);
  const VcdFile file = read_vcd_file(vcd.path);
  if (!file.issues.empty()) throw std::runtime_error("the waveform did not read back: " + file.issues.front().message);
  const auto wave = [&](const std::string& name) {
    const VcdVariable* v = file.find(name);
    if (v == nullptr) throw std::runtime_error("the waveform has no " + name);
    return Wave{v};
  };
  const Wave m_clock = wave("endat.master_clock"), m_data = wave("endat.master_data"), m_en = wave("endat.master_data_driver_enable"),
             m_sample = wave("endat.master_sample"), e_clock = wave("endat.encoder_clock"), e_data = wave("endat.encoder_data"),
             e_en = wave("endat.encoder_data_driver_enable");

  // What to draw.
  const master::FrameResult* frame = nullptr;
  T64 from = 0, to = 0;
  const T64 period = sim::period_of(scenario.master.f_c).count();
  if (options.window) {
    from = options.window->first.count();
    to = std::min(options.window->second.count(), r.simulated.count());
    if (from >= r.simulated.count())
      throw std::invalid_argument("--from " + sim::format_time(options.window->first) + " is after the end of the run (" +
                                  sim::format_time(r.simulated) + ")");
  } else {
    if (options.frame) {
      if (*options.frame >= r.frames.size())
        throw std::invalid_argument("frame " + std::to_string(*options.frame) + ": the run has " +
                                    std::to_string(r.frames.size()) + " frames (0 .. " +
                                    std::to_string(r.frames.empty() ? 0 : r.frames.size() - 1) + ")");
      frame = &r.frames[*options.frame];
    } else {
      for (const auto& f : r.frames)
        if (!f.measurement) {
          frame = &f;
          break;
        }
      if (frame == nullptr && !r.frames.empty()) frame = &r.frames.front();
      if (frame == nullptr) throw std::invalid_argument("the run has no frames to draw");
    }
    // Continuous-clock words share the frame's FE1: draw to the last of them.
    T64 end = frame->end.count();
    for (const auto& f : r.frames)
      if (f.start == frame->start) end = std::max(end, f.end.count());
    const T64 frame_period = sim::period_of(frame->f_c).count();
    from = frame->start.count() - 2 * frame_period;
    const sim::Time recovery = scenario.encoder.short_t_m_selected && scenario.encoder.t_m_short ? *scenario.encoder.t_m_short
                                                                                                : scenario.encoder.t_m;
    to = end + recovery.count() + scenario.encoder.t_r.count() + 2 * frame_period;
    for (const auto& f : r.frames)  // not into the next frame
      if (f.start > frame->start && f.start.count() < to) to = std::max(end + frame_period, f.start.count() - frame_period / 2);
    to = std::min(to, r.simulated.count());
    from = std::max<T64>(from, 0);
  }
  const T64 f_period = frame != nullptr ? sim::period_of(frame->f_c).count() : period;

  // Measurements on the waveforms.
  struct Measure {
    std::string name;
    T64 a = kNone, b = kNone;
    std::string row;
  };
  std::vector<Measure> measures;
  std::vector<T64> m_fe, m_re, e_fe, e_re;
  T64 e_start = kNone, m_start = kNone;
  std::size_t launch = 0;  // the encoder's rising edge (1 = RE1) that launched the start bit
  // The encoder's receiver, logic and driver lie between its clock pin and its data pin.
  const T64 internal =
      (scenario.line.encoder.receiver_delay + scenario.encoder.output_delay + scenario.line.encoder.driver_delay).count();
  if (frame != nullptr) {
    const T64 fe1 = m_clock.first(frame->start.count() - 1, to, 0);
    const T64 e_fe1 = e_clock.first(frame->start.count() - 1, to, 0);
    if (fe1 != kNone && e_fe1 != kNone) {
      m_fe = m_clock.edges(fe1 - 1, to, 0);
      m_re = m_clock.edges(fe1, to, 1);
      e_fe = e_clock.edges(e_fe1 - 1, to, 0);
      e_re = e_clock.edges(e_fe1, to, 1);
      if (!m_re.empty()) measures.push_back({"t_ST", fe1, m_re.front(), "endat.master_clock"});
      const bool word = frame->outcome == master::FrameOutcome::Ok || frame->outcome == master::FrameOutcome::CrcError;
      const T64 enabled = e_en.first(e_fe1, to, 1);
      if (word && enabled != kNone) e_start = e_data.first(enabled, to, 1);
      if (e_start != kNone) {
        // The edge that launched the start bit (at 8 MHz the internal delay exceeds a period).
        for (T64 re : e_re)
          if (re + internal <= e_start) ++launch;
        measures.push_back({"t_cal", e_fe1, e_start, "endat.encoder_data"});
        if (launch >= 1 && launch <= m_re.size()) {
          const T64 re_s = m_re[launch - 1];
          m_start = m_data.first(re_s, to, 1);
          if (m_start != kNone) measures.push_back({"t_D on the wires", re_s, m_start, "endat.master_data"});
        }
      }
      if (!e_re.empty()) {
        const T64 low = e_data.first(e_re.back(), to, 0);
        if (low != kNone && e_start != kNone) measures.push_back({"t_m", e_re.back(), low, "endat.encoder_data"});
      }
    }
  }

  // Axis with breaks over stretches longer than eight clock periods without an edge.
  std::vector<T64> all_edges;
  for (const Wave* w : {&m_clock, &m_data, &m_en, &m_sample, &e_clock, &e_data, &e_en}) {
    const auto e = w->edges(from, to, -1);
    all_edges.insert(all_edges.end(), e.begin(), e.end());
  }
  // A clock that runs on while DATA and the drivers stay as they are (memory access, polling)
  // is broken too when that lasts more than 64 periods, keeping two periods at each side.
  std::vector<T64> data_edges{from, to};
  for (const Wave* w : {&m_data, &m_en, &e_data, &e_en}) {
    const auto e = w->edges(from, to, -1);
    data_edges.insert(data_edges.end(), e.begin(), e.end());
  }
  std::sort(data_edges.begin(), data_edges.end());
  std::vector<std::pair<T64, T64>> forced;
  for (std::size_t i = 1; i < data_edges.size(); ++i)
    if (data_edges[i] - data_edges[i - 1] > 64 * f_period)
      forced.emplace_back(data_edges[i - 1] + 2 * f_period, data_edges[i] - 2 * f_period);
  const Axis axis(from, to, all_edges, forced, 8 * f_period, kLeft, kWidth);

  const std::vector<Row> rows{
      {"endat.master_clock", "CLOCK (master pins)", 80, false},
      {"endat.master_data", "DATA (master pins)", 176, false},
      {"endat.master_data_driver_enable", "master DATA driver on", 250, false},
      {"endat.master_sample", "master samples DATA", 300, true},
      {"endat.encoder_clock", "CLOCK (encoder pins)", 350, false},
      {"endat.encoder_data", "DATA (encoder pins)", 430, false},
      {"endat.encoder_data_driver_enable", "encoder DATA driver on", 504, false},
  };
  const auto row_y = [&](const std::string& name) {
    for (const auto& row : rows)
      if (row.name == name) return row.y;
    return 0.0;
  };

  std::vector<const checker::Violation*> violations;
  for (const auto& v : r.violations) {
    const bool in_frame = frame != nullptr && v.frame && *v.frame == frame->index;
    const bool in_window = frame == nullptr && v.time.count() >= from && v.time.count() <= to;
    if (in_frame || in_window) violations.push_back(&v);
  }
  const double axis_y = 560;
  const double height = axis_y + 50 + 16.0 * static_cast<double>(violations.size() + 1) + 20;

  Svg svg;
  svg.out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1600\" height=\"" + num(height) + "\" viewBox=\"0 0 1600 " +
            num(height) + "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"12\">\n";
  svg.out +=
      "<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"5\" refY=\"5\" markerWidth=\"6\" markerHeight=\"6\" "
      "orient=\"auto-start-reverse\"><path d=\"M0 0 L10 5 L0 10 z\" fill=\"context-stroke\"/></marker></defs>\n";
  svg.rect(0, 0, 1600, height, "fill=\"white\"");
  std::string title = scenario.name;
  std::string caption;
  if (frame != nullptr) {
    title += ": frame #" + std::to_string(frame->index) + ", " + std::string(protocol::info(frame->command).key) + " (" +
             std::string(master::to_string(frame->outcome)) + ")";
  } else {
    title += ": " + sim::format_time(sim::Time{from}) + " .. " + sim::format_time(sim::Time{to});
  }
  svg.text(20, 26, title, "font-size=\"16\" font-weight=\"bold\"");
  // The t_D the master compensates with (its measurement) is not the t_D drawn on the wires.
  const std::string compensation =
      frame != nullptr ? (frame->compensated ? "compensating with the measured t_D " + sim::format_time(frame->t_d_used)
                                             : std::string("no delay compensation"))
                       : (scenario.master.delay_compensation ? std::string("delay compensation on")
                                                             : std::string("no delay compensation"));
  std::string subtitle = "f_c " + sim::format_frequency(frame != nullptr ? frame->f_c : scenario.master.f_c) + ", cable " +
                         num(scenario.line.cable_length_m) + " m, " + compensation + ", true round trip " +
                         sim::format_time(r.true_round_trip) + ", seed " + std::to_string(r.seed);
  svg.text(20, 46, subtitle, "fill=\"#444\"");

  // Axis breaks as grey bands.
  for (const auto& s : axis.segments())
    if (s.broken) {
      const double x1 = axis.x(s.a), x2 = axis.x(s.b);
      svg.rect(x1, 64, x2 - x1, axis_y - 64, "fill=\"#f2f2f2\"");
      svg.text((x1 + x2) / 2, axis_y + 14, "// " + sim::format_time(sim::Time{s.b - s.a}),
               "text-anchor=\"middle\" fill=\"#888\" font-size=\"10\"");
    }

  // Waveforms.
  for (const auto& row : rows) {
    // Drawing a long window takes a while: SIGINT and SIGTERM end it, with no diagram written.
    if (const int signal = interrupt_signal(); signal != 0)
      throw Interrupted(scenario.file + ": interrupted by " + signal_name(signal) + " while drawing: no diagram written", signal);
    const Wave w = wave(row.name);
    svg.text(16, row.y + kRowHeight / 2 + 4, row.label);
    if (row.strobe) {
      for (T64 t : w.edges(from, to, -1)) svg.line(axis.x(t), row.y + 4, axis.x(t), row.y + kRowHeight, "stroke=\"#1f7a3a\"");
      continue;
    }
    const auto level_y = [&](bool high) { return high ? row.y : row.y + kRowHeight; };
    bool level = w.at(from);
    std::string d = "M" + num(axis.x(from)) + " " + num(level_y(level));
    for (T64 t : w.edges(from, to, -1)) {
      level = !level;
      d += " H" + num(axis.x(t)) + " V" + num(level_y(level));
    }
    d += " H" + num(axis.x(to));
    svg.out += "<path d=\"" + d + "\" fill=\"none\" stroke=\"black\" stroke-width=\"1.2\"/>\n";
  }
  // Sampling instants across the master's DATA.
  for (T64 t : m_sample.edges(from, to, -1))
    svg.line(axis.x(t), row_y("endat.master_data") - 4, axis.x(t), row_y("endat.master_sample"),
             "stroke=\"#1f7a3a\" stroke-dasharray=\"2 2\" stroke-width=\"0.8\"");

  // Fields.
  namespace fp = protocol::frame_position;
  const auto fe = [&](unsigned k) { return m_fe[k - 1]; };  // FE_k
  if (frame != nullptr && m_fe.size() >= fp::kTurnaround) {
    const std::string bits = protocol::mode_bits_string(frame->mode_bits);
    svg.field(axis.x(fe(fp::kFirstModeBit)), axis.x(fe(fp::kTurnaround)), row_y("endat.master_data") - 22, "mode bits " + bits, bits);
    svg.field(axis.x(fe(fp::kFrameStart)), axis.x(fe(fp::kFirstModeBit)), row_y("endat.master_data") - 22, "turnaround", "");
    // 2.1 parameter frames: 8 bits of address / MRS code / port and 16 bits after the mode bits.
    constexpr unsigned kAddressEnd = fp::kTurnaround + protocol::kPayloadAddressBits, kPayloadEnd = fp::kTurnaround + protocol::kPayloadBits;
    if (frame->payload && m_fe.size() >= kPayloadEnd) {
      svg.field(axis.x(fe(fp::kTurnaround)), axis.x(fe(kAddressEnd)), row_y("endat.master_data") - 22,
                "address " + sim::hex_0x(protocol::payload_address(*frame->payload), 2), "address");
      svg.field(axis.x(fe(kAddressEnd)), axis.x(fe(kPayloadEnd)), row_y("endat.master_data") - 22,
                "parameter " + sim::hex_0x(protocol::payload_parameter(*frame->payload), 4), "parameter");
    }
  }
  if (e_start != kNone && frame != nullptr && launch >= 1) {
    // The answer as the master expects it for this command (position, parameter or test values).
    const auto layout = protocol::answer_layout(protocol::info(frame->command), scenario.master.position_bits);
    std::size_t slot = launch - 1;  // index into e_re of the rising edge that launched the bit
    for (const auto& spec : layout.fields()) {
      const std::size_t last = slot + spec.width;  // edge after the field
      if (last >= e_re.size() + 1) break;
      // Bits appear on the encoder's DATA pin the encoder's internal delay after the clock edge.
      const T64 a = e_re[slot] + internal, b = (last < e_re.size() ? e_re[last] : e_re[last - 1] + f_period) + internal;
      std::string name(protocol::field_name(spec.field));
      std::string short_name = spec.field == protocol::Field::StartBit ? "S" : name;
      if (spec.field == protocol::Field::Position) name += " (" + std::to_string(spec.width) + " bits, LSB first)";
      if (spec.field == protocol::Field::Crc) name += " (" + std::to_string(protocol::kCrcBits) + " bits)";
      svg.field(axis.x(a), axis.x(b), row_y("endat.encoder_data") - 22, name, short_name);
      slot = last;
    }
    // 2.2 additional data after the CRC, in wire order (additional data 2 first): each a LOW bit,
    // WRN, RM, Busy, the information code, two data bytes and its own CRC (D297403 2.3.5).
    for (const auto& d : frame->additional_data) {
      const std::size_t last = slot + protocol::kAdditionalDatumBits;
      if (last > e_re.size()) break;
      const auto edge = [&](std::size_t i) { return (i < e_re.size() ? e_re[i] : e_re[i - 1] + f_period) + internal; };
      const bool second = protocol::is_additional_data_2(d.information());
      svg.field(axis.x(edge(slot)), axis.x(edge(last)), row_y("endat.encoder_data") - 22,
                std::string(second ? "additional data 2: " : "additional data 1: ") +
                    std::string(protocol::info(d.information()).key) + (d.crc_ok ? "" : " (CRC FAIL)"),
                second ? "AD2" : "AD1");
      const std::size_t busy = slot + protocol::kAdditionalDatumBusyBit;  // after the LOW bit, WRN and RM
      svg.field(axis.x(edge(busy)), axis.x(edge(busy + 1)), row_y("endat.encoder_data") - 40,
                d.busy() ? "Busy 1" : "Busy 0", d.busy() ? "B1" : "B0");
      slot = last;
    }
  }
  // The 2.2 command supplement the master drives after the encoder's data (MRS code or address,
  // then 16 bits): while the master's DATA driver is on after the answer.
  if (frame != nullptr && frame->supplement && e_start != kNone) {
    const T64 on = m_en.first(e_start, to, 1);
    const T64 off = on != kNone ? m_en.first(on, to, 0) : kNone;
    if (on != kNone) {
      const std::string text = "command supplement " + sim::hex_0x(protocol::payload_address(*frame->supplement), 2) + " " +
                               sim::hex_0x(protocol::payload_parameter(*frame->supplement), 4);
      svg.field(axis.x(on), axis.x(off != kNone ? off : to), row_y("endat.master_data") - 22, text, "supplement");
    }
  }
  // Clock numbers at both ends.
  for (const auto& [edges, row] : {std::pair{&m_re, "endat.master_clock"}, std::pair{&e_re, "endat.encoder_clock"}}) {
    std::vector<double> xs;
    for (T64 t : *edges)
      if (t >= from && t <= to) xs.push_back(axis.x(t));
    svg.clock_numbers(xs, row_y(row) - 3);
  }

  // Timing parameters.
  const auto bad_check = [&](const std::string& check) {
    for (const auto* v : violations)
      if (v->check == check) return true;
    return false;
  };
  for (const auto& m : measures) {
    const double y = row_y(m.row) + kRowHeight + 18;
    const std::string value = sim::format_time(sim::Time{m.b - m.a});
    const std::string check = m.name == "t_ST" ? "t_st" : m.name == "t_cal" ? "t_cal" : m.name.starts_with("t_D") ? "t_d" : "t_m_t_r";
    svg.dimension(axis.x(m.a), axis.x(m.b), y, m.name + " = " + value, bad_check(check));
    caption += (caption.empty() ? "" : ", ") + m.name + " " + value;
  }

  // Violations: a red mark at the time on its end's rows, and the list below.
  double list_y = axis_y + 50;
  std::vector<std::pair<double, double>> labels;
  std::multimap<double, std::size_t> labels_by_x;  // x -> place in labels
  std::vector<std::size_t> near;
  if (!violations.empty()) svg.text(20, list_y, "Violations", "font-weight=\"bold\" fill=\"#c00000\"");
  for (const auto* v : violations) {
    const bool encoder_side = v->where == line::ObservationPoint::EncoderPins;
    const double y1 = encoder_side ? row_y("endat.encoder_clock") - 6 : row_y("endat.master_clock") - 6;
    const double y2 = encoder_side ? row_y("endat.encoder_data_driver_enable") + kRowHeight : row_y("endat.master_sample") + kRowHeight;
    const double x = axis.x(std::clamp(v->time.count(), from, to));
    svg.line(x, y1, x, y2, "stroke=\"#c00000\" stroke-width=\"1.5\"");
    double label_y = y1 + 8;
    // Stagger labels that would overlap: each label closer than 90 px, in the order they were
    // placed (found by x, so that a window of many findings is not quadratic).
    near.clear();
    for (auto l = labels_by_x.upper_bound(x - 90); l != labels_by_x.end() && l->first < x + 90; ++l)
      near.push_back(l->second);
    std::sort(near.begin(), near.end());
    for (const std::size_t k : near) {
      const auto& [lx, ly] = labels[k];
      if (std::abs(lx - x) < 90 && std::abs(ly - label_y) < 10) label_y = ly + 11;
    }
    labels_by_x.emplace(x, labels.size());
    labels.emplace_back(x, label_y);
    svg.text(x + 3, label_y, v->check, "fill=\"#c00000\" font-size=\"10\"");
    list_y += 16;
    std::string text = std::string(checker::to_string(v->severity)) + " " + v->check + " at " + sim::format_time(v->time) +
                       " (" + std::string(line::to_string(v->where));
    if (v->clock) text += ", clock " + std::to_string(*v->clock);
    if (!v->field.empty()) text += ", " + v->field;
    text += "): measured " + v->measured + ", limit " + v->limit + " [" + v->spec + "]";
    svg.text(20, list_y, text, "fill=\"#c00000\" font-size=\"11\"");
  }

  // Time axis: ticks at the window's ends and at the frame's FE1.
  svg.line(kLeft, axis_y, kLeft + kWidth, axis_y, "stroke=\"#888\"");
  std::vector<T64> ticks{from, to};
  if (!m_fe.empty()) ticks.push_back(m_fe.front());
  std::vector<double> placed;
  for (T64 t : ticks) {
    if (std::any_of(placed.begin(), placed.end(), [&](double x) { return std::abs(x - axis.x(t)) < 70; })) continue;
    placed.push_back(axis.x(t));
    svg.line(axis.x(t), axis_y - 4, axis.x(t), axis_y + 4, "stroke=\"#888\"");
    svg.text(axis.x(t), axis_y + 28, sim::format_time(sim::Time{t}), "text-anchor=\"middle\" fill=\"#666\" font-size=\"10\"");
  }
  if (!m_fe.empty()) svg.text(axis.x(m_fe.front()), 74, "FE1", "text-anchor=\"middle\" fill=\"#666\" font-size=\"10\"");
  svg.out += "</svg>\n";

  Diagram d;
  d.svg = std::move(svg.out);
  d.caption = title + (caption.empty() ? "" : ": " + caption) +
              (violations.empty() ? "" : "; " + std::to_string(violations.size()) + " violations");
  return d;
}

}  // namespace endatsim::scenarios
