#include "swell/validation/results/text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace swell::validation {

std::string table_number(double x) {
  if (std::isnan(x)) return "—";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return fmt::format("{:.4g}", x);
}

std::size_t display_width(const std::string& s) {
  return std::size_t(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

std::string pad_to_width(const std::string& s, std::size_t width) {
  const std::size_t have = display_width(s);
  return s + std::string(width > have ? width - have : 0, ' ');
}

std::size_t utf8_sequence_length(const unsigned char* s, std::size_t available,
                                 char32_t* code_point) {
  const unsigned char c = s[0];
  std::size_t length = 0;
  char32_t code = 0;
  if (c < 0x80) {
    length = 1;
    code = c;
  } else if (c >= 0xC2 && c <= 0xDF) {
    length = 2;
    code = c & 0x1F;
  } else if (c >= 0xE0 && c <= 0xEF) {
    length = 3;
    code = c & 0x0F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    length = 4;
    code = c & 0x07;
  }
  if (length == 0 || length > available) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((s[k] & 0xC0) != 0x80) return 0;
    code = (code << 6) | (s[k] & 0x3F);
  }
  const char32_t smallest = length == 1 ? 0 : length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;
  if (code < smallest || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  if (code_point) *code_point = code;
  return length;
}

std::string valid_utf8(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const std::size_t length = utf8_sequence_length(s + i, n - i);
    if (length == 0) {
      out += "\xEF\xBF\xBD";
      ++i;
    } else {
      out.append(text, i, length);
      i += length;
    }
  }
  return out;
}

std::string xml_escape(const std::string& text, bool in_attribute) {
  std::string out;
  out.reserve(text.size() + 16);
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    char32_t code = 0;
    const std::size_t length = utf8_sequence_length(s + i, n - i, &code);
    if (length == 0) {
      out += "\xEF\xBF\xBD";  // U+FFFD for the one bad byte; resynchronize on the next
      ++i;
      continue;
    }
    switch (code) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      case '\t': out += in_attribute ? "&#9;" : "\t"; break;
      case '\n': out += in_attribute ? "&#10;" : "\n"; break;
      case '\r': out += "&#13;"; break;  // else read back as a newline
      default:
        // Other C0 controls, U+FFFE and U+FFFF are not XML 1.0 characters.
        if (code >= 0x20 && code != 0xFFFE && code != 0xFFFF) out.append(text, i, length);
    }
    i += length;
  }
  return out;
}

std::string xml_attribute(const std::string& name, const std::string& value) {
  return " " + name + "=\"" + xml_escape(value) + "\"";
}

}  // namespace swell::validation
