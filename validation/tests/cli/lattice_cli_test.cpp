// The command line of rank-1 lattices: `swell lattice` (its JSON against the library
// and the contract's keys), `swell synth --impl lattice` (N-vectors, points.npy, mesh.ply and a
// case.toml with [sampling] that `swell gate` and `swell fit` read back), and bad input: exit 2
// with a message naming what was wrong.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"
#include "swell/reference/lattice.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_io.hpp"
#include "swell/validation/io/npy.hpp"

namespace {

namespace fs = std::filesystem;
using swell::test::swell;

class LatticeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("swell_lattice_cli_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

nlohmann::json read_json(const std::string& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

TEST_F(LatticeCli, LatticeJsonHoldsTheContractsKeysAndTheLibrarysValues) {
  const auto run = swell("lattice --points 4096 --length 200,100 --json " + path("l.json"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto doc = read_json(path("l.json"));
  const auto lattice = swell::reference::korobov_lattice(4096, {200, 100});
  EXPECT_EQ(doc.at("points"), 4096);
  EXPECT_EQ(doc.at("kind"), "korobov");
  EXPECT_EQ(doc.at("dim"), 2);
  EXPECT_EQ(doc.at("generator").get<std::vector<std::int64_t>>(), lattice.generator());
  const auto merits = swell::reference::lattice_merits(lattice);
  EXPECT_EQ(doc.at("merits").at("shortest_dual_vector").get<std::vector<std::int64_t>>(),
            merits.shortest_dual_vector);
  EXPECT_DOUBLE_EQ(doc.at("merits").at("lambda1").get<double>(), merits.lambda1);
  EXPECT_DOUBLE_EQ(doc.at("merits").at("zaremba_rho").get<double>(), merits.zaremba_rho);
  EXPECT_DOUBLE_EQ(doc.at("merits").at("p2").get<double>(), merits.p2);
  const auto band = swell::reference::lattice_band(lattice);
  EXPECT_DOUBLE_EQ(doc.at("band").at("inscribed_radius").get<double>(), band.inscribed_radius);
  EXPECT_DOUBLE_EQ(doc.at("band").at("covering_radius").get<double>(), band.covering_radius);
  EXPECT_DOUBLE_EQ(doc.at("band").at("alias_free_fraction").get<double>(), band.alias_free_fraction);
  ASSERT_EQ(doc.at("wave_vectors").size(), 4096u);
  for (std::int64_t m = 0; m < 4096; m += 97) {
    const auto k = lattice.wave_vector(m);
    EXPECT_EQ(doc.at("wave_vectors").at(m).get<std::vector<int>>(), std::vector<int>(k.begin(), k.end()));
  }
  // The text names the generator and the band.
  const auto text = swell("lattice --points 233 --kind fibonacci --length 200");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("fibonacci N=233 g=(1,144)"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("alias-free fraction"), std::string::npos);
  const auto three = swell("lattice --points 4096 --dim 3 --json -");
  ASSERT_EQ(three.exit_code, 0) << three.output;
  EXPECT_EQ(nlohmann::json::parse(three.output).at("generator").size(), 3u);
}

TEST_F(LatticeCli, BadLatticeInputExitsTwoNamingIt) {
  struct Bad {
    std::string arguments, naming;
  };
  for (const Bad& bad : std::vector<Bad>{
           {"lattice --points 20 --kind fibonacci", "Fibonacci"},
           {"lattice --points 21 --kind fibonacci --dim 3", "2-D"},
           {"lattice --points 1", "points"},
           {"lattice --points 64 --length 0", "--length"},
           {"lattice --points 64 --dim 3 --length 1,2", "--length"},
           {"synth --model jonswap --hs 3 --tp 8 --length 200 --impl fftw --points 64 --out " + path("a"), "--points"},
           {"synth --model jonswap --hs 3 --tp 8 --length 200 --impl lattice --n 64 --out " + path("b"), "--points"},
           {"synth --model jonswap --hs 3 --tp 8 --length 200 --impl lattice --points 4096 --format exr --out " + path("c"), "npy"},
           {"synth --model jonswap --hs 3 --tp 8 --length 200 --impl lattice:fft=nope --points 4096 --out " + path("d"), "nope"},
           {"synth --model jonswap --hs 3 --tp 8 --length 200 --impl lattice:threads=2 --points 4096 --out " + path("e"), "fft=NAME"},
           {"synth --model jonswap --hs 3 --tp 8 --length 200 --impl lattice:fft=radix2 --points 3000 --out " + path("f"), "radix2"},
           {"synth --model jonswap --hs 3 --tp 8 --length 200 --impl lattice --points 4096 --kind fibonacci --out " + path("g"), "Fibonacci"},
           {"synth --model jonswap --hs 3 --tp 8 --length 200 --impl lattice --out " + path("h"), "--points"},
           {"check ocean --impl lattice:fft=nope", "nope"},
       }) {
    const auto run = swell(bad.arguments);
    EXPECT_EQ(run.exit_code, 2) << bad.arguments << "\n" << run.output;
    EXPECT_NE(run.output.find(bad.naming), std::string::npos)
        << bad.arguments << ": '" << bad.naming << "' not in " << run.output;
  }
}

TEST_F(LatticeCli, SynthWritesLatticeFramesThatGateAndFitReadBack) {
  const std::string out = path("lattice");
  const auto made = swell("synth --model jonswap --hs 3 --tp 8 --gamma 3.3 --length 800 --impl "
                          "lattice:fft=radix2 --points 16384 --frames 4 --dt 0.5 --seed 11 "
                          "--precision fp64 --json " + path("synth.json") + " --out " + out);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const auto doc = read_json(path("synth.json"));
  EXPECT_NE(doc.at("sampling").get<std::string>().find("korobov N=16384"), std::string::npos);
  // The case file's [sampling] section, read back as the same lattice.
  const auto case_file = swell::validation::read_case_file(fs::path(out) / "case.toml");
  ASSERT_TRUE(case_file.ocean.is_lattice());
  const auto lattice = swell::reference::korobov_lattice(16384, {800, 800});
  EXPECT_EQ(case_file.ocean.lattice->generator(), lattice.generator());
  std::ifstream toml(fs::path(out) / "case.toml");
  const std::string text((std::istreambuf_iterator<char>(toml)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("[sampling]\nkind = \"lattice\"\npoints = 16384"), std::string::npos) << text;
  // points.npy: N × 2 metres, the lattice's points; frames: N-vectors, float64.
  const auto points = swell::validation::read_npy(fs::path(out) / "points.npy");
  ASSERT_EQ(points.shape, (std::vector<std::size_t>{16384, 2}));
  const auto xy = points.values<double>();
  for (std::int64_t n : {0, 1, 777, 16383}) {
    const auto x = lattice.point(n);
    EXPECT_DOUBLE_EQ(xy[2 * n], x[0]);
    EXPECT_DOUBLE_EQ(xy[2 * n + 1], x[1]);
  }
  const auto height = swell::validation::read_npy(fs::path(out) / "frame_0003_h.npy");
  EXPECT_EQ(height.shape, (std::vector<std::size_t>{16384}));
  EXPECT_EQ(height.dtype, swell::validation::NpyArray::Dtype::f8);
  EXPECT_GT(fs::file_size(fs::path(out) / "mesh.ply"), 16384u * 12u);
  const auto frames = swell::validation::read_frames(case_file);
  EXPECT_EQ(frames.frames.size(), 4u);
  // The gate passes the right surface; the fit's intervals cover the truth.
  const auto gate = swell("gate --case " + (fs::path(out) / "case.toml").string());
  EXPECT_EQ(gate.exit_code, 0) << gate.output;
  const auto fit = swell("fit --case " + (fs::path(out) / "case.toml").string() + " --input " + out +
                         " --json " + path("fit.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.output;
  const auto fitted = read_json(path("fit.json"));
  EXPECT_NE(fitted.dump().find("\"hs\""), std::string::npos);
  // A damaged frame (a grid-shaped array) is refused by name.
  swell::validation::write_npy(fs::path(out) / "frame_0001_h.npy",
                               swell::validation::NpyArray::from_values(
                                   {128, 128}, std::span<const double>(height.values<double>())));
  const auto refused = swell("gate --case " + (fs::path(out) / "case.toml").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("[sampling] points = 16384"), std::string::npos) << refused.output;
}

TEST_F(LatticeCli, CaseFileSamplingSectionRefusesWhatIsWrong) {
  const std::string rest =
      "[time]\nframes = 1\n[spectrum]\nmodel = \"jonswap\"\nhs = 3.0\ntp = 8.0\n"
      "[spreading]\nmodel = \"cos2s\"\ns = 10.0\n";
  struct Bad {
    std::string head, naming;
  };
  for (const Bad& bad : std::vector<Bad>{
           {"[grid]\nlength = [200.0, 200.0]\n[sampling]\nkind = \"lattice\"\npoints = 4096\n", "generator"},
           {"[grid]\nlength = [200.0, 200.0]\n[sampling]\nkind = \"lattice\"\ngenerator = [1, 671]\n", "points"},
           {"[grid]\nn = [64, 64]\nlength = [200.0, 200.0]\n[sampling]\nkind = \"lattice\"\npoints = 4096\ngenerator = [1, 671]\n", "[grid] n"},
           {"[grid]\nlength = [200.0, 200.0]\n[sampling]\nkind = \"lattice\"\npoints = 4096\ngenerator = [2, 4]\n", "gcd"},
           {"[grid]\nlength = [200.0, 200.0]\n[sampling]\nkind = \"hexagonal\"\n", "kind"},
           {"[grid]\nn = [64, 64]\nlength = [200.0, 200.0]\n[sampling]\npoints = 4096\n", "points"},
       }) {
    const auto file = path("bad.toml");
    std::ofstream(file) << bad.head << rest;
    try {
      (void)swell::validation::read_case_file(file);
      ADD_FAILURE() << "accepted:\n" << bad.head;
    } catch (const swell::InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(bad.naming), std::string::npos)
          << "'" << bad.naming << "' not in " << e.what();
    }
  }
}

}  // namespace
