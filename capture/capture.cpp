#include "capture/capture.hpp"

#include <algorithm>
#include <array>
#include <fstream>

namespace endatsim::capture {
namespace {

bool ends_at_separator(const std::string& full, const std::string& suffix) {
  if (suffix.size() > full.size() || full.compare(full.size() - suffix.size(), suffix.size(), suffix) != 0) return false;
  if (suffix.size() == full.size()) return true;
  const char before = full[full.size() - suffix.size() - 1];
  return before == '.' || before == '/' || before == ':';
}

std::string list(const std::vector<std::string>& names, std::size_t at_most) {
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < at_most; ++i) out += (i == 0 ? "" : ", ") + names[i];
  if (names.size() > at_most) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

}  // namespace

std::unique_ptr<Reader> open(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaptureError(path + ": cannot open the capture for reading");
  std::array<char, 4> magic{};
  in.read(magic.data(), magic.size());
  const bool zip = in.gcount() == 4 && magic[0] == 'P' && magic[1] == 'K' && magic[2] == 3 && magic[3] == 4;
  if (zip) return open_sigrok(path);
  std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".csv") return open_csv(path);
  return open_vcd(path);
}

std::uint32_t find_signal(const Reader& reader, const std::string& name) {
  const auto& all = reader.signals();
  for (std::uint32_t i = 0; i < all.size(); ++i)
    if (all[i] == name) return i;
  std::vector<std::string> matches;
  std::uint32_t found = 0;
  for (std::uint32_t i = 0; i < all.size(); ++i)
    if (ends_at_separator(all[i], name)) {
      matches.push_back(all[i]);
      found = i;
    }
  if (matches.size() == 1) return found;
  if (matches.empty())
    throw CaptureError(reader.path() + ": no signal named '" + name + "'; the capture has: " + list(all, 40));
  throw CaptureError(reader.path() + ": '" + name + "' is ambiguous; it matches: " + list(matches, 40) +
                     " (give more of the path)");
}

}  // namespace endatsim::capture
