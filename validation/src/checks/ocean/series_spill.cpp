// The first pass's series on disk for the dispersion pass (series_spill.hpp).
#include "checks/ocean/series_spill.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace swell::validation::ocean_analysis {

SeriesSpill::SeriesSpill(std::size_t values) : values_(values) {
  std::error_code error;
  const auto directory = std::filesystem::temp_directory_path(error);
  if (error) return;
  std::string path = (directory / "swell_series_XXXXXX").string();
  std::vector<char> name(path.begin(), path.end());
  name.push_back('\0');
  fd_ = ::mkstemp(name.data());
  if (fd_ >= 0) ::unlink(name.data());  // gone with the descriptor, whatever ends the process
}

SeriesSpill::~SeriesSpill() { close(); }

void SeriesSpill::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void SeriesSpill::write(std::size_t f, std::size_t first, std::span<const std::complex<double>> values) {
  if (fd_ < 0) return;
  if (first > values_ || values.size() > values_ - first) return close();
  const std::size_t bytes = values.size() * sizeof(std::complex<double>);
  const char* data = reinterpret_cast<const char*>(values.data());
  const off_t offset = off_t((f * values_ + first) * sizeof(std::complex<double>));
  for (std::size_t done = 0; done < bytes;) {
    const ssize_t n = ::pwrite(fd_, data + done, bytes - done, offset + off_t(done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return close();  // no room: the dispersion pass reads the frames again
    done += std::size_t(n);
  }
}

bool SeriesSpill::read(std::size_t f, std::span<std::complex<double>> values) const {
  if (fd_ < 0 || values.size() != values_) return false;
  const std::size_t bytes = values_ * sizeof(std::complex<double>);
  char* data = reinterpret_cast<char*>(values.data());
  const off_t offset = off_t(f * bytes);
  for (std::size_t done = 0; done < bytes;) {
    const ssize_t n = ::pread(fd_, data + done, bytes - done, offset + off_t(done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += std::size_t(n);
  }
  return true;
}

}  // namespace swell::validation::ocean_analysis
