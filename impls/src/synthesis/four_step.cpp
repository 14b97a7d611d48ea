#include "synthesis/four_step.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "swell/reference/errors.hpp"
#include "synthesis/kernels.hpp"

namespace swell::impls::synthesis {
namespace {

// From this many points on, a lattice frame's automatic transform is the four-step one where
// it can be, on a backend whose large 1-D plans are not blocked already (radix2; measured in
// docs/lattice.md §Measured: at 2^16 radix2's four-step won in fp32 in two runs, 2.40 against
// 3.53 ms and 2.13 against 4.24, and in fp64 lost once and won once, 3.94 against 3.37 ms and
// 4.35 against 4.99; from 2^18 on it wins 1.8–2.7× in both).
constexpr long kFourStepMinPoints = 1L << 17;
constexpr int kFourStepComplexPlanes = kComplexPairs;
// Values of p1 per unpack band: kFourStepBand consecutive complex values of a row (128 bytes
// in fp32) per read.
constexpr int kFourStepBand = 16;
// Step 1's columns per batch: radix2 transforms 16 fp32 (8 fp64) signals at once, one per
// vector lane; FFTW's batch of 16 columns of 2048 fp32 complex values is 256 KB, in L2.
constexpr int kFourStepBlock = 16;
constexpr int kFourStepPrefetchRows = 16;

}  // namespace

// The factorization N = n1·n2 with n2 the largest divisor of N at most √N that the backend
// plans as a batch of 1-D transforms, n1 = N/n2 likewise, and n2 ≥ the step-1 block (so
// that the columns are worth batching); none for N below kFourStepMinPoints unless asked for.
std::unique_ptr<FourStep> FourStep::make(LatticeTransform choice, const Backend& backend,
                                         const TransformSpec& frame, Packing packing) {
  const int nx = frame.nx;
  if (choice == LatticeTransform::one_pass) return nullptr;
  const auto refuse = [&](const std::string& why) -> std::unique_ptr<FourStep> {
    if (choice == LatticeTransform::four_step) {
      throw InvalidInput(fmt::format("lattice transform four_step on {} points with {}: {}", nx,
                                     backend.name(), why));
    }
    return nullptr;
  };
  if (choice == LatticeTransform::automatic &&
      (nx < kFourStepMinPoints || backend.capabilities().blocked_large_1d)) {
    return nullptr;
  }
  if (packing != Packing::complex_pairs || frame.placement != Placement::in_place) {
    return refuse("it needs complex pairs transformed in place");
  }
  if (backend.capabilities().device_resident) {
    return refuse("a device backend would copy every batch of columns through the host");
  }
  const auto plans = [&](int length, int howmany) {
    TransformSpec one = frame;
    one.nx = length;
    one.ny = 1;
    one.howmany = howmany;
    try {
      backend.validate(one);
      return true;
    } catch (const InvalidInput&) {
      return false;
    }
  };
  int n2 = 0;
  for (int d = static_cast<int>(std::sqrt(double(nx))) + 1; d >= 2; --d) {
    if (long(d) * d <= nx && nx % d == 0 && plans(d, kFourStepBlock) &&
        plans(nx / d, kFourStepComplexPlanes * (nx / d))) {
      n2 = d;
      break;
    }
  }
  if (n2 < kFourStepBlock) {
    return refuse(fmt::format("N has no factor pair n1·n2 with {} ≤ n2 ≤ √N that {} plans",
                              kFourStepBlock, backend.name()));
  }
  auto f = std::unique_ptr<FourStep>(new FourStep);
  f->points_ = nx;
  f->n2_ = n2;
  f->n1_ = nx / n2;
  TransformSpec columns = frame;
  columns.nx = f->n2_;
  columns.howmany = kFourStepBlock;
  f->columns_ = backend.plan(columns);
  TransformSpec rows = frame;
  rows.nx = f->n1_;
  rows.howmany = kFourStepComplexPlanes * f->n2_;
  f->rows_ = backend.plan(rows);
  while ((1L << (2 * f->shift_)) < long(nx)) ++f->shift_;
  const long low_size = 1L << f->shift_;
  const long high_size = (long(nx) + low_size - 1) / low_size;
  const long double two_pi_over_n = 2 * std::numbers::pi_v<long double> / nx;
  const auto fill = [&](auto& table) {
    using Complex = typename std::decay_t<decltype(table.low)>::value_type;
    using R = typename Complex::value_type;
    table.low.resize(low_size);
    table.high.resize(high_size);
    for (long e = 0; e < low_size; ++e) {
      table.low[e] = Complex(R(std::cos(two_pi_over_n * e)), R(std::sin(two_pi_over_n * e)));
    }
    for (long e = 0; e < high_size; ++e) {
      const long double angle = two_pi_over_n * (e * low_size);
      table.high[e] = Complex(R(std::cos(angle)), R(std::sin(angle)));
    }
  };
  if (frame.precision == Precision::f32) fill(f->twiddles32_); else fill(f->twiddles64_);
  return f;
}

template <typename Real>
void FourStep::transform(void* spectra, int threads) const {
  using Complex = std::complex<Real>;
  auto* data = static_cast<Complex*>(spectra);
  const auto& tw = twiddles<Real>();
  const long n = points_, mask = (1L << shift_) - 1;
  const int blocks_per_plane = (n1_ + kFourStepBlock - 1) / kFourStepBlock;
  const int tasks = kFourStepComplexPlanes * blocks_per_plane;
#pragma omp parallel num_threads(threads)
  {
    HostBuffer scratch(sizeof(Complex) * std::size_t(kFourStepBlock) * n2_);
    auto* buffer = static_cast<Complex*>(scratch.host_data());
#pragma omp for schedule(static)
    for (int task = 0; task < tasks; ++task) {
      Complex* plane = data + std::size_t(task / blocks_per_plane) * n;
      const int first = (task % blocks_per_plane) * kFourStepBlock;
      const int width = std::min(kFourStepBlock, n1_ - first);
      // Columns first … first + width − 1 of the n2 × n1 array, each to a contiguous signal
      // (a short last block leaves the rest of the scratch as it was: transformed, unused).
      for (int m2 = 0; m2 < n2_; ++m2) {
        const Complex* row = plane + std::size_t(m2) * n1_ + first;
        if (m2 + kFourStepPrefetchRows < n2_) {
          const Complex* ahead = row + std::size_t(kFourStepPrefetchRows) * n1_;
          __builtin_prefetch(ahead);
          __builtin_prefetch(ahead + width - 1);
        }
        for (int c = 0; c < width; ++c) buffer[std::size_t(c) * n2_ + m2] = row[c];
      }
      columns_->execute(static_cast<const void*>(buffer), static_cast<void*>(buffer));
      // The twiddles, multiplied out by hand: std::complex's operator* goes through
      // __mulsc3 (C's Annex G infinities) unless -ffast-math, several times slower.
      for (int c = 0; c < width; ++c) {
        Real* signal = reinterpret_cast<Real*>(buffer + std::size_t(c) * n2_);
        const long m1 = first + c;
        long e = 0;  // m1·p2 mod N
        for (int p2 = 0; p2 < n2_; ++p2) {
          const std::complex<Real> hi = tw.high[e >> shift_], lo = tw.low[e & mask];
          const Real wr = hi.real() * lo.real() - hi.imag() * lo.imag();
          const Real wi = hi.real() * lo.imag() + hi.imag() * lo.real();
          const Real xr = signal[2 * p2], xi = signal[2 * p2 + 1];
          signal[2 * p2] = xr * wr - xi * wi;
          signal[2 * p2 + 1] = xr * wi + xi * wr;
          e += m1;
          if (e >= n) e -= n;
        }
      }
      for (int p2 = 0; p2 < n2_; ++p2) {
        Complex* row = plane + std::size_t(p2) * n1_ + first;
        for (int c = 0; c < width; ++c) row[c] = buffer[std::size_t(c) * n2_ + p2];
      }
    }
  }
  rows_->execute(static_cast<const void*>(data), static_cast<void*>(data));
}

// Point n = n2·p1 + p2 lies at p2·n1 + p1 of each plane. Bands of kFourStepBand values of p1
// (that many runs of n2 consecutive points) are first transposed into a scratch in natural
// order, reading kFourStepBand consecutive values of each row, then unpacked as a whole
// frame's samples are.
template <typename Real>
Real FourStep::unpack(const void* spectra, std::byte* fields, const Real* inverse_scale,
                      int threads) const {
  using Complex = std::complex<Real>;
  const auto* data = static_cast<const Complex*>(spectra);
  const std::size_t n = std::size_t(points_);
  const int bands = (n1_ + kFourStepBand - 1) / kFourStepBand;
  Real probe = 0;
#pragma omp parallel num_threads(threads) reduction(+ : probe)
  {
    std::vector<Complex> scratch(std::size_t(kFourStepComplexPlanes) * kFourStepBand * n2_);
#pragma omp for schedule(static)
    for (int band = 0; band < bands; ++band) {
      const int first = band * kFourStepBand;
      const int height = std::min(kFourStepBand, n1_ - first);
      const std::size_t band_points = std::size_t(height) * n2_;
      for (int plane = 0; plane < kFourStepComplexPlanes; ++plane) {
        const Complex* in = data + plane * n;
        Complex* out = scratch.data() + plane * band_points;
        for (int p2 = 0; p2 < n2_; ++p2) {
          const Complex* row = in + std::size_t(p2) * n1_ + first;
          for (int r = 0; r < height; ++r) out[std::size_t(r) * n2_ + p2] = row[r];
        }
      }
      UnpackTask<Real> task;
      task.pairs = true;
      task.data = reinterpret_cast<const Real*>(scratch.data());
      task.data_plane = band_points;
      task.count = n;
      task.fields = reinterpret_cast<Real*>(fields) + std::size_t(first) * n2_;
      task.begin = 0;
      task.end = band_points;
      task.inverse_scale = inverse_scale;
      probe += unpack_range(task);
    }
  }
  return probe;
}

template void FourStep::transform<float>(void*, int) const;
template void FourStep::transform<double>(void*, int) const;
template float FourStep::unpack<float>(const void*, std::byte*, const float*, int) const;
template double FourStep::unpack<double>(const void*, std::byte*, const double*, int) const;

}  // namespace swell::impls::synthesis
