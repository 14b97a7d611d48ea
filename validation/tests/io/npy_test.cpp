// NumPy .npy I/O against the published format (numpy.lib.format, NEP 1): files byte for byte as
// numpy.save writes them, round trips of every supported dtype, the other header layouts numpy
// and older writers produce, and a named InvalidInput — never a crash — for every malformed file.
//
// The golden bytes here are written out by hand from the spec, not produced by swell's writer.
#include <gtest/gtest.h>

#include <complex>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <random>
#include <sstream>
#include <string>
#include <typeinfo>
#include <unistd.h>
#include <vector>

#include "swell/reference/errors.hpp"
#include "swell/validation/io/npy.hpp"

namespace {

namespace fs = std::filesystem;
using swell::InvalidInput;
using swell::validation::NpyArray;
using swell::validation::npy_header;
using swell::validation::read_npy;
using swell::validation::write_npy;
using Dtype = NpyArray::Dtype;
using namespace std::string_literals;

// Each test gets its own directory under the system temp directory, removed afterwards.
class Npy : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("swell_npy_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path file(const std::string& name) const { return dir_ / name; }

  fs::path write_bytes(const std::string& name, const std::string& bytes) const {
    const auto path = file(name);
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path;
  }

  static std::string read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  fs::path dir_;
};

// magic, version, little-endian header length, the dict, spaces, '\n' — padded by hand so that
// the whole header is `total` bytes (the test states `total`; this only does the arithmetic).
std::string npy_file(int major, const std::string& dict, std::size_t total, const std::string& data = "") {
  const std::size_t length_bytes = major == 1 ? 2 : 4;
  const std::size_t prefix = 8 + length_bytes;
  if (total < prefix + dict.size() + 1) {
    ADD_FAILURE() << "test bug: a " << dict.size() << "-byte dict does not fit " << total;
    return "";
  }
  const std::size_t header_length = total - prefix;
  std::string out = "\x93NUMPY"s + char(major) + '\0';
  for (std::size_t i = 0; i < length_bytes; ++i) out += char((header_length >> (8 * i)) & 0xff);
  out += dict;
  out += std::string(total - prefix - dict.size() - 1, ' ');
  out += '\n';
  return out + data;
}

template <typename T>
std::string raw(const std::vector<T>& values) {
  std::string out(values.size() * sizeof(T), '\0');
  if (!values.empty()) std::memcpy(out.data(), values.data(), out.size());
  return out;
}

// Runs read_npy on the path and expects InvalidInput naming the file and every fragment.
void expect_rejected(const fs::path& path, std::initializer_list<std::string> fragments) {
  try {
    read_npy(path);
    ADD_FAILURE() << path << " was accepted";
  } catch (const InvalidInput& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << "no file name in: " << message;
    for (const auto& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "'" << fragment << "' not in: " << message;
    }
  }
}

const std::string kF8Dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (3,), }";
// 1.0, 2.0, 3.0 as little-endian IEEE doubles: 0x3FF0000000000000, 0x4000…, 0x4008….
const std::string kOneTwoThree =
    "\x00\x00\x00\x00\x00\x00\xf0\x3f"
    "\x00\x00\x00\x00\x00\x00\x00\x40"
    "\x00\x00\x00\x00\x00\x00\x08\x40"s;

// ------------------------------------------------------------------ golden bytes

TEST_F(Npy, WritesFloat64VectorByteForByteAsNumpy) {
  // numpy.save(np.array([1.0, 2.0, 3.0])): a 128-byte header (the data 64-byte aligned),
  // header length 118 = 0x76, the dict as numpy's repr writes it, spaces, '\n'.
  ASSERT_EQ(kF8Dict.size(), 57u);
  const std::string expected = "\x93NUMPY\x01\x00\x76\x00"s + kF8Dict + std::string(60, ' ') +
                               "\n" + kOneTwoThree;
  ASSERT_EQ(expected.size(), 128u + 24u);

  const auto path = file("f8.npy");
  write_npy(path, NpyArray::from_values<double>({3}, std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_EQ(read_bytes(path), expected);

  const auto back = read_npy(write_bytes("golden.npy", expected));
  EXPECT_EQ(back.dtype, Dtype::f8);
  EXPECT_EQ(back.shape, (std::vector<std::size_t>{3}));
  EXPECT_EQ(back.values<double>(), (std::vector<double>{1.0, 2.0, 3.0}));
}

TEST_F(Npy, WritesComplex64MatrixByteForByteAsNumpy) {
  // numpy.save(np.arange(1, 13, dtype='<f4').view('<c8').reshape(2, 3)): re, im interleaved.
  const std::string dict = "{'descr': '<c8', 'fortran_order': False, 'shape': (2, 3), }";
  std::vector<float> interleaved;
  for (int i = 1; i <= 12; ++i) interleaved.push_back(float(i));
  const std::string data = raw(interleaved);
  // 1.0f is 0x3F800000: spot-check the layout written out by hand.
  ASSERT_EQ(data.substr(0, 8), "\x00\x00\x80\x3f\x00\x00\x00\x40"s);
  const std::string expected = npy_file(1, dict, 128, data);

  std::vector<std::complex<float>> values;
  for (int i = 0; i < 6; ++i) values.emplace_back(float(2 * i + 1), float(2 * i + 2));
  const auto path = file("c8.npy");
  write_npy(path, NpyArray::from_values({2, 3}, values));
  EXPECT_EQ(read_bytes(path), expected);
  EXPECT_EQ(read_npy(path).values<std::complex<float>>(), values);
}

TEST_F(Npy, HeaderOfEachDtypeAndRank) {
  struct Case {
    Dtype dtype;
    std::vector<std::size_t> shape;
    std::string dict;
  };
  // numpy ≥ 1.24 appends 21 − len(repr(shape[0])) spaces of growth room after the dict; with the
  // 64-byte alignment these small headers all come to 128 bytes either way.
  const std::vector<Case> cases = {
      {Dtype::f4, {5}, "{'descr': '<f4', 'fortran_order': False, 'shape': (5,), }"},
      {Dtype::f8, {4, 6}, "{'descr': '<f8', 'fortran_order': False, 'shape': (4, 6), }"},
      {Dtype::c8, {1000000}, "{'descr': '<c8', 'fortran_order': False, 'shape': (1000000,), }"},
      {Dtype::c16, {2048, 1025}, "{'descr': '<c16', 'fortran_order': False, 'shape': (2048, 1025), }"},
      {Dtype::f8, {}, "{'descr': '<f8', 'fortran_order': False, 'shape': (), }"},
  };
  for (const auto& c : cases) {
    const auto header = npy_header(c.dtype, c.shape);
    EXPECT_EQ(std::string(header.begin(), header.end()), npy_file(1, c.dict, 128)) << c.dict;
  }
}

TEST_F(Npy, AlreadyAlignedHeaderGetsAnotherSixtyFourBytesAsInNumpy) {
  // numpy pads by 64 − (len % 64), which is 64, not 0, when the header would already end on a
  // boundary: numpy.save(np.empty((0, 1, 1, 1, 1, 1, 1, 1, 10**17))) has a 192-byte header.
  const std::vector<std::size_t> shape = {0, 1, 1, 1, 1, 1, 1, 1, 100000000000000000};
  const std::string dict =
      "{'descr': '<f8', 'fortran_order': False, 'shape': (0, 1, 1, 1, 1, 1, 1, 1, "
      "100000000000000000), }" + std::string(20, ' ');  // growth room: 21 − len("0")
  ASSERT_EQ(10 + dict.size() + 1, 128u) << "the unpadded header is exactly aligned";
  const auto header = npy_header(Dtype::f8, shape);
  EXPECT_EQ(std::string(header.begin(), header.end()), npy_file(1, dict, 192));

  // A zero-element array of that shape writes and reads back.
  NpyArray empty;
  empty.shape = shape;
  const auto path = file("empty.npy");
  write_npy(path, empty);
  EXPECT_EQ(fs::file_size(path), 192u);
  EXPECT_EQ(read_npy(path).shape, shape);
}

TEST_F(Npy, WritesVersion2WhenAskedAndReadsItBack) {
  // Version 2.0: a 4-byte header length (116 = 0x74), same dict, still 128 bytes in all.
  const std::string expected = "\x93NUMPY\x02\x00\x74\x00\x00\x00"s + kF8Dict +
                               std::string(58, ' ') + "\n" + kOneTwoThree;
  const auto path = file("v2.npy");
  write_npy(path, NpyArray::from_values<double>({3}, std::vector<double>{1, 2, 3}), 2);
  EXPECT_EQ(read_bytes(path), expected);
  EXPECT_EQ(read_npy(path).values<double>(), (std::vector<double>{1, 2, 3}));
  EXPECT_THROW(npy_header(Dtype::f8, {3}, 3), InvalidInput);
}

// ------------------------------------------------------------------ round trips

template <typename T>
std::vector<T> ramp(std::size_t n) {
  std::vector<T> v;
  for (std::size_t i = 0; i < n; ++i) {
    if constexpr (std::is_floating_point_v<T>) {
      v.push_back(T(0.25) * T(i) - T(1.5));
    } else {
      using R = typename T::value_type;
      v.emplace_back(R(0.5) * R(i) - R(2), R(-0.125) * R(i) + R(1e-3));
    }
  }
  return v;
}

template <typename T>
void round_trip(const fs::path& dir, Dtype dtype) {
  for (const auto& shape : std::vector<std::vector<std::size_t>>{{7}, {1}, {3, 4}, {1, 5}, {6, 1}}) {
    std::size_t n = 1;
    for (auto d : shape) n *= d;
    const auto values = ramp<T>(n);
    const auto original = NpyArray::from_values(shape, values);
    ASSERT_EQ(original.dtype, dtype);
    for (int version : {1, 2}) {
      const auto path = dir / ("rt_" + swell::validation::to_descr(dtype).substr(1) + "_" +
                               std::to_string(shape.size()) + "_" + std::to_string(version) + ".npy");
      write_npy(path, original, version);
      // Data starts on a 64-byte boundary, as numpy aligns it.
      EXPECT_EQ((fs::file_size(path) - original.data.size()) % 64, 0u);
      const auto back = read_npy(path);
      EXPECT_EQ(back.dtype, dtype);
      EXPECT_EQ(back.shape, shape);
      EXPECT_EQ(back.data, original.data);
      EXPECT_EQ(back.values<T>(), values);
    }
  }
}

TEST_F(Npy, RoundTripsFloat32) { round_trip<float>(dir_, Dtype::f4); }
TEST_F(Npy, RoundTripsFloat64) { round_trip<double>(dir_, Dtype::f8); }
TEST_F(Npy, RoundTripsComplex64) { round_trip<std::complex<float>>(dir_, Dtype::c8); }
TEST_F(Npy, RoundTripsComplex128) { round_trip<std::complex<double>>(dir_, Dtype::c16); }

TEST_F(Npy, KeepsNonFiniteValuesBitForBit) {
  // NaN and Inf are data, not an I/O problem: the consumer decides what to do with them.
  const std::vector<double> values = {std::numeric_limits<double>::quiet_NaN(),
                                      std::numeric_limits<double>::infinity(), -0.0};
  const auto original = NpyArray::from_values<double>({3}, values);
  const auto path = file("nan.npy");
  write_npy(path, original);
  EXPECT_EQ(read_npy(path).data, original.data);
}

TEST_F(Npy, ReadsOtherValidHeaderLayouts) {
  // Layouts numpy, older numpy and other writers produce, all meaning '<f8' of shape (3,).
  const std::vector<std::pair<std::string, std::string>> files = {
      // numpy < 1.9 aligned the data to 16 bytes only: 80 bytes of header.
      {"legacy16", npy_file(1, kF8Dict, 80, kOneTwoThree)},
      // Hand-made version 2.0 and 3.0 (UTF-8) headers with a 64-byte header.
      {"v2", npy_file(2, kF8Dict, 128, kOneTwoThree)},
      {"v3", npy_file(3, kF8Dict, 128, kOneTwoThree)},
      // Keys in another order, double quotes, no trailing comma, odd whitespace.
      {"order", npy_file(1, "{\"shape\":(3 ,),'descr' : \"<f8\",\n 'fortran_order':False}", 80,
                         kOneTwoThree)},
      // Python 2 numpy wrote shapes as longs: (3L,).
      {"py2long", npy_file(1, "{'descr': '<f8', 'fortran_order': False, 'shape': (3L,), }", 80,
                           kOneTwoThree)},
      // No padding at all (header length exactly the dict and its newline).
      {"unpadded", npy_file(1, kF8Dict, 10 + kF8Dict.size() + 1, kOneTwoThree)},
  };
  for (const auto& [name, bytes] : files) {
    SCOPED_TRACE(name);
    const auto array = read_npy(write_bytes(name + ".npy", bytes));
    EXPECT_EQ(array.dtype, Dtype::f8);
    EXPECT_EQ(array.shape, (std::vector<std::size_t>{3}));
    EXPECT_EQ(array.values<double>(), (std::vector<double>{1, 2, 3}));
  }
}

TEST_F(Npy, ReadsAnyRank) {
  // The reader is general; it is `swell fft` that needs rank 1 or 2.
  const auto scalar = read_npy(write_bytes(
      "r0.npy", npy_file(1, "{'descr': '<f8', 'fortran_order': False, 'shape': (), }", 128,
                         kOneTwoThree.substr(0, 8))));
  EXPECT_TRUE(scalar.shape.empty());
  EXPECT_EQ(scalar.values<double>(), (std::vector<double>{1.0}));
  const auto cube = read_npy(write_bytes(
      "r3.npy", npy_file(1, "{'descr': '<f8', 'fortran_order': False, 'shape': (1, 3, 1), }", 128,
                         kOneTwoThree)));
  EXPECT_EQ(cube.shape, (std::vector<std::size_t>{1, 3, 1}));
  const auto empty = read_npy(write_bytes(
      "zero.npy", npy_file(1, "{'descr': '<c16', 'fortran_order': False, 'shape': (0, 4), }", 128)));
  EXPECT_EQ(empty.elements(), 0u);
}

// Fortran order (first axis fastest, as np.save writes np.fft.ifft2's output): read back in C
// order. Element (i, j, k) of a 2×3×4 array holds 100i + 10j + k; on disk it sits at Fortran
// offset i + 2j + 6k.
TEST_F(Npy, FortranOrderIsReadIntoCOrder) {
  std::vector<double> fortran(24);
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 4; ++k) fortran[i + 2 * j + 6 * k] = 100 * i + 10 * j + k;
    }
  }
  std::string data(reinterpret_cast<const char*>(fortran.data()), 24 * 8);
  const auto cube = read_npy(write_bytes(
      "f3.npy", npy_file(1, "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3, 4), }", 128, data)));
  ASSERT_EQ(cube.shape, (std::vector<std::size_t>{2, 3, 4}));
  const auto values = cube.values<double>();
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 4; ++k) EXPECT_EQ(values[(i * 3 + j) * 4 + k], 100 * i + 10 * j + k);
    }
  }
  // Complex 2-D (np.fft output): (ny, nx) = (2, 3), element (j, i) = j + i·1i, column-major.
  std::vector<std::complex<float>> column_major;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 2; ++j) column_major.emplace_back(float(j), float(i));
  }
  data.assign(reinterpret_cast<const char*>(column_major.data()), 6 * 8);
  const auto plane = read_npy(write_bytes(
      "f2.npy", npy_file(1, "{'descr': '<c8', 'fortran_order': True, 'shape': (2, 3), }", 128, data)));
  const auto z = plane.values<std::complex<float>>();
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) EXPECT_EQ(z[j * 3 + i], std::complex<float>(float(j), float(i)));
  }
  // Rank 1: the same bytes either way.
  const auto line = read_npy(write_bytes(
      "f1.npy", npy_file(1, "{'descr': '<f8', 'fortran_order': True, 'shape': (3,), }", 128, kOneTwoThree)));
  EXPECT_EQ(line.values<double>(), (std::vector<double>{1, 2, 3}));
}

// ------------------------------------------------------------------ malformed files

TEST_F(Npy, MissingFileAndDirectory) {
  expect_rejected(file("nothing_here.npy"), {"no such file"});
  fs::create_directories(file("adir.npy"));
  expect_rejected(file("adir.npy"), {"directory"});
  expect_rejected(write_bytes("empty.npy", ""), {"empty"});
}

TEST_F(Npy, EveryTruncationIsNamed) {
  const std::string whole = npy_file(1, "{'descr': '<c16', 'fortran_order': False, 'shape': (2, 3), }",
                                     128, raw(ramp<std::complex<double>>(6)));
  ASSERT_NO_THROW(read_npy(write_bytes("whole.npy", whole)));
  for (std::size_t length = 0; length < whole.size(); ++length) {
    SCOPED_TRACE(length);
    const auto path = write_bytes("cut.npy", whole.substr(0, length));
    if (length == 0) {
      expect_rejected(path, {"empty"});
    } else if (length < 6) {
      expect_rejected(path, {});
    } else {
      expect_rejected(path, {"truncated"});
    }
  }
}

TEST_F(Npy, BadMagicAndVersion) {
  const std::string good = npy_file(1, kF8Dict, 128, kOneTwoThree);
  std::string bytes = good;
  bytes[0] = '\x94';
  expect_rejected(write_bytes("magic0.npy", bytes), {"magic"});
  bytes = good;
  bytes[5] = 'Z';
  expect_rejected(write_bytes("magic5.npy", bytes), {"magic"});
  expect_rejected(write_bytes("text.npy", "hello, world\n"), {"magic"});
  for (const auto& [major, minor] : {std::pair{1, 1}, {0, 0}, {4, 0}, {2, 5}, {255, 255}}) {
    bytes = good;
    bytes[6] = char(major);
    bytes[7] = char(minor);
    expect_rejected(write_bytes("version.npy", bytes),
                    {"version " + std::to_string(major) + "." + std::to_string(minor)});
  }
}

TEST_F(Npy, UnsupportedLayoutsAndDtypes) {
  auto with = [&](const std::string& name, const std::string& descr, const std::string& order,
                  const std::string& shape) {
    const std::string dict =
        "{'descr': " + descr + ", 'fortran_order': " + order + ", 'shape': " + shape + ", }";
    return write_bytes(name, npy_file(1, dict, 128, kOneTwoThree));
  };
  expect_rejected(with("order1.npy", "'<f8'", "1", "(3,)"), {"fortran_order", "True or False"});
  expect_rejected(with("big.npy", "'>f8'", "False", "(3,)"), {"big-endian", "'>f8'"});
  expect_rejected(with("int.npy", "'<i4'", "False", "(6,)"),
                  {"unsupported dtype '<i4'", "'<f4'", "'<f8'", "'<c8'", "'<c16'"});
  expect_rejected(with("big_half.npy", "'>f2'", "False", "(12,)"), {"big-endian", "'>f2'", "'<f2'"});
  expect_rejected(with("long_double.npy", "'<f16'", "False", "(1,)"), {"unsupported dtype"});
  expect_rejected(with("quad.npy", "'<c32'", "False", "(1,)"), {"unsupported dtype"});
  expect_rejected(with("pipe.npy", "'|f8'", "False", "(3,)"), {"'|f8'", "'<f8'"});
  expect_rejected(with("native.npy", "'=f8'", "False", "(3,)"), {"'=f8'", "'<f8'"});
  expect_rejected(with("struct.npy", "[('x', '<f8')]", "False", "(3,)"), {"structured"});
  expect_rejected(with("descr_num.npy", "8", "False", "(3,)"), {"'descr'"});
}

TEST_F(Npy, BadShapes) {
  auto with_shape = [&](const std::string& name, const std::string& shape) {
    return write_bytes(
        name, npy_file(1, "{'descr': '<f8', 'fortran_order': False, 'shape': " + shape + ", }",
                       128, kOneTwoThree));
  };
  expect_rejected(with_shape("neg.npy", "(-1,)"), {"negative", "-1"});
  expect_rejected(with_shape("neg2.npy", "(3, -2)"), {"entry 1", "negative"});
  expect_rejected(with_shape("float.npy", "(3.0,)"), {"not an integer", "3.0"});
  expect_rejected(with_shape("string.npy", "('3',)"), {"not an integer"});
  expect_rejected(with_shape("bool.npy", "(True,)"), {"not an integer"});
  expect_rejected(with_shape("list.npy", "[3]"), {"tuple", "list"});
  expect_rejected(with_shape("int.npy", "3"), {"tuple"});
  expect_rejected(with_shape("paren.npy", "(3)"), {"tuple"});  // Python: (3) is just 3
  expect_rejected(with_shape("hex.npy", "(0x3,)"), {"not an integer"});
  // Sizes that overflow are refused before anything is allocated.
  expect_rejected(with_shape("huge.npy", "(99999999999999999999999,)"), {"too large"});
  expect_rejected(with_shape("over.npy", "(1099511627776, 1099511627776)"), {"64 bits"});
  expect_rejected(with_shape("over3.npy", "(4294967296, 4294967296, 0)"), {"64 bits"});
  // Plausible but wrong: more data than the file holds.
  expect_rejected(with_shape("long.npy", "(1000000000000,)"), {"truncated data"});
}

TEST_F(Npy, BadHeaderDicts) {
  auto with_dict = [&](const std::string& name, const std::string& dict) {
    return write_bytes(name, npy_file(1, dict, 128, kOneTwoThree));
  };
  expect_rejected(with_dict("list.npy", "[1, 2]"), {"not a dict"});
  expect_rejected(with_dict("string.npy", "'descr'"), {"not a dict"});
  expect_rejected(with_dict("no_descr.npy", "{'fortran_order': False, 'shape': (3,), }"),
                  {"no 'descr'"});
  expect_rejected(with_dict("no_order.npy", "{'descr': '<f8', 'shape': (3,), }"),
                  {"no 'fortran_order'"});
  expect_rejected(with_dict("no_shape.npy", "{'descr': '<f8', 'fortran_order': False, }"),
                  {"no 'shape'"});
  expect_rejected(with_dict("extra.npy",
                            "{'descr': '<f8', 'fortran_order': False, 'shape': (3,), 'x': 1}"),
                  {"unexpected header key 'x'"});
  expect_rejected(with_dict("twice.npy",
                            "{'descr': '<f8', 'descr': '<f8', 'fortran_order': False, 'shape': (3,)}"),
                  {"twice"});
  expect_rejected(with_dict("keytype.npy", "{1: '<f8', 'fortran_order': False, 'shape': (3,)}"),
                  {"not a string"});
  expect_rejected(with_dict("open.npy", "{'descr': '<f8', 'fortran_order': False, 'shape': (3,), "),
                  {"cannot parse"});
  expect_rejected(with_dict("unterminated.npy", "{'descr': '<f8, 'fortran_order': False}"),
                  {"cannot parse"});
  expect_rejected(with_dict("escape.npy", "{'descr': '<f\\x38', 'fortran_order': False, 'shape': (3,)}"),
                  {"escape"});
  expect_rejected(with_dict("name.npy", "{'descr': '<f8', 'fortran_order': false, 'shape': (3,)}"),
                  {"false"});
  expect_rejected(with_dict("after.npy", kF8Dict + " 1"), {"after the dict"});
  expect_rejected(with_dict("nul.npy", "{'descr': '<f8',\0 'fortran_order': False, 'shape': (3,)}"s),
                  {"0x00"});
  // Deep nesting is refused, not recursed into until the stack runs out.
  expect_rejected(write_bytes("deep.npy", npy_file(2, "{'shape': " + std::string(100000, '('), 100032)),
                  {"nested"});
}

TEST_F(Npy, HeaderLengthBeyondTheFileAndTrailingBytes) {
  std::string bytes = npy_file(1, kF8Dict, 128, kOneTwoThree);
  bytes[8] = '\xff';
  bytes[9] = '\xff';  // 65535 bytes of header in a 152-byte file
  expect_rejected(write_bytes("hlen.npy", bytes), {"header length", "65535"});
  std::string v2 = npy_file(2, kF8Dict, 128, kOneTwoThree);
  v2[8] = v2[9] = v2[10] = v2[11] = '\xff';  // 4 GiB of header
  expect_rejected(write_bytes("hlen2.npy", v2), {"header length", "4294967295"});

  expect_rejected(write_bytes("trailing.npy", npy_file(1, kF8Dict, 128, kOneTwoThree + "\x01"s)),
                  {"1 trailing bytes"});
  expect_rejected(write_bytes("short.npy", npy_file(1, kF8Dict, 128, kOneTwoThree.substr(0, 23))),
                  {"truncated data", "24 bytes"});
}

TEST_F(Npy, CorruptedFilesNeverCrash) {
  // Random byte flips across the header (and a bit beyond): each file either reads or is
  // rejected with InvalidInput naming it — never another exception, never a crash.
  const std::string good = npy_file(1, "{'descr': '<c8', 'fortran_order': False, 'shape': (2, 2), }",
                                    128, raw(ramp<std::complex<float>>(4)));
  std::mt19937 random(12345);
  std::uniform_int_distribution<std::size_t> where(0, 140);
  std::uniform_int_distribution<int> byte(0, 255), flips(1, 4);
  const std::string alphabet = "(){}[],:' \"-0123456789LTFNe.<>|=fci\n\0"s;
  std::uniform_int_distribution<std::size_t> pick(0, alphabet.size() - 1);
  int accepted = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string bytes = good;
    for (int k = flips(random); k > 0; --k) {
      // Half the flips use header punctuation, which reaches deeper into the parser.
      bytes[where(random)] = trial % 2 ? char(byte(random)) : alphabet[pick(random)];
    }
    const auto path = write_bytes("fuzz.npy", bytes);
    try {
      read_npy(path);
      ++accepted;
    } catch (const InvalidInput& e) {
      ASSERT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      FAIL() << "trial " << trial << ": " << typeid(e).name() << ": " << e.what();
    }
  }
  EXPECT_GT(accepted, 0) << "flips in the padding are harmless";
}

// ------------------------------------------------------------------ writing errors

TEST_F(Npy, WriterRefusesInconsistentArraysAndUnwritablePaths) {
  NpyArray bad;
  bad.dtype = Dtype::c16;
  bad.shape = {4};
  bad.data.resize(63);  // 4 complex128 need 64 bytes
  try {
    write_npy(file("bad.npy"), bad);
    ADD_FAILURE() << "accepted 63 bytes for shape (4,)";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("bad.npy"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("64"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(file("bad.npy")));

  const auto nowhere = file("no/such/dir/out.npy");
  try {
    write_npy(nowhere, NpyArray::from_values<float>({1}, std::vector<float>{1}));
    ADD_FAILURE() << "wrote into a missing directory";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(nowhere.string()), std::string::npos) << e.what();
  }

  EXPECT_THROW(NpyArray::from_values<double>({2, 2}, std::vector<double>{1, 2, 3}), InvalidInput);
  EXPECT_THROW(NpyArray::from_values<double>({3}, std::vector<double>{1, 2, 3}).values<float>(),
               InvalidInput);
}

// ------------------------------------------------------------------ reading from a stream
// read_npy(std::istream&, name), which the fuzzer (validation/fuzz/npy_fuzzer.cpp) calls: the
// same reader as for files, messages naming `name`.

TEST_F(Npy, ReadsFromAStreamAsFromAFile) {
  const std::string bytes = npy_file(1, kF8Dict, 128, kOneTwoThree);
  std::istringstream in(bytes, std::ios::binary);
  const NpyArray from_stream = read_npy(in, "memory.npy");
  const NpyArray from_file = read_npy(write_bytes("same.npy", bytes));
  EXPECT_EQ(from_stream.dtype, from_file.dtype);
  EXPECT_EQ(from_stream.shape, from_file.shape);
  EXPECT_EQ(from_stream.data, from_file.data);
  EXPECT_EQ(from_stream.values<double>(), (std::vector<double>{1, 2, 3}));

  std::istringstream truncated(bytes.substr(0, bytes.size() - 1), std::ios::binary);
  try {
    (void)read_npy(truncated, "memory.npy");
    ADD_FAILURE() << "accepted a truncated stream";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()).rfind("memory.npy: truncated data", 0), 0u) << e.what();
  }
}

}  // namespace
