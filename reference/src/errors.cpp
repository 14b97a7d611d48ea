#include "swell/reference/errors.hpp"

#include <sstream>

namespace swell {

void fail_requirement(std::string_view what, std::string_view rule, double value) {
  std::ostringstream message;
  message.precision(17);
  message << what << " must be " << rule << " (got " << value << ")";
  throw InvalidInput(message.str());
}

}  // namespace swell
