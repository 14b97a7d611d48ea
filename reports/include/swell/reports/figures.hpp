#pragma once
// gnuplot figures as swell writes them: <stem>.dat (one block per series) and <stem>.gp beside
// the rendered <stem>.png, so that a reader can restyle a figure without rerunning swell.
// Used by `swell report` (performance figures), `swell sweep` (statistics against the varied
// parameters) and `swell fit --spectrum` (buoy fits over time).
#include <array>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace swell::reports {

struct Series {
  std::string title;
  std::vector<std::pair<double, double>> points;  // sorted by x
  bool dashed = false;
  // Optional, one [low, high] per point: drawn as a shaded band behind the series (an interval
  // over seeds, a confidence interval).
  std::vector<std::array<double, 2>> band;
};

struct Figure {
  std::string stem, title, xlabel, ylabel, description;
  bool log_x = true, log_y = true;
  bool points_only = false;
  std::vector<Series> series;
  // Where "" is written by the .gp's header comment ("swell report", "swell sweep", …).
  std::string written_by = "swell report";
  std::string key = "outside right top";  // gnuplot's `set key` position
};

// Whether `program` (a name looked up in PATH, or a path) can be executed.
bool program_found(const std::string& program);

// Runs gnuplot on `script` in `dir`; returns "" on success or what went wrong.
std::string run_gnuplot(const std::string& program, const std::filesystem::path& dir,
                        const std::string& script);

// Writes <stem>.dat and <stem>.gp into dir; renders <stem>.png when `render` (problems collects
// what went wrong). Returns the figure's entry for a report's JSON: png, data, script, title,
// description, rendered.
nlohmann::json write_figure(const Figure& figure, const std::filesystem::path& dir,
                            const std::string& gnuplot, bool render,
                            std::vector<std::string>& problems);

}  // namespace swell::reports
