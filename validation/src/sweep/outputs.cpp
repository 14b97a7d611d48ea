// A sweep's outputs over its runs: runs.csv and runs.json (one row a run), points.csv and
// points.json (per point, the statistics over its seeds against the point's case), and the plots
// of each statistic against each numeric varied key (docs/sweeps.md).
#include "swell/validation/sweep/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <tuple>

#include <boost/math/distributions/students_t.hpp>
#include <fmt/format.h>

#include "sweep/sweep_internal.hpp"
#include "swell/reports/figures.hpp"
#include "swell/validation/fit/jonswap_fit.hpp"
#include "swell/validation/results/report.hpp"
#include "swell/validation/stats/periodogram.hpp"

namespace swell::validation::sweep {

using namespace detail;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Mean, standard deviation and the t interval of the mean (95 %) of the finite values.
struct Summary {
  int n = 0;
  double mean = kNaN, sd = kNaN, low = kNaN, high = kNaN;
};

Summary summarize(const std::vector<double>& values) {
  Summary s;
  double sum = 0;
  for (double x : values) {
    if (std::isfinite(x)) {
      sum += x;
      ++s.n;
    }
  }
  if (s.n == 0) return s;
  s.mean = sum / s.n;
  if (s.n < 2) return s;
  double squares = 0;
  for (double x : values) {
    if (std::isfinite(x)) squares += (x - s.mean) * (x - s.mean);
  }
  s.sd = std::sqrt(squares / (s.n - 1));
  const double t = boost::math::quantile(boost::math::students_t(s.n - 1), 0.975);
  s.low = s.mean - t * s.sd / std::sqrt(double(s.n));
  s.high = s.mean + t * s.sd / std::sqrt(double(s.n));
  return s;
}

struct PointSummary {
  std::size_t point = 0;
  int runs = 0;
  std::map<std::string, Summary> statistics;  // statistic_names() and fit_hs, fit_tp, fit_gamma
  // The fit against the point's truth (its case's JONSWAP parameters).
  std::map<std::string, double> truth, bias, coverage;
  std::map<std::string, int> calibrated;
  int converged = 0;
  // What the point's spectrum gives on its grid (band-limited: Σ μ(k) over the grid's k ≠ 0,
  // each at ω(|k|)): hs = 4 √m0, tm01 = 2π m0/m1, tm02 = 2π √(m0/m2). The measured means
  // scatter about these; the spectrum's untruncated moments (swell spectrum) differ from them
  // by the tail beyond the grid's Nyquist wave number.
  double expected_hs = kNaN, expected_tm01 = kNaN, expected_tm02 = kNaN;
};

void expected_moments(const reference::OceanCase& ocean, PointSummary& p) {
  const FrequencyMoments moments =
      frequency_moments(ocean, expected_periodogram(*ocean.directional_spectrum(), ocean.grid));
  p.expected_hs = 4 * std::sqrt(moments.m[0]);
  p.expected_tm01 = moments.tm01();
  p.expected_tm02 = moments.tm02();
}

const std::vector<std::string> kFitNames = {"hs", "tp", "gamma"};

// The value labels of a point, one per variation.
std::vector<std::string> labels_of(const SweepSpec& spec, std::size_t point) {
  const auto index = value_indices(spec, point);
  std::vector<std::string> labels(spec.variations.size());
  for (std::size_t v = 0; v < labels.size(); ++v) labels[v] = spec.variations[v].labels[index[v]];
  return labels;
}

std::string csv_cell(const std::string& s) {
  return s.find_first_of(",\"\n") == std::string::npos ? s : "\"" + s + "\"";
}

// The statistics summarized per point: statistic_names(), and the fitted parameters with --fit.
std::vector<std::string> summarized_names(const SweepSpec& spec) {
  std::vector<std::string> names = statistic_names();
  if (spec.fit) {
    for (const auto& name : kFitNames) names.push_back("fit_" + name);
  }
  return names;
}

// runs.csv and runs.json: one row a run, in the order of `rows`.
void write_runs(const SweepSpec& spec, const std::vector<RunRow>& rows, const fs::path& dir) {
  std::ofstream csv(dir / "runs.csv");
  csv << "point,replicate,seed";
  for (const auto& v : spec.variations) csv << "," << csv_cell(v.name);
  for (const auto& name : statistic_names()) csv << "," << name;
  if (spec.fit) {
    for (const auto& name : kFitNames) {
      csv << ",fit_" << name << ",fit_" << name << "_ci95_low,fit_" << name << "_ci95_high,fit_"
          << name << "_calibrated";
    }
    csv << ",fit_converged";
  }
  csv << ",seconds\n";
  json runs = json::array();
  for (const auto& row : rows) {
    csv << row.point << "," << row.replicate << "," << row.seed;
    for (const auto& label : labels_of(spec, row.point)) csv << "," << csv_cell(label);
    for (const auto& name : statistic_names()) csv << "," << text(row.statistics.at(name));
    if (spec.fit) {
      for (const auto& name : kFitNames) {
        const auto& f = row.fit.at(name);
        csv << "," << text(f.value) << "," << text(f.ci95_low) << "," << text(f.ci95_high) << ","
            << (f.calibrated ? 1 : 0);
      }
      csv << "," << (row.fit_converged ? 1 : 0);
    }
    csv << "," << fmt::format("{:.6f}", row.seconds) << "\n";
    runs.push_back(row_json(spec, row));
  }
  std::ofstream(dir / "runs.json") << json{{"sweep", spec.to_json()}, {"runs", runs}}.dump(1) << "\n";
}

// Per point, over its seeds: each statistic's mean and interval, the spectrum's band-limited
// moments, and with --fit the fits' bias and coverage against the point's case.
std::vector<PointSummary> summarize_points(const SweepSpec& spec, const std::vector<RunRow>& rows) {
  std::vector<PointSummary> points;
  std::map<std::size_t, std::vector<const RunRow*>> by_point;
  for (const auto& row : rows) by_point[row.point].push_back(&row);
  for (const auto& [index, point_rows] : by_point) {
    PointSummary p;
    p.point = index;
    p.runs = int(point_rows.size());
    for (const auto& name : statistic_names()) {
      std::vector<double> values;
      for (const auto* r : point_rows) values.push_back(r->statistics.at(name));
      p.statistics[name] = summarize(values);
    }
    const Point point = make_point(spec, index);
    expected_moments(point.case_file.ocean, p);
    if (spec.fit) {
      const auto truth = case_jonswap_parameters(point.case_file.ocean);
      p.truth = {{"hs", truth.hs}, {"tp", truth.tp}, {"gamma", truth.gamma}};
      for (const auto* r : point_rows) p.converged += r->fit_converged;
      for (const auto& name : kFitNames) {
        std::vector<double> values;
        int covered = 0, calibrated = 0;
        for (const auto* r : point_rows) {
          const auto& f = r->fit.at(name);
          values.push_back(r->fit_converged ? f.value : kNaN);
          if (r->fit_converged && f.calibrated) {
            ++calibrated;
            covered += f.ci95_low <= p.truth[name] && p.truth[name] <= f.ci95_high;
          }
        }
        p.statistics["fit_" + name] = summarize(values);
        p.bias[name] = p.statistics["fit_" + name].mean - p.truth[name];
        p.calibrated[name] = calibrated;
        p.coverage[name] = calibrated > 0 ? double(covered) / calibrated : kNaN;
      }
    }
    points.push_back(std::move(p));
  }
  return points;
}

// points.csv and points.json.
void write_points(const SweepSpec& spec, const std::vector<PointSummary>& points,
                  const fs::path& dir) {
  const std::vector<std::string> summarized = summarized_names(spec);
  std::ofstream csv(dir / "points.csv");
  csv << "point";
  for (const auto& v : spec.variations) csv << "," << csv_cell(v.name);
  csv << ",runs,expected_hs,expected_tm01,expected_tm02";
  for (const auto& name : summarized) {
    csv << "," << name << "_mean," << name << "_sd," << name << "_ci95_low," << name << "_ci95_high";
  }
  if (spec.fit) {
    for (const auto& name : kFitNames) {
      csv << ",true_" << name << ",bias_" << name << ",coverage_" << name << ",calibrated_" << name;
    }
    csv << ",converged";
  }
  csv << "\n";
  json points_json = json::array();
  for (const auto& p : points) {
    csv << p.point;
    const auto labels = labels_of(spec, p.point);
    for (const auto& label : labels) csv << "," << csv_cell(label);
    csv << "," << p.runs << "," << text(p.expected_hs) << "," << text(p.expected_tm01) << ","
        << text(p.expected_tm02);
    json entry = {{"point", p.point}, {"runs", p.runs},
                  {"expected", {{"hs", json_number(p.expected_hs)}, {"tm01", json_number(p.expected_tm01)},
                                {"tm02", json_number(p.expected_tm02)}}}};
    for (std::size_t v = 0; v < spec.variations.size(); ++v) entry["parameters"][spec.variations[v].name] = labels[v];
    for (const auto& name : summarized) {
      const Summary& s = p.statistics.at(name);
      csv << "," << text(s.mean) << "," << text(s.sd) << "," << text(s.low) << "," << text(s.high);
      entry["statistics"][name] = {{"mean", json_number(s.mean)}, {"sd", json_number(s.sd)},
                                   {"ci95_of_mean", {json_number(s.low), json_number(s.high)}}, {"n", s.n}};
    }
    if (spec.fit) {
      for (const auto& name : kFitNames) {
        csv << "," << text(p.truth.at(name)) << "," << text(p.bias.at(name)) << ","
            << text(p.coverage.at(name)) << "," << p.calibrated.at(name);
        entry["fit"][name] = {{"truth", json_number(p.truth.at(name))}, {"bias", json_number(p.bias.at(name))},
                              {"coverage", json_number(p.coverage.at(name))},
                              {"calibrated_intervals", p.calibrated.at(name)}};
      }
      csv << "," << p.converged;
      entry["fit"]["converged"] = p.converged;
    }
    csv << "\n";
    points_json.push_back(entry);
  }
  std::ofstream(dir / "points.json") << json{{"sweep", spec.to_json()}, {"points", points_json}}.dump(1) << "\n";
}

// One figure: statistic `name` against numeric variation v, one series per combination of the
// other keys' values, with the 95 % interval of the mean as a band, and the value it should
// scatter about where there is one.
reports::Figure statistic_figure(const SweepSpec& spec, const std::vector<PointSummary>& points,
                                 std::size_t v, const std::string& name) {
  const Variation& variation = spec.variations[v];
  std::map<std::string, reports::Series> series;
  reports::Series truth{name.rfind("fit_", 0) == 0 ? "truth (the point's case)"
                                                   : "the spectrum on the grid (band-limited)",
                        {}, true, {}};
  for (const auto& p : points) {
    const auto labels = labels_of(spec, p.point);
    std::string others;
    for (std::size_t w = 0; w < labels.size(); ++w) {
      if (w != v) others += (others.empty() ? "" : ", ") + spec.variations[w].name + " = " + labels[w];
    }
    const double x = variation.numbers[value_indices(spec, p.point)[v]];
    const Summary& s = p.statistics.at(name);
    if (!std::isfinite(s.mean)) continue;
    auto& line = series[others];
    line.title = others.empty() ? "mean over seeds (band: 95 % interval of the mean)" : others;
    line.points.emplace_back(x, s.mean);
    line.band.push_back({std::isfinite(s.low) ? s.low : s.mean, std::isfinite(s.high) ? s.high : s.mean});
    if (others.empty()) {
      // The value the statistic should scatter about: the fit's truth, or the spectrum's
      // band-limited value on the grid.
      if (name.rfind("fit_", 0) == 0) truth.points.emplace_back(x, p.truth.at(name.substr(4)));
      if (name == "hs") truth.points.emplace_back(x, p.expected_hs);
      if (name == "tm01") truth.points.emplace_back(x, p.expected_tm01);
      if (name == "tm02") truth.points.emplace_back(x, p.expected_tm02);
    }
  }
  reports::Figure figure;
  figure.stem = name + "_vs_" + variation.key;
  figure.title = fmt::format("{} against {} ({} seeds per point)", name, variation.name, spec.seeds);
  figure.xlabel = variation.name;
  figure.ylabel = name;
  figure.log_x = figure.log_y = false;
  figure.written_by = "swell sweep";
  figure.key = "inside top left box opaque";
  for (auto& entry : series) {
    // A named reference, not a structured binding: lambdas may not capture bindings before C++20
    // (clang refuses it in the sanitizer build).
    const auto& line = entry.second;
    // Sorted by x, bands kept beside their points.
    std::vector<std::size_t> order(line.points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return line.points[a].first < line.points[b].first; });
    reports::Series sorted{line.title, {}, false, {}};
    for (auto i : order) {
      sorted.points.push_back(line.points[i]);
      sorted.band.push_back(line.band[i]);
    }
    figure.series.push_back(std::move(sorted));
  }
  if (!truth.points.empty()) {
    std::sort(truth.points.begin(), truth.points.end());
    figure.series.push_back(truth);
  }
  return figure;
}

// plots/: each statistic against each numeric varied key; the notes say what was not rendered.
std::vector<std::string> write_plots(const SweepSpec& spec, const std::vector<PointSummary>& points,
                                     const fs::path& dir, const std::string& gnuplot) {
  std::vector<std::string> notes;
  const bool render = reports::program_found(gnuplot);
  if (!render) {
    notes.push_back(gnuplot.empty()
                        ? std::string("no gnuplot given: the plots' .dat and .gp are written to plots/, their PNGs are not")
                        : fmt::format("gnuplot ('{}') was not found: the plots' .dat and .gp are written "
                                      "to plots/, their PNGs are not (install gnuplot-nox)", gnuplot));
  }
  const fs::path plots = dir / "plots";
  fs::create_directories(plots);
  for (std::size_t v = 0; v < spec.variations.size(); ++v) {
    if (!spec.variations[v].numeric()) continue;
    for (const auto& name : summarized_names(spec)) {
      reports::write_figure(statistic_figure(spec, points, v, name), plots, gnuplot, render, notes);
    }
  }
  return notes;
}

}  // namespace

std::vector<std::string> write_outputs(const SweepSpec& spec, std::vector<RunRow> rows,
                                       const fs::path& dir, const std::string& gnuplot) {
  std::sort(rows.begin(), rows.end(), [](const RunRow& a, const RunRow& b) {
    return std::tie(a.point, a.replicate) < std::tie(b.point, b.replicate);
  });
  fs::create_directories(dir);
  write_runs(spec, rows, dir);
  const std::vector<PointSummary> points = summarize_points(spec, rows);
  write_points(spec, points, dir);
  return write_plots(spec, points, dir, gnuplot);
}

}  // namespace swell::validation::sweep
