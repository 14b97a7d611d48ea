#include "swell/validation/io/npy.hpp"

#include "swell/validation/io/half.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <istream>
#include <limits>
#include <optional>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace swell::validation {
namespace {

namespace fs = std::filesystem;
using Dtype = NpyArray::Dtype;

constexpr std::array<unsigned char, 6> kMagic = {0x93, 'N', 'U', 'M', 'P', 'Y'};
constexpr std::size_t kMagicAndVersion = 8;  // numpy's MAGIC_LEN
constexpr std::size_t kAlign = 64;           // numpy's ARRAY_ALIGN (data offset alignment)
// numpy ≥ 1.24 leaves room after the dict for the growing axis to reach 21 digits, so a file can
// be appended to without rewriting the data; reproduced so that our files match numpy's bytes.
constexpr std::size_t kGrowthAxisMaxDigits = 21;
// Far above any header these dtypes need (numpy itself refuses more than 10000 by default); stops
// a corrupt length field from making us read a large part of a file as a header.
constexpr std::size_t kMaxHeaderBytes = 1 << 20;
constexpr int kMaxNesting = 16;  // of brackets in a header; a real one nests 1 deep

const char* const kSupported =
    "'<f2' (float16), '<f4' (float32), '<f8' (float64), '<c8' (complex64), '<c16' (complex128)";

[[noreturn]] void fail(const fs::path& path, const std::string& problem) {
  throw InvalidInput(path.string() + ": " + problem);
}

std::optional<std::size_t> checked_product(std::size_t a, std::size_t b) {
  std::size_t out = 0;
  if (__builtin_mul_overflow(a, b, &out)) return std::nullopt;
  return out;
}

// ------------------------------------------------------------------ header dict parser
//
// The header is a Python literal that numpy reads with ast.literal_eval. This parses the subset
// a header can sensibly hold — strings, integers, True/False/None, tuples, lists, dicts — with
// Python's meaning for parentheses: "(3)" is the integer 3, "(3,)" a 1-tuple. Anything else (an
// escape sequence, a float) is kept as an opaque token or rejected with its byte offset.

struct DictEntry;

struct Literal {
  enum class Type { string, integer, non_integer_number, boolean, none, tuple, list, dict };
  Type type = Type::none;
  std::string text;        // string contents; the digits of an integer; a number's source
  bool negative = false;   // integer sign
  bool value = false;      // boolean
  std::vector<Literal> items;                          // tuple, list
  std::vector<DictEntry> entries;                      // dict, in file order
};

// Not a std::pair<Literal, Literal>: pair needs complete element types where Literal is still
// being defined, which GCC lets pass and clang with libstdc++ rejects.
struct DictEntry {
  Literal key, value;
};

std::string describe(const Literal& v) {
  switch (v.type) {
    case Literal::Type::string: return "a string";
    case Literal::Type::integer: return "an integer";
    case Literal::Type::non_integer_number: return "the number " + v.text;
    case Literal::Type::boolean: return v.value ? "True" : "False";
    case Literal::Type::none: return "None";
    case Literal::Type::tuple: return "a tuple";
    case Literal::Type::list: return "a list";
    case Literal::Type::dict: return "a dict";
  }
  return "?";
}

class HeaderParser {
 public:
  // python2_longs: versions 1.0 and 2.0 may come from Python 2, which wrote shapes as (3L,).
  HeaderParser(const fs::path& path, std::string_view text, bool python2_longs)
      : path_(path), text_(text), python2_longs_(python2_longs) {}

  Literal parse_document() {
    skip_space();
    Literal value = parse_value(0);
    skip_space();
    if (pos_ != text_.size()) error("unexpected text after the dict");
    return value;
  }

 private:
  [[noreturn]] void error(const std::string& what) const {
    fail(path_, "cannot parse the header at byte " + std::to_string(pos_) + ": " + what);
  }

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }

  void skip_space() {
    while (!at_end() && (peek() == ' ' || peek() == '\t' || peek() == '\n' || peek() == '\r' ||
                         peek() == '\f' || peek() == '\v')) {
      ++pos_;
    }
  }

  void expect(char c) {
    skip_space();
    if (peek() != c) error(std::string("expected '") + c + "'");
    ++pos_;
  }

  Literal parse_value(int depth) {
    if (depth > kMaxNesting) error("brackets nested too deep");
    skip_space();
    if (at_end()) error("the header ends where a value should be");
    const char c = peek();
    if (c == '\'' || c == '"') return parse_string();
    if (c == '(') return parse_parenthesized(depth);
    if (c == '[') return parse_sequence(depth, ']', Literal::Type::list);
    if (c == '{') return parse_dict(depth);
    if (c == '+' || c == '-' || c == '.' || (c >= '0' && c <= '9')) return parse_number();
    if (is_identifier_char(c)) return parse_name();
    error(std::string("unexpected character ") + printable(c));
  }

  static std::string printable(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) return std::string("'") + c + "'";
    static const char* hex = "0123456789abcdef";
    return std::string("byte 0x") + hex[u >> 4] + hex[u & 15];
  }

  static bool is_identifier_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  }

  Literal parse_string() {
    const char quote = text_[pos_++];
    Literal v;
    v.type = Literal::Type::string;
    while (true) {
      if (at_end() || peek() == '\n') error("unterminated string");
      const char c = text_[pos_++];
      if (c == quote) break;
      // No dtype string needs an escape; refusing them keeps the parser small and exact.
      if (c == '\\') error("escape sequences in header strings are not supported");
      v.text += c;
    }
    return v;
  }

  // "()" empty tuple, "(x)" just x, "(x,)" and "(x, y)" tuples.
  Literal parse_parenthesized(int depth) {
    ++pos_;
    skip_space();
    if (peek() == ')') {
      ++pos_;
      Literal v;
      v.type = Literal::Type::tuple;
      return v;
    }
    Literal first = parse_value(depth + 1);
    skip_space();
    if (peek() == ')') {
      ++pos_;
      return first;
    }
    if (peek() != ',') error("expected ',' or ')'");
    ++pos_;
    Literal v = parse_sequence_rest(depth, ')', Literal::Type::tuple);
    v.items.insert(v.items.begin(), std::move(first));
    return v;
  }

  Literal parse_sequence(int depth, char close, Literal::Type type) {
    ++pos_;  // the opening bracket
    return parse_sequence_rest(depth, close, type);
  }

  // Items up to `close`, separated by commas, a trailing comma allowed.
  Literal parse_sequence_rest(int depth, char close, Literal::Type type) {
    Literal v;
    v.type = type;
    while (true) {
      skip_space();
      if (peek() == close) {
        ++pos_;
        return v;
      }
      v.items.push_back(parse_value(depth + 1));
      skip_space();
      if (peek() == ',') {
        ++pos_;
      } else if (peek() != close) {
        error(std::string("expected ',' or '") + close + "'");
      }
    }
  }

  Literal parse_dict(int depth) {
    ++pos_;
    Literal v;
    v.type = Literal::Type::dict;
    while (true) {
      skip_space();
      if (peek() == '}') {
        ++pos_;
        return v;
      }
      Literal key = parse_value(depth + 1);
      expect(':');
      Literal value = parse_value(depth + 1);
      v.entries.push_back({std::move(key), std::move(value)});
      skip_space();
      if (peek() == ',') {
        ++pos_;
      } else if (peek() != '}') {
        error("expected ',' or '}'");
      }
    }
  }

  // A decimal integer (optionally signed; 'L'-suffixed from Python 2), or any other number-like
  // token, kept as text so that the shape check can say what it found.
  Literal parse_number() {
    const std::size_t start = pos_;
    Literal v;
    if (peek() == '+' || peek() == '-') {
      v.negative = peek() == '-';
      ++pos_;
      skip_space();
    }
    const std::size_t digits_start = pos_;
    while (!at_end() && (is_identifier_char(peek()) || peek() == '.' ||
                         ((peek() == '+' || peek() == '-') &&
                          (text_[pos_ - 1] == 'e' || text_[pos_ - 1] == 'E')))) {
      ++pos_;
    }
    std::string token(text_.substr(digits_start, pos_ - digits_start));
    if (python2_longs_ && token.size() > 1 && (token.back() == 'L' || token.back() == 'l')) {
      token.pop_back();
    }
    if (token.empty()) error("a sign without a number");
    const bool all_digits = token.find_first_not_of("0123456789") == std::string::npos;
    if (all_digits) {
      v.type = Literal::Type::integer;
      v.text = token;
    } else {
      v.type = Literal::Type::non_integer_number;
      v.text = std::string(text_.substr(start, pos_ - start));
    }
    return v;
  }

  Literal parse_name() {
    const std::size_t start = pos_;
    while (!at_end() && is_identifier_char(peek())) ++pos_;
    const std::string_view name = text_.substr(start, pos_ - start);
    Literal v;
    if (name == "True" || name == "False") {
      v.type = Literal::Type::boolean;
      v.value = name == "True";
    } else if (name == "None") {
      v.type = Literal::Type::none;
    } else {
      pos_ = start;
      error("unexpected name '" + std::string(name) + "'");
    }
    return v;
  }

  const fs::path& path_;
  std::string_view text_;
  bool python2_longs_;
  std::size_t pos_ = 0;
};

// ------------------------------------------------------------------ header meaning

Dtype dtype_from_descr(const fs::path& path, const Literal& descr) {
  if (descr.type == Literal::Type::list) {
    fail(path, std::string("structured dtypes (a list in 'descr') are not supported; supported: ") +
                   kSupported);
  }
  if (descr.type != Literal::Type::string) {
    fail(path, "'descr' must be a dtype string such as '<f8', got " + describe(descr));
  }
  const std::string& d = descr.text;
  if (d == "<f2") return Dtype::f2;
  if (d == "<f4") return Dtype::f4;
  if (d == "<f8") return Dtype::f8;
  if (d == "<c8") return Dtype::c8;
  if (d == "<c16") return Dtype::c16;
  const std::string type = d.empty() ? "" : d.substr(1);
  const bool ours = type == "f2" || type == "f4" || type == "f8" || type == "c8" || type == "c16";
  if (!d.empty() && d[0] == '>') {
    fail(path, "big-endian dtype '" + d + "' is not supported; save little-endian data " +
                   (ours ? "(numpy: a.astype('<" + type + "'))" : std::string("")) +
                   "; supported: " + kSupported);
  }
  if (ours && (d[0] == '|' || d[0] == '=')) {
    // numpy writes '|' only for one-byte types and never writes '=' (it resolves native order),
    // so for these types either byte order marker is not something numpy produces.
    fail(path, "dtype '" + d + "' has byte order '" + d.substr(0, 1) +
                   "', which numpy never writes for a multi-byte type; expected '<" + type + "'");
  }
  fail(path, "unsupported dtype '" + d + "'; supported: " + kSupported);
}

std::vector<std::size_t> shape_from_literal(const fs::path& path, const Literal& shape) {
  if (shape.type != Literal::Type::tuple) {
    fail(path, "'shape' must be a tuple of integers such as (3,) or (2, 3), got " +
                   describe(shape));
  }
  std::vector<std::size_t> dims;
  for (std::size_t i = 0; i < shape.items.size(); ++i) {
    const Literal& entry = shape.items[i];
    const std::string which = "'shape' entry " + std::to_string(i);
    if (entry.type != Literal::Type::integer) {
      fail(path, which + " is not an integer (got " + describe(entry) + ")");
    }
    // Leading zeros aside, more than 20 digits cannot fit in 64 bits.
    const auto first = entry.text.find_first_not_of('0');
    const std::string digits = first == std::string::npos ? "0" : entry.text.substr(first);
    if (entry.negative && digits != "0") {
      fail(path, which + " is negative (-" + digits + ")");
    }
    std::size_t value = 0;
    bool overflow = digits.size() > 20;
    for (char c : digits) {
      if (overflow) break;
      overflow = __builtin_mul_overflow(value, std::size_t{10}, &value) ||
                 __builtin_add_overflow(value, std::size_t(c - '0'), &value);
    }
    if (overflow) fail(path, which + " (" + digits + ") is too large");
    dims.push_back(value);
  }
  return dims;
}

std::string hex_bytes(const unsigned char* bytes, std::size_t n) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (std::size_t i = 0; i < n; ++i) {
    out += "\\x";
    out += hex[bytes[i] >> 4];
    out += hex[bytes[i] & 15];
  }
  return out;
}

std::uint64_t little_endian(const unsigned char* bytes, std::size_t n) {
  std::uint64_t value = 0;
  for (std::size_t i = n; i-- > 0;) value = (value << 8) | bytes[i];
  return value;
}

}  // namespace

// ------------------------------------------------------------------ NpyArray

std::size_t itemsize(Dtype dtype) {
  switch (dtype) {
    case Dtype::f2: return 2;
    case Dtype::f4: return 4;
    case Dtype::f8: return 8;
    case Dtype::c8: return 8;
    case Dtype::c16: return 16;
  }
  return 0;
}

std::string to_descr(Dtype dtype) {
  switch (dtype) {
    case Dtype::f2: return "<f2";
    case Dtype::f4: return "<f4";
    case Dtype::f8: return "<f8";
    case Dtype::c8: return "<c8";
    case Dtype::c16: return "<c16";
  }
  return "?";
}

// Python's repr of a tuple of ints, which is what numpy writes.
std::string shape_string(const std::vector<std::size_t>& shape) {
  std::string out = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    if (i > 0) out += ", ";
    out += std::to_string(shape[i]);
  }
  if (shape.size() == 1) out += ",";
  return out + ")";
}

namespace {

// A Fortran-ordered array (first axis fastest: what np.fft.ifft2 returns and np.save writes as
// is) rearranged into C order (last axis fastest), which NpyArray holds: the element at C
// index (i0, …, ik) comes from Fortran offset i0 + d0·(i1 + d1·(i2 + …)).
void to_c_order(NpyArray& array) {
  const std::size_t rank = array.shape.size();
  if (rank < 2 || array.elements() == 0) return;  // one order for rank 0 and 1
  const std::size_t item = array.itemsize();
  std::vector<std::size_t> fortran_stride(rank, 1);
  for (std::size_t d = 1; d < rank; ++d) fortran_stride[d] = fortran_stride[d - 1] * array.shape[d - 1];
  std::vector<unsigned char> out(array.data.size());
  std::vector<std::size_t> index(rank, 0);
  std::size_t from = 0;  // Fortran offset of `index`
  for (std::size_t to = 0; to < array.elements(); ++to) {
    std::memcpy(out.data() + to * item, array.data.data() + from * item, item);
    for (std::size_t d = rank; d-- > 0;) {  // next C index: the last axis moves fastest
      if (++index[d] < array.shape[d]) {
        from += fortran_stride[d];
        break;
      }
      from -= (array.shape[d] - 1) * fortran_stride[d];
      index[d] = 0;
    }
  }
  array.data = std::move(out);
}

}  // namespace

std::size_t NpyArray::elements() const {
  std::size_t n = 1;
  for (std::size_t d : shape) {
    const auto product = checked_product(n, d);
    if (!product) throw InvalidInput("npy shape " + shape_string(shape) + " overflows");
    n = *product;
  }
  return n;
}

std::size_t NpyArray::itemsize() const { return validation::itemsize(dtype); }

std::vector<double> half_values(const NpyArray& array) {
  if (array.dtype != Dtype::f2) {
    throw InvalidInput("npy array holds '" + to_descr(array.dtype) + "', asked for '<f2'");
  }
  if (array.data.size() != array.elements() * 2) {
    throw InvalidInput("npy array of shape " + shape_string(array.shape) + " holds " +
                       std::to_string(array.data.size()) + " bytes, expected " +
                       std::to_string(array.elements() * 2));
  }
  std::vector<double> out(array.elements());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto bits = std::uint16_t(array.data[2 * i] | (std::uint16_t(array.data[2 * i + 1]) << 8));
    out[i] = half_bits_to_double(bits);
  }
  return out;
}

// ------------------------------------------------------------------ reading

NpyArray read_npy(const fs::path& path) {
  std::error_code error;
  const auto status = fs::status(path, error);
  if (!fs::exists(status)) fail(path, "no such file");
  if (fs::is_directory(status)) fail(path, "is a directory, not an .npy file");
  if (!fs::is_regular_file(status)) fail(path, "is not a regular file");
  std::ifstream file(path, std::ios::binary);
  if (!file) fail(path, std::string("cannot open for reading: ") + std::strerror(errno));
  return read_npy(file, path);
}

NpyArray read_npy(std::istream& file, const fs::path& path) {
  file.seekg(0, std::ios::end);
  const std::streamoff end = file.tellg();
  file.seekg(0, std::ios::beg);
  if (end < 0 || !file) fail(path, "cannot determine the file size");
  const auto size = static_cast<std::size_t>(end);

  // Everything is read with `read_exact`, which only ever asks for bytes already known to exist.
  auto read_exact = [&](void* into, std::size_t n) {
    if (n > 0 && !file.read(static_cast<char*>(into), static_cast<std::streamsize>(n))) {
      fail(path, "read error after " + std::to_string(file.gcount()) + " bytes");
    }
  };

  if (size == 0) fail(path, "empty file (0 bytes), not an .npy file");

  // Magic string and version.
  std::array<unsigned char, kMagicAndVersion> prefix{};
  const std::size_t have = std::min(size, prefix.size());
  read_exact(prefix.data(), have);
  const std::size_t magic_have = std::min(have, kMagic.size());
  if (!std::equal(prefix.begin(), prefix.begin() + magic_have, kMagic.begin())) {
    fail(path, "not a NumPy .npy file: it starts with '" + hex_bytes(prefix.data(), magic_have) +
                   "', not the magic string '\\x93NUMPY'");
  }
  if (size < kMagicAndVersion) {
    fail(path, "truncated: " + std::to_string(size) +
                   " bytes, too short for the magic string and version (8 bytes)");
  }
  const int major = prefix[6], minor = prefix[7];
  if (minor != 0 || major < 1 || major > 3) {
    fail(path, "unsupported .npy format version " + std::to_string(major) + "." +
                   std::to_string(minor) + " (swell reads 1.0, 2.0 and 3.0)");
  }

  // Header length: u16 in version 1.0, u32 in 2.0 and 3.0, little-endian.
  const std::size_t length_bytes = major == 1 ? 2 : 4;
  const std::size_t header_start = kMagicAndVersion + length_bytes;
  if (size < header_start) {
    fail(path, "truncated: the file ends inside the header length field (" +
                   std::to_string(size) + " bytes)");
  }
  std::array<unsigned char, 4> length_field{};
  read_exact(length_field.data(), length_bytes);
  const std::uint64_t header_length = little_endian(length_field.data(), length_bytes);
  if (header_length > size - header_start) {
    fail(path, "truncated header: the header length field says " + std::to_string(header_length) +
                   " bytes but only " + std::to_string(size - header_start) +
                   " bytes follow it");
  }
  if (header_length > kMaxHeaderBytes) {
    fail(path, "header of " + std::to_string(header_length) + " bytes is implausibly large (at most " +
                   std::to_string(kMaxHeaderBytes) + ")");
  }
  std::string header(static_cast<std::size_t>(header_length), '\0');
  read_exact(header.data(), header.size());

  // The dict. Version 3.0 headers are UTF-8 rather than Latin-1; the keys and values that matter
  // are ASCII either way, and any other byte can only end up in a rejected string.
  const Literal dict = HeaderParser(path, header, major <= 2).parse_document();
  if (dict.type != Literal::Type::dict) {
    fail(path, "the header is not a dict (got " + describe(dict) +
                   "); expected {'descr': …, 'fortran_order': …, 'shape': …}");
  }
  const Literal *descr = nullptr, *fortran_order = nullptr, *shape = nullptr;
  for (const auto& [key, value] : dict.entries) {
    if (key.type != Literal::Type::string) {
      fail(path, "header key is " + describe(key) + ", not a string");
    }
    const Literal** slot = key.text == "descr"           ? &descr
                           : key.text == "fortran_order" ? &fortran_order
                           : key.text == "shape"         ? &shape
                                                         : nullptr;
    if (!slot) {
      fail(path, "unexpected header key '" + key.text +
                     "'; an .npy header has exactly 'descr', 'fortran_order' and 'shape'");
    }
    if (*slot) fail(path, "header key '" + key.text + "' appears twice");
    *slot = &value;
  }
  for (const auto& [name, slot] : {std::pair{"descr", descr}, std::pair{"fortran_order", fortran_order},
                                   std::pair{"shape", shape}}) {
    if (!slot) {
      fail(path, std::string("the header has no '") + name +
                     "' key; an .npy header has exactly 'descr', 'fortran_order' and 'shape'");
    }
  }
  if (fortran_order->type != Literal::Type::boolean) {
    fail(path, "'fortran_order' must be True or False, got " + describe(*fortran_order));
  }

  NpyArray array;
  array.dtype = dtype_from_descr(path, *descr);
  array.shape = shape_from_literal(path, *shape);

  // The data: exactly elements · itemsize bytes, computed without overflow before any allocation.
  std::size_t expected = array.itemsize();
  for (std::size_t d : array.shape) {
    const auto product = checked_product(expected, d);
    if (!product) {
      fail(path, "shape " + shape_string(array.shape) + " of '" + to_descr(array.dtype) +
                     "' describes more bytes than fit in 64 bits");
    }
    expected = *product;
  }
  const std::size_t data_start = header_start + static_cast<std::size_t>(header_length);
  const std::size_t available = size - data_start;
  const std::string what = "shape " + shape_string(array.shape) + " of '" + to_descr(array.dtype) +
                           "' needs " + std::to_string(expected) + " bytes of data";
  if (available < expected) {
    fail(path, "truncated data: " + what + ", the file holds " + std::to_string(available));
  }
  if (available > expected) {
    fail(path, std::to_string(available - expected) + " trailing bytes after the data (" + what +
                   ", the file holds " + std::to_string(available) + ")");
  }
  array.data.resize(expected);
  read_exact(array.data.data(), expected);
  if (fortran_order->value) to_c_order(array);
  return array;
}

// ------------------------------------------------------------------ writing

std::vector<unsigned char> npy_header(Dtype dtype, const std::vector<std::size_t>& shape,
                                      int major_version) {
  if (major_version < 0 || major_version > 2) {
    throw InvalidInput("npy: swell writes format versions 1.0 and 2.0 (asked for " +
                       std::to_string(major_version) + ".0)");
  }
  // As numpy: the dict's keys sorted, each value's repr followed by ", ", then the growth room.
  std::string dict = "{'descr': '" + to_descr(dtype) +
                     "', 'fortran_order': False, 'shape': " + shape_string(shape) + ", }";
  if (!shape.empty()) dict += std::string(kGrowthAxisMaxDigits - std::to_string(shape[0]).size(), ' ');

  auto wrap = [&](int major) -> std::optional<std::vector<unsigned char>> {
    const std::size_t length_bytes = major == 1 ? 2 : 4;
    const std::size_t with_newline = dict.size() + 1;
    // numpy's padding rule, including its quirk: an already aligned header gets 64 more spaces.
    const std::size_t pad = kAlign - (kMagicAndVersion + length_bytes + with_newline) % kAlign;
    const std::uint64_t header_length = with_newline + pad;
    if (header_length > (major == 1 ? 0xFFFFu : 0xFFFFFFFFu)) return std::nullopt;
    std::vector<unsigned char> out(kMagic.begin(), kMagic.end());
    out.push_back(static_cast<unsigned char>(major));
    out.push_back(0);
    for (std::size_t i = 0; i < length_bytes; ++i) {
      out.push_back(static_cast<unsigned char>(header_length >> (8 * i)));
    }
    out.insert(out.end(), dict.begin(), dict.end());
    out.insert(out.end(), pad, ' ');
    out.push_back('\n');
    return out;
  };
  if (major_version != 0) {
    if (auto bytes = wrap(major_version)) return *bytes;
    throw InvalidInput("npy: a header of " + std::to_string(dict.size()) +
                       " bytes does not fit format version " + std::to_string(major_version) +
                       ".0");
  }
  if (auto bytes = wrap(1)) return *bytes;
  if (auto bytes = wrap(2)) return *bytes;
  throw InvalidInput("npy: a header of " + std::to_string(dict.size()) + " bytes is too large");
}

void write_npy(const fs::path& path, const NpyArray& array, int major_version) {
  std::optional<std::size_t> expected = array.itemsize();
  for (std::size_t d : array.shape) expected = expected ? checked_product(*expected, d) : expected;
  if (!expected) fail(path, "cannot write: shape " + shape_string(array.shape) + " overflows");
  if (array.data.size() != *expected) {
    fail(path, "cannot write: shape " + shape_string(array.shape) + " of '" +
                   to_descr(array.dtype) + "' needs " + std::to_string(*expected) +
                   " bytes of data, the array holds " + std::to_string(array.data.size()));
  }
  std::vector<unsigned char> header;
  try {
    header = npy_header(array.dtype, array.shape, major_version);
  } catch (const InvalidInput& e) {
    fail(path, e.what());
  }

  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) fail(path, std::string("cannot open for writing: ") + std::strerror(errno));
  file.write(reinterpret_cast<const char*>(header.data()), static_cast<std::streamsize>(header.size()));
  if (!array.data.empty()) {
    file.write(reinterpret_cast<const char*>(array.data.data()),
               static_cast<std::streamsize>(array.data.size()));
  }
  file.close();
  if (!file) {
    // A half-written .npy would later read as "truncated"; leave nothing instead.
    const std::string reason = std::strerror(errno);
    std::error_code ignored;
    fs::remove(path, ignored);
    fail(path, "write failed: " + reason);
  }
}

}  // namespace swell::validation
