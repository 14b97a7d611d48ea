#include "swell/reports/figures.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace swell::reports {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::string run_gnuplot(const std::string& program, const fs::path& dir, const std::string& script) {
  const std::string err_file = (dir / (script + ".log")).string();
  const pid_t child = fork();
  if (child < 0) return "fork failed";
  if (child == 0) {
    if (chdir(dir.c_str()) != 0) _exit(126);
    FILE* err = std::freopen(err_file.c_str(), "w", stderr);
    (void)err;
    execlp(program.c_str(), program.c_str(), script.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  waitpid(child, &status, 0);
  std::ifstream log(err_file);
  std::stringstream text;
  text << log.rdbuf();
  log.close();
  std::error_code ignored;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    fs::remove(err_file, ignored);
    return "";
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127) return program + " could not be started";
  return fmt::format("{} exited with status {}: {}", program, WIFEXITED(status) ? WEXITSTATUS(status) : -1,
                     text.str());
}

bool program_found(const std::string& program) {
  if (program.empty()) return false;
  if (program.find('/') != std::string::npos) return access(program.c_str(), X_OK) == 0;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string d; std::getline(dirs, d, ':');) {
    if (!d.empty() && access((fs::path(d) / program).c_str(), X_OK) == 0) return true;
  }
  return false;
}

json write_figure(const Figure& figure, const fs::path& dir, const std::string& gnuplot,
                  bool render, std::vector<std::string>& problems) {
  std::ofstream dat(dir / (figure.stem + ".dat"));
  dat << "# " << figure.title << "\n# x: " << figure.xlabel << "\n# y: " << figure.ylabel
      << "\n# one block per series (gnuplot's index), in the order of the .gp's plot command;"
         " columns x y, then band low and high where the series has one\n";
  std::ostringstream plot;
  int index = 0;
  for (const auto& series : figure.series) {
    if (series.points.empty()) continue;
    const bool banded = series.band.size() == series.points.size();
    dat << "\n\n# " << series.title << "\n";
    for (std::size_t i = 0; i < series.points.size(); ++i) {
      const auto& [x, y] = series.points[i];
      dat << fmt::format("{:.9g} {:.9g}", x, y);
      if (banded) dat << fmt::format(" {:.9g} {:.9g}", series.band[i][0], series.band[i][1]);
      dat << "\n";
    }
    const std::string source = quoted(figure.stem + ".dat") + " index " + std::to_string(index);
    if (banded) {
      plot << (plot.tellp() > 0 ? ", \\\n     " : "plot ") << source
           << " using 1:3:4 with filledcurves fc rgb '#cfe0f0' fs transparent solid 0.5 notitle";
    }
    plot << (plot.tellp() > 0 ? ", \\\n     " : "plot ") << source
         << (series.dashed ? " with lines dt 2 lw 1.5"
             : figure.points_only ? " with points pt 7"
                                  : " with linespoints pt 7 ps 0.6")
         << " title " << quoted(series.title);
    ++index;
  }
  dat.close();
  std::ofstream gp(dir / (figure.stem + ".gp"));
  gp << "# " << figure.title << " — written by `" << figure.written_by << "`; edit and run `gnuplot "
     << figure.stem << ".gp` here to restyle\n"
     << "set terminal pngcairo size 960,600 noenhanced font ',10'\n"
     << "set output " << quoted(figure.stem + ".png") << "\n"
     << "set title " << quoted(figure.title) << "\n"
     << "set xlabel " << quoted(figure.xlabel) << "\nset ylabel " << quoted(figure.ylabel) << "\n"
     << (figure.log_x ? "set logscale x 2\n" : "") << (figure.log_y ? "set logscale y\n" : "")
     << "set grid\nset key " << figure.key << "\n";
  if (index == 0) {
    gp << "set label 1 'no data' at graph 0.5, 0.5 center\nunset logscale\nplot [0:1][0:1] NaN notitle\n";
  } else {
    gp << plot.str() << "\n";
  }
  gp.close();
  json entry = {{"png", figure.stem + ".png"}, {"data", figure.stem + ".dat"},
                {"script", figure.stem + ".gp"}, {"title", figure.title},
                {"description", figure.description}, {"rendered", false}};
  if (render) {
    const std::string problem = run_gnuplot(gnuplot, dir, figure.stem + ".gp");
    if (problem.empty()) {
      entry["rendered"] = true;
    } else {
      problems.push_back(figure.stem + ".png: " + problem);
    }
  }
  return entry;
}

}  // namespace swell::reports
