#pragma once
// The three tiers of failure (see docs/conventions.md, "Errors"):
//  - InvalidInput: the caller asked for something swell cannot do (bad value, unknown name).
//    The message names the field, the rule and the value. The CLI turns it into exit code 2.
//  - NumericalError: a well-posed computation did not reach its stated accuracy.
//  - InternalError: a violated internal invariant — a bug in swell, never the caller's fault
//    (a non-finite value from a case that passed its validity rule). The CLI prints it as a
//    bug with exit code 3; nothing is written.
#include <stdexcept>
#include <string>
#include <string_view>

namespace swell {

class InvalidInput : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// Throws InvalidInput "<what> must be <rule> (got <value>)".
[[noreturn]] void fail_requirement(std::string_view what, std::string_view rule, double value);

// Throws InvalidInput "<what> must be <rule> (got <value>)" unless ok. Inline and on string
// views, so that a check in a function evaluated millions of times (a spectrum under
// quadrature) builds no string unless it fails.
inline void require(bool ok, std::string_view what, std::string_view rule, double value) {
  if (!ok) fail_requirement(what, rule, value);
}

}  // namespace swell
