#include "endatsim/capture/capture.hpp"
#include "endatsim/sim/text.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <algorithm>
#include <array>
#include <fstream>

namespace endatsim::capture {

std::size_t utf8_length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(i);
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;
  if (b >= 0xC2 && b <= 0xDF) n = 2;
  else if (b >= 0xE0 && b <= 0xEF) {
    n = 3;
    if (b == 0xE0) lo = 0xA0;
    if (b == 0xED) hi = 0x9F;
  } else if (b >= 0xF0 && b <= 0xF4) {
    n = 4;
    if (b == 0xF0) lo = 0x90;
    if (b == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto b = static_cast<unsigned char>(text[i]);
    if (b >= 0x20 && b < 0x7F) {
      out += text[i++];
      continue;
    }
    if (const std::size_t n = b >= 0x80 ? utf8_length(text, i) : 0; n != 0) {
      out.append(text.substr(i, n));
      i += n;
      continue;
    }
    out += "\\x" + sim::hex_digits(b, 2);
    ++i;
  }
  return out;
}
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

bool starts_like_zip(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, 4> magic{};
  in.read(magic.data(), magic.size());
  return in.gcount() == 4 && magic[0] == 'P' && magic[1] == 'K' && magic[2] == 3 && magic[3] == 4;
}

std::unique_ptr<Reader> open(const std::string& path) {
  // Looked at before it is opened: opening a FIFO would wait for a writer.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw CaptureError(path + ": cannot open the capture for reading: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw CaptureError(path + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaptureError(path + ": cannot open the capture for reading: " + std::strerror(errno));
  if (starts_like_zip(path)) return open_sigrok(path);
  std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".csv") return open_csv(path);
  return open_vcd(path);
}

std::uint32_t find_signal(const Reader& reader, const std::string& name) {
  // Every name with the signal it names: the signals' own, then their aliases.
  std::vector<std::pair<std::string, std::uint32_t>> names;
  const auto& all = reader.signals();
  for (std::uint32_t i = 0; i < all.size(); ++i) names.emplace_back(all[i], i);
  names.insert(names.end(), reader.aliases().begin(), reader.aliases().end());
  for (const auto& [full, index] : names)
    if (full == name) return index;
  std::vector<std::string> matches;
  std::vector<std::uint32_t> signals;
  for (const auto& [full, index] : names)
    if (ends_at_separator(full, name)) {
      matches.push_back(full);
      signals.push_back(index);
    }
  // Several names of one signal are no ambiguity.
  if (!signals.empty() && std::all_of(signals.begin(), signals.end(), [&](auto i) { return i == signals[0]; }))
    return signals[0];
  std::vector<std::string> candidates;
  for (const auto& n : names) candidates.push_back(n.first);
  if (matches.empty())
    throw CaptureError(reader.path() + ": no signal named '" + name + "'; the capture has: " + list(candidates, 40));
  throw CaptureError(reader.path() + ": '" + name + "' is ambiguous; it matches: " + list(matches, 40) +
                     " (give more of the path)");
}

}  // namespace endatsim::capture
