// Printable quotes of file text (tdo_io/text.h).
#include "tdo_io/text.h"

#include <cstdio>

namespace tdo_io {

namespace {

std::string escaped(std::string_view text, std::size_t max, bool all) {
  const std::size_t n = text.size() < max ? text.size() : max;
  std::string out;
  out.reserve(n + 24);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (!all && c >= 0x20 && c != 0x7f) {
      out.push_back(static_cast<char>(c));
    } else if (c == '\\') {
      out += "\\\\";
    } else if (c >= 0x20 && c < 0x7f) {
      out.push_back(static_cast<char>(c));
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned>(c));
      out += buf;
    }
  }
  if (n < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

}  // namespace

std::string printable(std::string_view text, std::size_t max) { return escaped(text, max, true); }

std::string one_line(std::string_view text, std::size_t max) { return escaped(text, max, false); }

}  // namespace tdo_io
