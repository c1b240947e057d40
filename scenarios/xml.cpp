#include "endatsim/scenarios/xml.hpp"

#include "endatsim/capture/capture.hpp"

namespace endatsim::scenarios {

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (static_cast<unsigned char>(c) >= 0x80) {
      // A valid UTF-8 character as it is; any other byte (a capture's names may hold anything)
      // as U+FFFD, so that the document stays well-formed.
      const std::size_t n = capture::utf8_length(text, i);
      out += n == 0 ? std::string("\xEF\xBF\xBD") : text.substr(i, n);
      if (n != 0) i += n - 1;
      continue;
    }
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      case '\n': case '\t': case '\r': out += c; break;
      default:
        if (static_cast<unsigned char>(c) >= 0x20) out += c;  // other control characters are not XML
    }
  }
  return out;
}

}  // namespace endatsim::scenarios
