// swell.fit: the JONSWAP fit of `swell fit` on height arrays, one list of frames per
// realization; the result is the command's JSON document (jonswap_fit_json).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reference/sampling_validity.hpp"
#include "swell/validation/fit/jonswap_fit.hpp"
#include "swell/validation/io/frame_io.hpp"

namespace swell::python {
namespace {

std::string fit(const Case& c, const py::list& realizations, bool sigma, int frame, const std::string& interval) {
  const auto& file = *c.file;
  validation::require_single_grid(file, "swell.fit");
  const auto& ocean = file.ocean;
  const auto truth = validation::case_jonswap_parameters(ocean);  // the family, before any array
  if (interval != "profile" && interval != "wald") {
    throw InvalidInput(fmt::format("interval '{}': give \"profile\" or \"wald\"", interval));
  }
  // The command's validity rule, per sample and realization (fit_command.cpp).
  const double samples = double(ocean.sampling().size());
  const double bytes = samples * (16.0 * double(py::len(realizations)) * ocean.frames + 48);
  reference::require_valid_sampling(ocean, reference::kFloat64, std::uint64_t(std::min(bytes, 1.8e19)), "swell.fit");
  std::vector<reference::FrameSequence> frames;
  for (std::size_t r = 0; r < py::len(realizations); ++r) {
    try {
      frames.push_back(validation::frames_from_arrays(ocean, file.input.precision,
                                                      field_arrays_of(realizations[r].cast<py::dict>())));
    } catch (const InvalidInput& e) {
      throw InvalidInput(py::len(realizations) == 1 ? std::string(e.what())
                                                    : fmt::format("realization {}: {}", r, e.what()));
    }
  }
  validation::JonswapFitOptions options;
  options.fit_sigma = sigma;
  options.frame = frame;
  options.interval = interval == "wald" ? validation::IntervalMethod::wald
                                        : validation::IntervalMethod::profile_likelihood;
  py::gil_scoped_release release;
  const auto result = validation::fit_jonswap(ocean, frames, options);
  auto document = validation::jonswap_fit_json(result, truth, file.scale == validation::SpectrumScale::free,
                                               options.interval);
  document["report"] = result.report;
  return document.dump();
}

}  // namespace

void bind_fit(py::module_& m) { m.def("fit", &fit); }

}  // namespace swell::python
