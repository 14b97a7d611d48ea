// libFuzzer target: parse_case_toml on arbitrary bytes. The reader's contract for bad input is
// InvalidInput naming the file; any other exception escapes and libFuzzer reports it, as it
// does a crash, a sanitizer report or a hang. A case that parses must also survive the round
// trip case_file.hpp promises: case_toml writes it, parse_case_toml reads back the same case.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "swell/reference/errors.hpp"
#include "swell/validation/io/case_file.hpp"

namespace {

void fail_round_trip(const std::string& first, const std::string& second) {
  std::fprintf(stderr, "case_toml does not round-trip:\n--- written\n%s\n--- read back and written\n%s\n",
               first.c_str(), second.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  swell::validation::CaseFile parsed;
  try {
    parsed = swell::validation::parse_case_toml(text, "fuzz.toml");
  } catch (const swell::InvalidInput&) {
    return 0;  // rejected with a message: the contract
  }
  const std::string written = swell::validation::case_toml(parsed);
  std::string rewritten;
  try {
    rewritten = swell::validation::case_toml(swell::validation::parse_case_toml(written, "fuzz.toml"));
  } catch (const swell::InvalidInput& e) {
    std::fprintf(stderr, "case_toml wrote a case its reader rejects: %s\n", e.what());
    fail_round_trip(written, "");
  }
  if (rewritten != written) fail_round_trip(written, rewritten);
  return 0;
}
