#include "endatsim/scenarios/gtkw.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "endatsim/scenarios/waveform_names.hpp"

namespace endatsim::scenarios {
namespace {

// GTKWave's named markers are the letters A .. Z.
constexpr std::size_t kNamedMarkers = 26;
// The window the save file asks for, and the width of its wave area (without the signal names)
// that the zoom is chosen for.
constexpr int kWindowWidth = 1400, kWindowHeight = 700;
constexpr double kViewPixels = 800.0;
// GTKWave's zoom z shows 2^-z time units in one of its "frames" of 200 pixels (measured with
// GTKWave 3.3's getWindowStartTime / getWindowEndTime: each step of z halves the window).
constexpr double kGtkwavePixelsPerFrame = 200.0;

struct View {
  sim::Time start{0};
  sim::Time marker{-1};
  double zoom = 0.0;
};

// The first frame that is not a delay measurement (else the first frame), shown whole with a
// tenth of its length before and after it.
View first_frame_view(const ScenarioResult& r) {
  const auto it = std::find_if(r.frames.begin(), r.frames.end(), [](const auto& f) { return !f.measurement; });
  const auto* frame = it != r.frames.end() ? &*it : (r.frames.empty() ? nullptr : &r.frames.front());
  if (frame == nullptr) return {};
  const sim::Time length = std::max(frame->end - frame->start, sim::ns(1));
  View v;
  v.start = std::max(sim::Time::zero(), frame->start - length / 10);
  v.marker = frame->start;
  // 2^-zoom time units (1 ps here) per 200 pixels; GTKWave accepts zooms from -62 to 0.
  const double per_frame = static_cast<double>((length + length / 5).count()) / kViewPixels * kGtkwavePixelsPerFrame;
  v.zoom = std::clamp(-std::log2(std::max(per_frame, 1.0)), -62.0, 0.0);
  return v;
}

}  // namespace

std::string gtkw_save_file(const ScenarioResult& result, const std::string& vcd_path) {
  const View view = first_frame_view(result);
  std::vector<sim::Time> named;
  for (const auto& v : result.violations) named.push_back(v.time);
  std::sort(named.begin(), named.end());
  named.erase(std::unique(named.begin(), named.end()), named.end());
  if (named.size() > kNamedMarkers) named.resize(kNamedMarkers);

  char zoom[32];
  std::snprintf(zoom, sizeof zoom, "%.6f", view.zoom);
  std::string title = result.name;  // a comment line: a name from a file must not end it early
  std::replace_if(title.begin(), title.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  std::string text = "[*] endatsim " + title + "\n";
  text += "[dumpfile] \"" + std::filesystem::absolute(vcd_path).lexically_normal().string() + "\"\n";
  text += "[size] " + std::to_string(kWindowWidth) + " " + std::to_string(kWindowHeight) + "\n";
  text += "[timestart] " + std::to_string(view.start.count()) + "\n";
  text += "*" + std::string(zoom) + " " + std::to_string(view.marker.count());
  for (const auto t : named) text += " " + std::to_string(t.count());
  text += "\n";
  const std::string scope = std::string(kWaveformScope) + ".";
  for (auto end : {line::ObservationPoint::MasterPins, line::ObservationPoint::EncoderPins}) {
    const bool master = end == line::ObservationPoint::MasterPins;
    text += std::string("@200\n-") + (master ? "master" : "encoder") + " pins\n@28\n";
    for (const char* signal : {"clock", "data", "data_driver_enable"}) text += scope + pin_wave_name(end, signal) + "\n";
    if (master) text += scope + "master_sample\n" + scope + "master_frame\n" + scope + "decoded\n";
  }
  return text;
}

}  // namespace endatsim::scenarios
