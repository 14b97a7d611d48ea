#pragma once
// Each frame's height transform at the resolved wave vectors, as the first pass over the frames
// saw it, kept in an unlinked temporary file for the dispersion pass: reading 16 bytes per wave
// vector back costs a fraction of reading and transforming the frame again (an EXR frame is
// inflated whole whichever channels are wanted). The file lives on disk, not in the process's
// memory (the page cache holds it while memory is free), and vanishes with the process. Where
// it cannot be made or written (no room in the temporary directory), the dispersion pass reads
// the frames again instead.
#include <complex>
#include <cstddef>
#include <span>

namespace swell::validation::ocean_analysis {

class SeriesSpill {
 public:
  // Room for `values` complex values per frame, in std::filesystem::temp_directory_path()
  // (TMPDIR). ok() says whether the file was made.
  explicit SeriesSpill(std::size_t values);
  ~SeriesSpill();
  SeriesSpill(const SeriesSpill&) = delete;
  SeriesSpill& operator=(const SeriesSpill&) = delete;

  bool ok() const { return fd_ >= 0; }
  // Frame f's values from the `first`th on (a piece of the frame's); a failed write closes the
  // file (ok() is then false).
  void write(std::size_t f, std::size_t first, std::span<const std::complex<double>> values);
  // Frame f's values as written; false when the file cannot give them back.
  bool read(std::size_t f, std::span<std::complex<double>> values) const;

 private:
  void close();
  std::size_t values_ = 0;
  int fd_ = -1;
};

}  // namespace swell::validation::ocean_analysis
