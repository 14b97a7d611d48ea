// libFuzzer target: read_npy on arbitrary bytes, from memory. The reader's contract for bad input
// is InvalidInput naming the file; any other exception escapes and libFuzzer reports it, as it
// does a crash, a sanitizer report or a hang. An array that reads must be whole (data of
// elements · itemsize bytes) and must read back the same after swell writes it.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "swell/reference/errors.hpp"
#include "swell/validation/io/npy.hpp"

namespace {

using swell::validation::NpyArray;

NpyArray read(const std::string& bytes) {
  std::istringstream in(bytes, std::ios::binary);
  return swell::validation::read_npy(in, "fuzz.npy");
}

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "npy fuzzer: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  NpyArray array;
  try {
    array = read(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const swell::InvalidInput&) {
    return 0;  // rejected with a message: the contract
  }
  if (array.data.size() != array.elements() * array.itemsize()) {
    finding("an array read with the wrong number of data bytes");
  }
  const auto header = swell::validation::npy_header(array.dtype, array.shape);
  std::string file(header.begin(), header.end());
  file.append(array.data.begin(), array.data.end());
  NpyArray again;
  try {
    again = read(file);
  } catch (const swell::InvalidInput& e) {
    std::fprintf(stderr, "%s\n", e.what());
    finding("swell's own file of an array it read is rejected");
  }
  if (again.dtype != array.dtype || again.shape != array.shape || again.data != array.data) {
    finding("an array does not read back the same after writing");
  }
  return 0;
}
