#include "swell/reference/errors.hpp"

#include <sstream>

namespace swell {

void require(bool ok, const std::string& what, const std::string& rule, double value) {
  if (ok) return;
  std::ostringstream message;
  message.precision(17);
  message << what << " must be " << rule << " (got " << value << ")";
  throw InvalidInput(message.str());
}

}  // namespace swell
