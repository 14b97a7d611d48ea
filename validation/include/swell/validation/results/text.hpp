#pragma once
// Text helpers every renderer of results shares: numbers for a table, the display width of
// UTF-8, and strings made safe for XML 1.0 and JSON whatever bytes they hold (a case path may
// hold any).
#include <cstddef>
#include <string>

namespace swell::validation {

// A number for a results table: 4 significant digits, "—" for NaN, "inf" and "-inf".
std::string table_number(double x);

// Display width of a UTF-8 string in columns: its code points (every symbol swell prints is one
// column wide).
std::size_t display_width(const std::string& s);
// s followed by spaces up to `width` columns (nothing added when it is as wide already).
std::string pad_to_width(const std::string& s, std::size_t width);

// Length of the well-formed UTF-8 sequence at s (1 for ASCII), 0 when malformed: a lead byte
// with its continuation bytes, no overlong form, no surrogate, nothing above U+10FFFF. Stores
// the code point in *code_point when given.
std::size_t utf8_sequence_length(const unsigned char* s, std::size_t available,
                                 char32_t* code_point = nullptr);
// Valid UTF-8 of any byte string (each malformed byte → U+FFFD), for JSON, which must be UTF-8.
std::string valid_utf8(const std::string& text);
// Valid XML 1.0 character data from any byte string: markup characters escaped, control
// characters other than tab, newline and carriage return dropped (XML 1.0 cannot hold them, not
// even as references), U+FFFE/U+FFFF dropped, and malformed UTF-8 replaced by U+FFFD. In an
// attribute value tab and newline are written as references (a parser would normalize them to
// spaces).
std::string xml_escape(const std::string& text, bool in_attribute = true);
// ` name="value"` with the value escaped.
std::string xml_attribute(const std::string& name, const std::string& value);

}  // namespace swell::validation
