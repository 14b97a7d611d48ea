// `swell report DIR [--against DIR2] [--out DIR] [--threshold T] [--alpha A] [--gnuplot PROG]`:
// the performance report of a folder written by `swell bench` (reports/README.md), optionally
// compared with another's.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "swell/reference/errors.hpp"
#include "swell/reports/performance_report.hpp"

namespace swell::cli {

namespace fs = std::filesystem;

Action add_report_command(CLI::App& app) {
  auto dir = std::make_shared<std::string>();
  auto o = std::make_shared<reports::ReportOptions>();
  auto against = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  app.add_option("DIR", *dir, "a folder written by swell bench")->required();
  app.add_option("--against", *against, "another swell bench folder to compare with");
  app.add_option("--out", *out, "report folder (default DIR/report)");
  auto* threshold = app.add_option("--threshold", o->threshold,
                                   "least relative change of the median that counts as faster or slower "
                                   "(default 0.35 for separate runs, 0.10 for an interleaved pair)");
  app.add_option("--alpha", o->alpha, "significance level of the U test")->capture_default_str();
  app.add_option("--gnuplot", o->gnuplot, "gnuplot program (PNG figures); missing: data and scripts only")->capture_default_str();
  return [dir, o, against, out, threshold] {
    if (threshold->count() > 0 && !(o->threshold > 0 && o->threshold < 10)) {
      throw InvalidInput(fmt::format("--threshold {}: a relative change in (0, 10), e.g. 0.1 for 10 %", o->threshold));
    }
    o->bench_dir = *dir;
    o->against = *against;
    o->out = out->empty() ? fs::path(*dir) / "report" : fs::path(*out);
    const auto report = reports::write_performance_report(*o);
    std::cout << "swell report: " << (o->out / "README.md").string() << " (report.json, figures/)";
    if (report.contains("comparison")) {
      const auto& c = report["comparison"];
      std::cout << fmt::format("; against {}: {} faster, {} slower, {} unchanged, geometric mean ratio {}",
                               against->c_str(), c["faster"].get<int>(), c["slower"].get<int>(),
                               c["unchanged"].get<int>(), c["geometric_mean_ratio"].dump());
    }
    std::cout << "\n";
    for (const auto& note : report["notes"]) std::cerr << "swell report: note: " << note.get<std::string>() << "\n";
    return 0;
  };
}

}  // namespace swell::cli
