// swell sweep --case FILE --vary NAME=a:b:n | NAME=v1,v2,… [--vary …] --seeds S [--fit]
//             [--seed N] [--impl NAME] [--precision fp32|fp64] [--out DIR] [--threads T]
//             [--shard i/n] [--resume] [--progress auto|bar|plain|none] [--json FILE|-]
// swell sweep --merge DIR1 DIR2 … --out DIR
//
// Tuning experiments (docs/sweeps.md): every point of the product of the varied case keys ×
// S seeds is synthesized and measured (validation/sweep.hpp). Under `mpirun -np K` the points
// go round-robin to the ranks and rank 0 gathers the rows, keeps the journal and prints the
// progress; --shard i/n runs the points p with p mod n = i without MPI (job arrays), and --merge
// joins the shards' folders. Every finished run is appended at once to DIR/rows.jsonl, so an
// interruption (Ctrl-C) loses only the runs in progress and --resume continues.
//
// Exit 0 when every run finished, 1 when some run failed (the others are kept), 2 for bad input
// (before any work starts), 130 when interrupted.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <set>
#include <thread>

#include "commands.hpp"
#include "mpi_world.hpp"
#include "progress.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/sweep/sweep.hpp"

namespace swell::cli {
namespace {

namespace fs = std::filesystem;
namespace sweep = validation::sweep;
using nlohmann::json;

struct SweepOptions {
  std::string case_file;
  std::vector<std::string> vary;
  int seeds = 0;
  std::string seed;  // the sweep's seed; default: the case's [synthesis] seed
  bool fit = false;
  std::string impl = "radix2";
  std::string precision = "fp64";
  std::string out = "sweep";
  int threads = 0;  // 0: the cores over the ranks
  std::string shard;
  bool resume = false;
  std::vector<std::string> merge;
  std::string progress = "auto";
  std::string json;
  std::string gnuplot = "gnuplot";
};

std::atomic<bool> g_stop{false};
extern "C" void request_stop(int) { g_stop = true; }

struct Shard {
  int index = 0, count = 1;
  bool given = false;
  std::string text() const { return given ? fmt::format("{}/{}", index, count) : ""; }
};

Shard parse_shard(const std::string& text) {
  Shard shard;
  if (text.empty()) return shard;
  const auto slash = text.find('/');
  try {
    std::size_t used_i = 0, used_n = 0;
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    shard.index = std::stoi(text.substr(0, slash), &used_i);
    shard.count = std::stoi(text.substr(slash + 1), &used_n);
    if (used_i != slash || used_n != text.size() - slash - 1) throw std::invalid_argument("junk");
  } catch (const std::exception&) {
    throw InvalidInput(fmt::format("--shard {}: expected i/n, such as 0/4 (shard i of n, i from 0)", text));
  }
  if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count) {
    throw InvalidInput(fmt::format("--shard {}: needs n ≥ 1 and 0 ≤ i < n", text));
  }
  shard.given = true;
  return shard;
}

std::string read_text(const fs::path& path, const std::string& what) {
  std::ifstream file(path);
  if (!file) throw InvalidInput(fmt::format("{} {}: cannot be read", what, path.string()));
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

std::uint64_t parse_seed(const std::string& text) {
  std::size_t used = 0;
  try {
    if (!text.empty() && text[0] != '-') {
      const unsigned long long seed = std::stoull(text, &used);
      if (used == text.size()) return seed;
    }
  } catch (const std::exception&) {
  }
  throw InvalidInput(fmt::format("--seed {}: must be an integer in 0…2⁶⁴−1", text));
}

json sweep_file(const sweep::SweepSpec& spec, const Shard& shard) {
  json document = spec.to_json();
  document["shard"] = shard.given ? json(shard.text()) : json(nullptr);
  return document;
}

// The rows a journal holds. A last line cut short by an interruption is dropped (its run is
// done again); any other unreadable line is an error.
std::vector<sweep::RunRow> read_journal(const fs::path& path) {
  std::vector<sweep::RunRow> rows;
  std::ifstream file(path);
  if (!file) return rows;
  std::vector<std::string> lines;
  for (std::string line; std::getline(file, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  for (std::size_t i = 0; i < lines.size(); ++i) {
    try {
      rows.push_back(sweep::row_from_json(json::parse(lines[i])));
    } catch (const std::exception& e) {
      if (i + 1 == lines.size()) break;
      throw InvalidInput(fmt::format("{} line {}: {}", path.string(), i + 1, e.what()));
    }
  }
  return rows;
}

std::uint64_t run_key(std::size_t point, int replicate, int seeds) {
  return std::uint64_t(point) * std::uint64_t(seeds) + std::uint64_t(replicate);
}

bool in_shard(std::size_t point, const Shard& shard) {
  return !shard.given || point % std::size_t(shard.count) == std::size_t(shard.index);
}

// The difference between two sweep descriptions, for a refusal: the first differing key, in the
// order a user sets them (the counts derived from them last).
std::string first_difference(const json& a, const json& b) {
  std::vector<std::string> keys = {"case_file", "case", "variations", "seeds", "sweep_seed", "fit",
                                   "impl", "precision", "shard"};
  for (const auto& [key, value] : a.items()) {
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  for (const auto& [key, value] : b.items()) {
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  }
  for (const auto& key : keys) {
    if (a.contains(key) != b.contains(key)) return fmt::format("'{}' only in one", key);
    if (a.contains(key) && a[key] != b[key]) {
      const std::string shown = key == "case" ? "the case file's text" : fmt::format("{} ≠ {}", a[key].dump(), b[key].dump());
      return fmt::format("{} differs ({})", key, shown);
    }
  }
  return "";
}

void print_summary(const sweep::SweepSpec& spec, const fs::path& out) {
  const json points = json::parse(std::ifstream(out / "points.json")).at("points");
  std::string header;
  for (const auto& v : spec.variations) header += fmt::format("{:>10} ", v.name);
  header += fmt::format("{:>8} {:>8} {:>8} {:>8} {:>9} {:>9}", "Hs m", "Tp s", "Tm01 s", "Tm02 s",
                        "kurt", "foam");
  if (spec.fit) header += fmt::format(" {:>9} {:>9} {:>9}", "fit γ", "bias γ", "cover γ");
  std::cout << header << "\n";
  auto mean = [](const json& p, const char* name) {
    const auto& m = p["statistics"][name]["mean"];
    return m.is_number() ? m.get<double>() : NAN;
  };
  for (const auto& p : points) {
    std::string line;
    for (const auto& v : spec.variations) line += fmt::format("{:>10} ", p["parameters"][v.name].get<std::string>());
    line += fmt::format("{:>8.4g} {:>8.4g} {:>8.4g} {:>8.4g} {:>9.3g} {:>9.3g}", mean(p, "hs"),
                        mean(p, "tp"), mean(p, "tm01"), mean(p, "tm02"), mean(p, "excess_kurtosis"),
                        mean(p, "foam_fraction"));
    if (spec.fit) {
      const auto& g = p["fit"]["gamma"];
      line += fmt::format(" {:>9.4g} {:>9.3g} {:>9.3g}", mean(p, "fit_gamma"),
                          g["bias"].is_number() ? g["bias"].get<double>() : NAN,
                          g["coverage"].is_number() ? g["coverage"].get<double>() : NAN);
    }
    std::cout << line << "\n";
  }
}

int finish_outputs(const sweep::SweepSpec& spec, const std::vector<sweep::RunRow>& rows,
                   const fs::path& out, const SweepOptions& o, bool complete, int failures) {
  const auto notes = sweep::write_outputs(spec, rows, out, o.gnuplot);
  for (const auto& note : notes) std::cerr << "swell sweep: note: " << note << "\n";
  // With --json - standard output is the JSON document alone.
  if (o.json != "-") print_summary(spec, out);
  if (o.json != "-") std::cout << fmt::format("{} runs of {} points × {} seeds in {}: runs.csv, runs.json, points.csv, "
                           "points.json, plots/\n",
                           rows.size(), spec.point_count(), spec.seeds, out.string());
  if (!o.json.empty()) {
    write_json(o.json, {{"out", out.string()}, {"points", spec.point_count()}, {"runs", rows.size()},
                        {"complete", complete}, {"failed_runs", failures}, {"notes", notes}});
  }
  return failures > 0 ? 1 : 0;
}

int merge_shards(const SweepOptions& o) {
  if (!o.case_file.empty() || !o.vary.empty() || o.seeds != 0 || !o.shard.empty() || o.resume) {
    throw InvalidInput("--merge joins finished shard folders: give only the folders and --out "
                       "(the sweep itself is in each folder's sweep.json)");
  }
  std::optional<json> reference;
  sweep::SweepSpec spec;
  std::map<int, std::string> shards;
  int shard_count = 0;
  std::map<std::uint64_t, sweep::RunRow> rows;
  for (const auto& dir : o.merge) {
    const fs::path file = fs::path(dir) / "sweep.json";
    json document;
    try {
      document = json::parse(read_text(file, "--merge"));
    } catch (const json::exception& e) {
      throw InvalidInput(fmt::format("--merge {}: not JSON: {}", file.string(), e.what()));
    }
    const json shard_value = document.value("shard", json(nullptr));
    document.erase("shard");
    if (!reference) {
      reference = document;
      spec = sweep::SweepSpec::from_json(document);
    } else if (document != *reference) {
      throw InvalidInput(fmt::format("--merge {}: a different sweep from {}: {}", dir, o.merge[0],
                                     first_difference(*reference, document)));
    }
    const Shard shard = shard_value.is_string() ? parse_shard(shard_value.get<std::string>()) : Shard{};
    if (!shard.given) throw InvalidInput(fmt::format("--merge {}: not a shard (its sweep.json has no shard)", dir));
    if (shard_count != 0 && shard.count != shard_count) {
      throw InvalidInput(fmt::format("--merge {}: shard {} of a split into {}, others of {}", dir,
                                     shard.text(), shard.count, shard_count));
    }
    shard_count = shard.count;
    if (shards.count(shard.index)) {
      throw InvalidInput(fmt::format("--merge: shard {} given twice ({} and {})", shard.text(),
                                     shards[shard.index], dir));
    }
    shards[shard.index] = dir;
    for (auto& row : read_journal(fs::path(dir) / "rows.jsonl")) {
      if (!in_shard(row.point, shard)) {
        throw InvalidInput(fmt::format("--merge {}: a row of point {}, which is not in shard {}", dir,
                                       row.point, shard.text()));
      }
      rows[run_key(row.point, row.replicate, spec.seeds)] = row;
    }
  }
  std::vector<std::string> missing_shards;
  for (int i = 0; i < shard_count; ++i) {
    if (!shards.count(i)) missing_shards.push_back(fmt::format("{}/{}", i, shard_count));
  }
  if (!missing_shards.empty()) {
    throw InvalidInput(fmt::format("--merge: shard(s) {} missing", fmt::join(missing_shards, ", ")));
  }
  if (rows.size() != spec.run_count()) {
    std::map<int, int> missing;
    for (std::size_t p = 0; p < spec.point_count(); ++p) {
      for (int r = 0; r < spec.seeds; ++r) {
        if (!rows.count(run_key(p, r, spec.seeds))) ++missing[int(p % std::size_t(shard_count))];
      }
    }
    std::string which;
    for (const auto& [i, n] : missing) which += fmt::format("{}{} in {}", which.empty() ? "" : ", ", n, shards[i]);
    throw InvalidInput(fmt::format("--merge: {} of {} runs are missing ({}); finish those shards "
                                   "with --resume", spec.run_count() - rows.size(), spec.run_count(), which));
  }
  const fs::path out = o.out;
  fs::create_directories(out);
  std::ofstream(out / "sweep.json") << sweep_file(spec, Shard{}).dump(1) << "\n";
  std::vector<sweep::RunRow> all;
  std::ofstream journal(out / "rows.jsonl");
  for (const auto& [key, row] : rows) {
    journal << sweep::row_json(spec, row).dump() << "\n";
    all.push_back(row);
  }
  journal.close();
  std::cerr << fmt::format("swell sweep: merged {} shards, {} runs\n", shard_count, all.size());
  return finish_outputs(spec, all, out, o, true, 0);
}

// The rows finished by worker threads, waiting for the main thread (which alone calls MPI).
struct Outbox {
  std::mutex mutex;
  std::deque<std::pair<MpiWorld::Tag, std::string>> messages;
  void push(MpiWorld::Tag tag, std::string text) {
    const std::lock_guard lock(mutex);
    messages.emplace_back(tag, std::move(text));
  }
  bool pop(std::pair<MpiWorld::Tag, std::string>& message) {
    const std::lock_guard lock(mutex);
    if (messages.empty()) return false;
    message = std::move(messages.front());
    messages.pop_front();
    return true;
  }
};

int run_sweep(const SweepOptions& o) {
  MpiWorld world;
  sweep::SweepSpec spec;
  Shard shard;
  fs::path out = o.out;
  std::vector<sweep::RunRow> done_rows;
  // Every rank checks the sweep itself (the same inputs give the same refusal everywhere); rank
  // 0 alone checks the output folder and tells the others.
  try {
    if (o.case_file.empty()) throw InvalidInput("--case FILE is required (or --merge DIR …)");
    if (o.seeds < 1) throw InvalidInput(fmt::format("--seeds must be ≥ 1 (got {})", o.seeds));
    shard = parse_shard(o.shard);
    spec.case_path = o.case_file;
    spec.case_text = read_text(o.case_file, "--case");
    const validation::CaseFile base = validation::parse_case_toml(spec.case_text, spec.case_path);
    for (const auto& v : o.vary) spec.variations.push_back(sweep::parse_variation(v, spec.case_text, spec.case_path));
    spec.seeds = o.seeds;
    spec.sweep_seed = o.seed.empty() ? base.ocean.seed : parse_seed(o.seed);
    spec.fit = o.fit;
    spec.impl = o.impl;
    spec.precision = impls::precision_from_string(o.precision);
    sweep::validate(spec);
  } catch (const InvalidInput&) {
    if (world.root()) throw;
    return 2;
  }

  std::string verdict;  // rank 0's: "" to go on, else the refusal
  if (world.root()) {
    try {
      const json wanted = sweep_file(spec, shard);
      const fs::path file = out / "sweep.json";
      std::error_code error;
      if (fs::exists(file, error)) {
        if (!o.resume) {
          throw InvalidInput(fmt::format("--out {} holds a sweep already (sweep.json): --resume "
                                         "continues it, or choose another --out", out.string()));
        }
        json stored;
        try {
          stored = json::parse(read_text(file, "--resume"));
        } catch (const json::exception& e) {
          throw InvalidInput(fmt::format("--resume: {} is not JSON: {}", file.string(), e.what()));
        }
        if (stored != wanted) {
          throw InvalidInput(fmt::format("--resume: {} describes another sweep: {}", file.string(),
                                         first_difference(stored, wanted)));
        }
        done_rows = read_journal(out / "rows.jsonl");
      } else {
        if (o.resume) throw InvalidInput(fmt::format("--resume: {} holds no sweep (no sweep.json)", out.string()));
        fs::create_directories(out, error);
        std::ofstream f(file);
        f << wanted.dump(1) << "\n";
        if (!f) throw InvalidInput(fmt::format("--out {}: cannot write sweep.json there", out.string()));
        std::ofstream(out / "rows.jsonl", std::ios::trunc);
      }
    } catch (const InvalidInput& e) {
      verdict = e.what();
    }
  }
  world.broadcast(verdict);
  if (!verdict.empty()) {
    if (world.root()) throw InvalidInput(verdict);
    return 2;
  }
  std::string done_text;
  if (world.root()) {
    for (const auto& row : done_rows) done_text += std::to_string(run_key(row.point, row.replicate, spec.seeds)) + " ";
  }
  world.broadcast(done_text);
  std::set<std::uint64_t> done;
  {
    std::stringstream stream(done_text);
    for (std::uint64_t key; stream >> key;) done.insert(key);
  }

  // This rank's runs: the shard's points round-robin over the ranks, each point's seeds together.
  std::vector<std::pair<std::size_t, int>> mine;
  long shard_runs = 0;
  {
    std::size_t position = 0;
    for (std::size_t p = 0; p < spec.point_count(); ++p) {
      if (!in_shard(p, shard)) continue;
      shard_runs += spec.seeds;
      if (position++ % std::size_t(world.size()) != std::size_t(world.rank())) continue;
      for (int r = 0; r < spec.seeds; ++r) {
        if (!done.count(run_key(p, r, spec.seeds))) mine.emplace_back(p, r);
      }
    }
  }

  g_stop = false;
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
  const int threads = o.threads > 0 ? o.threads
                                    : std::max(1, int(std::thread::hardware_concurrency()) / world.size());
  Outbox outbox;
  std::atomic<std::size_t> next{0};
  std::atomic<int> running{threads};
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) {
    pool.emplace_back([&] {
      std::map<std::size_t, sweep::Point> points;  // built once per point
      for (std::size_t i; !g_stop && (i = next++) < mine.size();) {
        const auto [p, r] = mine[i];
        try {
          if (!points.count(p)) points.emplace(p, sweep::make_point(spec, p));
          const sweep::RunRow row = sweep::run(spec, points.at(p), r);
          outbox.push(MpiWorld::Tag::row, sweep::row_json(spec, row).dump());
        } catch (const std::exception& e) {
          outbox.push(MpiWorld::Tag::failure, fmt::format("point {} seed {}: {}", p, r, e.what()));
        }
      }
      --running;
    });
  }

  int failures = 0;
  if (world.root()) {
    Progress progress("swell sweep", o.progress, shard_runs, long(done.size()));
    std::ofstream journal(out / "rows.jsonl", std::ios::app);
    int finished_ranks = 1;  // this one, once its threads end
    bool local_done = false;
    auto handle = [&](MpiWorld::Tag tag, const std::string& text) {
      if (tag == MpiWorld::Tag::row) {
        journal << text << "\n" << std::flush;
        const json row = json::parse(text);
        std::string what = fmt::format("point {}", row["point"].get<std::size_t>());
        for (const auto& [name, value] : row["parameters"].items()) what += fmt::format(" {}={}", name, value.dump());
        progress.step(what + fmt::format(", seed {}", row["replicate"].get<int>()));
      } else if (tag == MpiWorld::Tag::failure) {
        ++failures;
        std::cerr << "\nswell sweep: run failed: " << text << "\n";
      } else {
        ++finished_ranks;
      }
    };
    while (true) {
      bool idle = true;
      std::pair<MpiWorld::Tag, std::string> message;
      while (outbox.pop(message)) {
        handle(message.first, message.second);
        idle = false;
      }
      MpiWorld::Tag tag;
      std::string text;
      int source = 0;
      while (world.receive(tag, text, source)) {
        handle(tag, text);
        idle = false;
      }
      if (!local_done && running == 0 && idle) local_done = true;
      if (local_done && finished_ranks == world.size()) {
        while (outbox.pop(message)) handle(message.first, message.second);
        break;
      }
      if (idle) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    progress.finish();
  } else {
    while (true) {
      std::pair<MpiWorld::Tag, std::string> message;
      bool idle = true;
      while (outbox.pop(message)) {
        world.send_to_root(message.first, message.second);
        idle = false;
      }
      if (running == 0 && idle) {
        while (outbox.pop(message)) world.send_to_root(message.first, message.second);
        world.send_to_root(MpiWorld::Tag::finished, "");
        break;
      }
      if (idle) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  for (auto& thread : pool) thread.join();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (!world.root()) return 0;

  const auto rows = read_journal(out / "rows.jsonl");
  // A signal after the last run changes nothing: the sweep is complete.
  if (g_stop && long(rows.size()) < shard_runs) {
    std::cerr << fmt::format("swell sweep: interrupted: {} of {} runs are on disk in {}; run the "
                             "same command with --resume to continue\n",
                             rows.size(), shard_runs, (out / "rows.jsonl").string());
    return 130;
  }
  if (failures > 0) {
    std::cerr << fmt::format("swell sweep: {} run(s) failed; the {} finished are kept (--resume "
                             "retries the failed ones)\n", failures, rows.size());
  }
  return finish_outputs(spec, rows, out, o, long(rows.size()) == shard_runs, failures);
}

}  // namespace

Action add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  app.add_option("--case", o->case_file, "the base case file (TOML; docs/case_files.md)");
  app.add_option("--vary", o->vary,
                 "NAME=a:b:n (n values from a to b) or NAME=v1,v2,…; NAME is a case key "
                 "(gamma, n, length, depth, choppiness, …) or SECTION.KEY; repeat for a product")
      ->allow_extra_args(false);
  app.add_option("--seeds", o->seeds, "replicates (independent seeds) per point");
  app.add_option("--seed", o->seed, "the sweep's seed, from which every run's seed derives "
                                    "(default: the case's [synthesis] seed)");
  app.add_flag("--fit", o->fit, "also fit JONSWAP (Hs, Tp, γ with 95 % intervals) to every run");
  app.add_option("--impl", o->impl, "transform backend of the synthesis (default radix2)");
  app.add_option("--precision", o->precision, "fp32 | fp64 (default fp64)")
      ->check(CLI::IsMember({"fp32", "fp64"}));
  app.add_option("--out", o->out, "output folder (default ./sweep)");
  app.add_option("--threads", o->threads, "worker threads per process (default: the cores over the ranks)")
      ->check(CLI::Range(1, 1024));
  app.add_option("--shard", o->shard, "i/n: run only the points p with p mod n = i (no MPI; join with --merge)");
  app.add_flag("--resume", o->resume, "continue the sweep in --out (its finished runs are kept)");
  app.add_option("--merge", o->merge, "join the shard folders given into --out");
  app.add_option("--progress", o->progress, "auto | bar | plain | none")
      ->check(CLI::IsMember({"auto", "bar", "plain", "none"}));
  app.add_option("--json", o->json, "a summary as JSON to FILE, or - for standard output");
  app.add_option("--gnuplot", o->gnuplot, "the gnuplot program for the plots (\"\": none)");
  return [o] { return o->merge.empty() ? run_sweep(*o) : merge_shards(*o); };
}

}  // namespace swell::cli
