// radix2: Cooley–Tukey radix-2 decimation in time, powers of two only, fp32 and fp64.
//
// Layout for speed: every pass (rows along x, then columns along y) takes a block of L signals
// (one register: L = 16 floats or 8 doubles with AVX-512, 8 or 4 with AVX, 4 or 2 with the
// portable build's SSE2 and on other architectures) into a per-thread
// scratch array of elements {re vector, im vector}: element i holds sample i of all L signals,
// split into real and imaginary lanes, in bit-reversed order. Each butterfly then works on
// whole vectors — one twiddle broadcast against L signals — with no shuffles. Twiddles come
// from long double cos/sin; every butterfly is the plain radix-2 one, a ± w·b, with the table
// twiddle w.
//
// What makes it fast (a 2-D transform is mostly memory traffic, not arithmetic):
//  * Up to three radix-2 stages per sweep over the scratch (stages h, 2h, 4h on 8 elements
//    held in registers), which cuts the loads and stores of the butterflies threefold; a
//    512-bit store takes two cycles on AMD Zen 4, so stores, not flops, bound a sweep.
//  * The first three stages (twiddles 1, ∓i and the eighth roots: two multiplications per
//    eight points) are done while gathering the input, and the last log2 R stages (R = 4 … 16)
//    while scattering the output, so the scratch (up to 512 KB, in L2) is swept only for the
//    stages in between: once up to n = 1024, twice at 2048 and 4096.
//  * Those middle stages run chunk by chunk on 128 elements (16 KB, in L1); from n = 4096 one
//    stage sweeps the whole scratch.
// Every butterfly is still the plain radix-2 one with the same table twiddle (the trivial ones
// 1 and ∓i done exactly), so the arithmetic is stage-by-stage radix 2; fusing only keeps values
// in registers between stages.
//  * Gathering L rows is an L×L in-register transpose of full 64-byte loads (AVX-512; with
//    AVX, of 16-byte loads into the halves of 32-byte registers, which keeps every shuffle
//    within a half; with SSE2, a 4×4 transpose or an unpack of 16-byte loads), not scalar moves;
//    gathering L columns is two loads and two shuffles per row. The strided column accesses are
//    software-prefetched a few rows ahead, since the hardware prefetchers do not follow 16 KB
//    strides. With narrower vectors two (AVX) or four (SSE2) adjacent column blocks go
//    together, so that each row's 128 bytes are used at once, as with AVX-512.
// Signals left over when a count is not a multiple of L, and sizes too small for the fused
// passes, go through the same stages with scalar gathers (unused lanes hold zeros).
#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstddef>
#include <numbers>
#include <vector>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "backends.hpp"
#include "complex_engine.hpp"
#include "swell/impls/radix2_kernel.hpp"

namespace swell::impls {
namespace {

// One vector of reals (GCC/Clang vector extension) as wide as the machine's registers: 64 bytes
// (zmm) with AVX-512, 32 bytes (ymm) with AVX, 16 (xmm) otherwise — the portable x86-64 build
// (SSE2) and other architectures. A vector wider than the registers is split into several,
// and the fused stages' eight elements no longer fit the 16 registers.
#if defined(__AVX512F__)
#define SWELL_RADIX2_VECTOR_BYTES 64
#elif defined(__AVX__)
#define SWELL_RADIX2_VECTOR_BYTES 32
#else
#define SWELL_RADIX2_VECTOR_BYTES 16
#endif
template <typename T>
struct VecOf;
template <>
struct VecOf<float> {
  typedef float type __attribute__((vector_size(SWELL_RADIX2_VECTOR_BYTES)));
};
template <>
struct VecOf<double> {
  typedef double type __attribute__((vector_size(SWELL_RADIX2_VECTOR_BYTES)));
};
template <typename T>
using Vec = typename VecOf<T>::type;
template <typename T>
constexpr int kLanes = SWELL_RADIX2_VECTOR_BYTES / sizeof(T);
// A scratch element: one sample of L signals.
//
// Copies go member by member: GCC 12 lowers the implicit copy of this 2-vector aggregate as a
// block move, which for every AVX2 target (not AVX-512) it carried through pairs of general
// registers (vmovq, vpinsrq) in the fused stages' loads and stores; without them the row pass
// at 256² took 37–40 % less on AMD Zen 1 (docs/performance.md §8).
template <typename T>
struct Cx {
  Vec<T> re, im;
  Cx() = default;
  Cx(Vec<T> real, Vec<T> imag) : re(real), im(imag) {}
  Cx(const Cx& other) : re(other.re), im(other.im) {}
  Cx& operator=(const Cx& other) {
    re = other.re;
    im = other.im;
    return *this;
  }
};

template <typename T>
struct Axis {
  int n = 1;
  std::vector<int> bit_reversed;      // over log2 n bits (small sizes)
  std::vector<int> quarter_reversed;  // over log2 n − 2 bits, for q < n/4 (fused first pass)
  std::vector<int> eighth_reversed;   // over log2 n − 3 bits, for q < n/8 (fused first pass)
  // Stage with butterfly span h uses w_j = e^(∓iπ j/h), j < h, stored at [h + j].
  std::vector<T> w_re, w_im_forward, w_im_inverse;

  explicit Axis(int size) : n(size), bit_reversed(size), w_re(size), w_im_forward(size), w_im_inverse(size) {
    int bits = 0;
    while ((1 << bits) < n) ++bits;
    const auto reverse = [](int i, int width) {
      int r = 0;
      for (int b = 0; b < width; ++b) r |= ((i >> b) & 1) << (width - 1 - b);
      return r;
    };
    for (int i = 0; i < n; ++i) bit_reversed[i] = reverse(i, bits);
    if (n >= 4) {
      quarter_reversed.resize(n / 4);
      for (int i = 0; i < n / 4; ++i) quarter_reversed[i] = reverse(i, bits - 2);
    }
    if (n >= 8) {
      eighth_reversed.resize(n / 8);
      for (int i = 0; i < n / 8; ++i) eighth_reversed[i] = reverse(i, bits - 3);
    }
    for (int h = 1; h < n; h <<= 1) {
      for (int j = 0; j < h; ++j) {
        const long double angle = std::numbers::pi_v<long double> * j / h;
        w_re[h + j] = static_cast<T>(std::cos(angle));
        w_im_forward[h + j] = static_cast<T>(-std::sin(angle));
        w_im_inverse[h + j] = static_cast<T>(std::sin(angle));
      }
    }
  }
};

// ------------------------------------------------------------------ butterflies

// a, b ← a + w·b, a − w·b with w = c + i·d.
template <typename T>
inline void butterfly(Cx<T>& a, Cx<T>& b, T c, T d) {
  const Vec<T> tr = c * b.re - d * b.im;
  const Vec<T> ti = c * b.im + d * b.re;
  b.re = a.re - tr;
  b.im = a.im - ti;
  a.re += tr;
  a.im += ti;
}

// w = 1: no multiplication.
template <typename T>
inline void butterfly_one(Cx<T>& a, Cx<T>& b) {
  const Cx<T> t = b;
  b.re = a.re - t.re;
  b.im = a.im - t.im;
  a.re += t.re;
  a.im += t.im;
}

// w = e^(∓iπ/2) = ∓i (forward −i, inverse +i): a swap and a sign, exact.
template <typename T>
inline void butterfly_i(Cx<T>& a, Cx<T>& b, bool inverse) {
  const Vec<T> tr = inverse ? -b.im : b.im;
  const Vec<T> ti = inverse ? b.re : -b.re;
  b.re = a.re - tr;
  b.im = a.im - ti;
  a.re += tr;
  a.im += ti;
}

// Radix-2 stages h, 2h, …, (R/2)·h on elements [begin, end) in one sweep (R = 2, 4, 8): the R
// elements a group of R·h touches at offset j (j + r·h, r < R) are closed under those stages and
// stay in registers between them. In the stage of span step·h, element r pairs with r + step and
// sits at offset j + (r mod step)·h in its group of 2·step·h, which indexes the twiddle.
template <typename T, int R>
void stage_group(Cx<T>* __restrict x, int begin, int end, int h, const T* wr, const T* wi) {
  for (int s = begin; s < end; s += R * h) {
    Cx<T>* p = x + s;
    for (int j = 0; j < h; ++j) {
      Cx<T> e[R];
#pragma GCC unroll 8
      for (int r = 0; r < R; ++r) e[r] = p[j + r * h];
#pragma GCC unroll 4
      for (int step = 1; step < R; step *= 2) {
#pragma GCC unroll 8
        for (int r = 0; r < R; ++r) {
          if (r & step) continue;
          const int w = step * h + j + (r & (step - 1)) * h;
          butterfly(e[r], e[r + step], wr[w], wi[w]);
        }
      }
#pragma GCC unroll 8
      for (int r = 0; r < R; ++r) p[j + r * h] = e[r];
    }
  }
}

// Stages first, 2·first, …, last (spans, powers of two) on [begin, end), three at a time (two
// and two when four are left, so no sweep does a single stage that a pair could share).
template <typename T>
void stages(Cx<T>* x, int begin, int end, int first, int last, const T* wr, const T* wi) {
  int count = 0;
  for (int h = first; h <= last; h *= 2) ++count;
  int h = first;
  while (count > 0) {
    const int fused = count == 4 ? 2 : std::min(count, 3);
    if (fused == 3) stage_group<T, 8>(x, begin, end, h, wr, wi);
    if (fused == 2) stage_group<T, 4>(x, begin, end, h, wr, wi);
    if (fused == 1) stage_group<T, 2>(x, begin, end, h, wr, wi);
    h <<= fused;
    count -= fused;
  }
}

// ------------------------------------------------------------------ gathers and scatters
//
// An IO gives the L signals of a block sample by sample: load1/store1 one sample m (natural
// order), load/store kGroup consecutive samples k … k + kGroup − 1.

#if defined(__SSE2__)
// One register's worth of complex values, unaligned.
template <typename T>
inline Vec<T> load_vec(const std::complex<T>* p) {
  Vec<T> v;
  __builtin_memcpy(&v, static_cast<const void*>(p), sizeof v);
  return v;
}
template <typename T>
inline void store_vec(std::complex<T>* p, Vec<T> v) {
  __builtin_memcpy(static_cast<void*>(p), &v, sizeof v);
}
#endif

#if defined(__SSE2__) && SWELL_RADIX2_VECTOR_BYTES <= 32
// The intrinsics' type for a Vec<T> (16 or 32 bytes), and two registers of interleaved complex
// values (re, im, re, im, …) split into their real and imaginary parts and back, by shuffles
// within 128-bit halves: with 32-byte registers the parts come out in a fixed permuted order
// (fp32: 0, 1, 4, 5 | 2, 3, 6, 7; fp64: 0, 2 | 1, 3) that interleave_low/high undo, with
// 16-byte ones in order.
template <typename T>
struct RegOf;
#if SWELL_RADIX2_VECTOR_BYTES == 16
template <>
struct RegOf<float> {
  typedef __m128 type;
};
template <>
struct RegOf<double> {
  typedef __m128d type;
};
#else
template <>
struct RegOf<float> {
  typedef __m256 type;
};
template <>
struct RegOf<double> {
  typedef __m256d type;
};
#endif
template <typename T>
using Reg = typename RegOf<T>::type;
#if SWELL_RADIX2_VECTOR_BYTES == 16
inline __m128 real_parts(__m128 a, __m128 b) { return _mm_shuffle_ps(a, b, 0x88); }
inline __m128 imag_parts(__m128 a, __m128 b) { return _mm_shuffle_ps(a, b, 0xDD); }
inline __m128d real_parts(__m128d a, __m128d b) { return _mm_unpacklo_pd(a, b); }
inline __m128d imag_parts(__m128d a, __m128d b) { return _mm_unpackhi_pd(a, b); }
inline __m128 interleave_low(__m128 re, __m128 im) { return _mm_unpacklo_ps(re, im); }
inline __m128 interleave_high(__m128 re, __m128 im) { return _mm_unpackhi_ps(re, im); }
inline __m128d interleave_low(__m128d re, __m128d im) { return _mm_unpacklo_pd(re, im); }
inline __m128d interleave_high(__m128d re, __m128d im) { return _mm_unpackhi_pd(re, im); }
#else
inline __m256 real_parts(__m256 a, __m256 b) { return _mm256_shuffle_ps(a, b, 0x88); }
inline __m256 imag_parts(__m256 a, __m256 b) { return _mm256_shuffle_ps(a, b, 0xDD); }
inline __m256d real_parts(__m256d a, __m256d b) { return _mm256_unpacklo_pd(a, b); }
inline __m256d imag_parts(__m256d a, __m256d b) { return _mm256_unpackhi_pd(a, b); }
inline __m256 interleave_low(__m256 re, __m256 im) { return _mm256_unpacklo_ps(re, im); }
inline __m256 interleave_high(__m256 re, __m256 im) { return _mm256_unpackhi_ps(re, im); }
inline __m256d interleave_low(__m256d re, __m256d im) { return _mm256_unpacklo_pd(re, im); }
inline __m256d interleave_high(__m256d re, __m256d im) { return _mm256_unpackhi_pd(re, im); }
#endif

// The rows' gathers and scatters move 16-byte pieces of rows: a 16-byte register is one piece
// (of one row), a 32-byte register two — at `first` in its low half and `first + apart` (another
// row) in its high half. No shuffle crosses the two 128-bit halves of a 32-byte register: on
// cores that split ymm operations in two (AMD Zen 1 and 2) a lane-crossing vperm2f128 costs
// several times an in-half unpack, while a 128-bit load into either half (vinsertf128 from
// memory) is as cheap as a plain load.
#if SWELL_RADIX2_VECTOR_BYTES == 16
template <typename T>
inline Reg<T> load_pieces(const std::complex<T>* first, std::size_t) {
  return (Reg<T>)load_vec(first);
}
template <typename T>
inline void store_pieces(std::complex<T>* first, std::size_t, Reg<T> v) {
  store_vec(first, (Vec<T>)v);
}
#else
inline __m256 load_pieces(const std::complex<float>* first, std::size_t apart) {
  const __m128 l = _mm_loadu_ps(reinterpret_cast<const float*>(first));
  const __m128 h = _mm_loadu_ps(reinterpret_cast<const float*>(first + apart));
  return _mm256_insertf128_ps(_mm256_castps128_ps256(l), h, 1);
}
inline __m256d load_pieces(const std::complex<double>* first, std::size_t apart) {
  const __m128d l = _mm_loadu_pd(reinterpret_cast<const double*>(first));
  const __m128d h = _mm_loadu_pd(reinterpret_cast<const double*>(first + apart));
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(l), h, 1);
}
inline void store_pieces(std::complex<float>* first, std::size_t apart, __m256 v) {
  _mm_storeu_ps(reinterpret_cast<float*>(first), _mm256_castps256_ps128(v));
  _mm_storeu_ps(reinterpret_cast<float*>(first + apart), _mm256_extractf128_ps(v, 1));
}
inline void store_pieces(std::complex<double>* first, std::size_t apart, __m256d v) {
  _mm_storeu_pd(reinterpret_cast<double*>(first), _mm256_castpd256_pd128(v));
  _mm_storeu_pd(reinterpret_cast<double*>(first + apart), _mm256_extractf128_pd(v, 1));
}
#endif

// The 4 × 4 transpose within each 128-bit half: lane i of v[c] ← lane c of v[i] (i, c < 4),
// and with 32-byte registers likewise lanes 4 + i. An involution, so loads and stores share it.
#if SWELL_RADIX2_VECTOR_BYTES == 16
inline void transpose_halves(__m128 (&v)[4]) {
  const __m128 t0 = _mm_unpacklo_ps(v[0], v[1]), t1 = _mm_unpackhi_ps(v[0], v[1]);
  const __m128 t2 = _mm_unpacklo_ps(v[2], v[3]), t3 = _mm_unpackhi_ps(v[2], v[3]);
  v[0] = _mm_shuffle_ps(t0, t2, 0x44);
  v[1] = _mm_shuffle_ps(t0, t2, 0xEE);
  v[2] = _mm_shuffle_ps(t1, t3, 0x44);
  v[3] = _mm_shuffle_ps(t1, t3, 0xEE);
}
#else
inline void transpose_halves(__m256 (&v)[4]) {
  const __m256 t0 = _mm256_unpacklo_ps(v[0], v[1]), t1 = _mm256_unpackhi_ps(v[0], v[1]);
  const __m256 t2 = _mm256_unpacklo_ps(v[2], v[3]), t3 = _mm256_unpackhi_ps(v[2], v[3]);
  v[0] = _mm256_shuffle_ps(t0, t2, 0x44);
  v[1] = _mm256_shuffle_ps(t0, t2, 0xEE);
  v[2] = _mm256_shuffle_ps(t1, t3, 0x44);
  v[3] = _mm256_shuffle_ps(t1, t3, 0xEE);
}
#endif
#endif

#if defined(__AVX512F__)
inline Vec<float> permute2(Vec<float> a, __m512i index, Vec<float> b) {
  return (Vec<float>)_mm512_permutex2var_ps((__m512)a, index, (__m512)b);
}
inline Vec<double> permute2(Vec<double> a, __m512i index, Vec<double> b) {
  return (Vec<double>)_mm512_permutex2var_pd((__m512d)a, index, (__m512d)b);
}

// Index vectors for the two-source permutes between interleaved complex and split re / im
// (sources a, b; b's lanes numbered L … 2L − 1).
template <typename T>
struct Shuffles {
  static constexpr int L = kLanes<T>;
  using Index = std::conditional_t<sizeof(T) == 4, int, long long>;
  // Interleaved complex pairs (a, b) ↔ split re / im.
  alignas(64) Index even[L]{}, odd[L]{};    // re from a,b = [re im re im …]; im likewise
  alignas(64) Index low[L]{}, high[L]{};    // re, im → first / second half interleaved

  constexpr Shuffles() {
    for (int p = 0; p < L; ++p) {
      even[p] = 2 * p;
      odd[p] = 2 * p + 1;
      low[p] = (p & 1) ? L + p / 2 : p / 2;
      high[p] = (p & 1) ? L + L / 2 + p / 2 : L / 2 + p / 2;
    }
  }
};
template <typename T>
constexpr Shuffles<T> kShuffles{};

inline __m512i index_vector(const int* p) { return _mm512_load_si512(p); }
inline __m512i index_vector(const long long* p) { return _mm512_load_si512(p); }

// The shuffles of the transposes, written with full masks: GCC 12's unmasked intrinsics pass
// _mm512_undefined_*() through, which -Wmaybe-uninitialized reports (GCC bug 105593). A full
// mask compiles to the plain instruction.
inline __m512 unpack_lo(__m512 a, __m512 b) { return _mm512_mask_unpacklo_ps(a, 0xFFFF, a, b); }
inline __m512 unpack_hi(__m512 a, __m512 b) { return _mm512_mask_unpackhi_ps(a, 0xFFFF, a, b); }
inline __m512d unpack_lo(__m512d a, __m512d b) { return _mm512_mask_unpacklo_pd(a, 0xFF, a, b); }
inline __m512d unpack_hi(__m512d a, __m512d b) { return _mm512_mask_unpackhi_pd(a, 0xFF, a, b); }
// 128-bit blocks: (a0, a2, b0, b2) for kEvenBlocks, (a1, a3, b1, b3) for kOddBlocks.
constexpr int kEvenBlocks = 0x88, kOddBlocks = 0xDD;
template <int kBlocks>
inline __m512 blocks(__m512 a, __m512 b) { return _mm512_mask_shuffle_f32x4(a, 0xFFFF, a, b, kBlocks); }
template <int kBlocks>
inline __m512d blocks(__m512d a, __m512d b) { return _mm512_mask_shuffle_f64x2(a, 0xFF, a, b, kBlocks); }

// The 4 × 4 transpose of 128-bit blocks: result b holds block b of a0, a1, a2, a3 in that order.
template <typename V>
inline std::array<V, 4> transpose_blocks(V a0, V a1, V a2, V a3) {
  const V even_low = blocks<kEvenBlocks>(a0, a1), odd_low = blocks<kOddBlocks>(a0, a1);
  const V even_high = blocks<kEvenBlocks>(a2, a3), odd_high = blocks<kOddBlocks>(a2, a3);
  return {blocks<kEvenBlocks>(even_low, even_high), blocks<kEvenBlocks>(odd_low, odd_high),
          blocks<kOddBlocks>(even_low, even_high), blocks<kOddBlocks>(odd_low, odd_high)};
}

// The first step of a transpose: rows 2i and 2i + 1 unpacked into t[2i] (low halves of each
// 128-bit block) and t[2i + 1] (high halves).
template <typename W, typename V, int L>
inline void unpack_row_pairs(const W (&v)[L], V (&t)[L]) {
#pragma GCC unroll 8
  for (int i = 0; i < L / 2; ++i) {
    t[2 * i] = unpack_lo((V)v[2 * i], (V)v[2 * i + 1]);
    t[2 * i + 1] = unpack_hi((V)v[2 * i], (V)v[2 * i + 1]);
  }
}

// v[i][p] ← v[p][i]: unpacks within 128-bit blocks, then two steps of whole-block shuffles.
// As many instructions as log2 L steps of two-source permutes (64 for floats, 24 for
// doubles), but cheaper ones, and no index vectors held in registers: the row pass took 9 %
// less at fp32 256², 16 % at fp64 512², the same elsewhere (docs/performance.md §3).
inline void transpose(Vec<float> (&v)[16]) {
  __m512 t[16], u[16];
  // t[2i + j], block k: columns 4k + 2j, 4k + 2j + 1 of rows 2i, 2i + 1, interleaved.
  unpack_row_pairs(v, t);
  // u[4g + j], block k: column 4k + j of rows 4g … 4g + 3.
#pragma GCC unroll 4
  for (int g = 0; g < 4; ++g) {
    const __m512d a = _mm512_castps_pd(t[4 * g]), b = _mm512_castps_pd(t[4 * g + 1]);
    const __m512d c = _mm512_castps_pd(t[4 * g + 2]), d = _mm512_castps_pd(t[4 * g + 3]);
    u[4 * g] = _mm512_castpd_ps(unpack_lo(a, c));
    u[4 * g + 1] = _mm512_castpd_ps(unpack_hi(a, c));
    u[4 * g + 2] = _mm512_castpd_ps(unpack_lo(b, d));
    u[4 * g + 3] = _mm512_castpd_ps(unpack_hi(b, d));
  }
  // Column 4k + j: block k of u[j], u[4 + j], u[8 + j], u[12 + j].
#pragma GCC unroll 4
  for (int j = 0; j < 4; ++j) {
    const auto k = transpose_blocks(u[j], u[4 + j], u[8 + j], u[12 + j]);
    for (int b = 0; b < 4; ++b) v[4 * b + j] = (Vec<float>)k[b];
  }
}
inline void transpose(Vec<double> (&v)[8]) {
  __m512d t[8];
  // t[2i + j], block k: column 2k + j of rows 2i, 2i + 1.
  unpack_row_pairs(v, t);
  // Column 2k + j: block k of t[j], t[2 + j], t[4 + j], t[6 + j].
#pragma GCC unroll 2
  for (int j = 0; j < 2; ++j) {
    const auto k = transpose_blocks(t[j], t[2 + j], t[4 + j], t[6 + j]);
    for (int b = 0; b < 4; ++b) v[2 * b + j] = (Vec<double>)k[b];
  }
}

#endif

// L whole rows of length n: row l at src + l·n, written to dst + l·n (may equal src).
template <typename T>
struct RowsIO {
  static constexpr int L = kLanes<T>;
  // Samples per load and store: one 64-byte line of each row (8 floats' or 4 doubles' complex
  // values), whatever the register width. Half lines (AVX's L / 2 samples) let the gather's 32
  // row streams at 4 KiB strides, which share an L1 set, evict each line between its halves:
  // fp64 2048-point rows took 6 % longer on Zen 1 (docs/performance.md §8).
  static constexpr int kGroup = 64 / int(sizeof(std::complex<T>));
  static_assert(kGroup % (L / 2) == 0);
  const std::complex<T>* src;
  std::complex<T>* dst;
  std::size_t n;

  Cx<T> load1(int m) const {
    Cx<T> x;
    for (int l = 0; l < L; ++l) {
      x.re[l] = src[l * n + m].real();
      x.im[l] = src[l * n + m].imag();
    }
    return x;
  }
  void store1(int m, const Cx<T>& x) const {
    for (int l = 0; l < L; ++l) dst[l * n + m] = std::complex<T>(x.re[l], x.im[l]);
  }
  // The next line of each of the L rows, read (rw = 0) or written (rw = 1) by the next load or
  // store of the same rows: the gather's and the scatter's 8–16 streams a row, 64–128 in all,
  // are more than the hardware prefetchers follow. On AMD Zen 1 the row pass took 10–25 % less
  // with it (fp64 512-point rows 2.06–2.25 → 1.53–1.64 ms, fp32 2048-point 21.5 → 18.5 ms); with
  // AVX-512 on Zen 4 it had not paid (docs/performance.md §3), so that path does not call it.
  void prefetch_next(const std::complex<T>* rows, int k, int rw) const {
    if (k + kGroup >= int(n)) return;
#pragma GCC unroll 8
    for (int l = 0; l < L; ++l) {
      if (rw) {
        __builtin_prefetch(rows + l * n + k + kGroup, 1);
      } else {
        __builtin_prefetch(rows + l * n + k + kGroup, 0);
      }
    }
  }
#if defined(__AVX512F__)
  // One 64-byte load per row, then a transpose: vector 2t holds the real parts of sample
  // k + t across the L rows, vector 2t + 1 the imaginary parts.
  void load(int k, Cx<T>* x) const {
    Vec<T> v[L];
#pragma GCC unroll 16
    for (int l = 0; l < L; ++l) v[l] = load_vec(src + l * n + k);
    transpose(v);
#pragma GCC unroll 8
    for (int t = 0; t < kGroup; ++t) x[t] = {v[2 * t], v[2 * t + 1]};
  }
  void store(int k, const Cx<T>* x) const {
    Vec<T> v[L];
#pragma GCC unroll 8
    for (int t = 0; t < kGroup; ++t) {
      v[2 * t] = x[t].re;
      v[2 * t + 1] = x[t].im;
    }
    transpose(v);
#pragma GCC unroll 16
    for (int l = 0; l < L; ++l) store_vec(dst + l * n + k, v[l]);
  }
#elif defined(__SSE2__)
  // Lane i holds row i; a register is loaded and stored as 16-byte pieces (load_pieces): one
  // piece of one row (16-byte vectors), or of row i and row i + L/2 (32-byte vectors, AVX).
  // fp32: a piece is a pair of samples, and the in-half 4 × 4 transpose of four registers
  // (rows 0–3, with AVX also 4–7) gives re and im of the pair across the L rows. fp64: a piece
  // is one sample, and the real and imaginary parts of two registers (rows 0 and 1, with AVX
  // also 2 and 3) give its re and im across the L rows.
  //
  // Each load and store also prefetches the next line of its L rows (prefetch_next).
  static constexpr std::size_t kPieceRowsApart = L / (SWELL_RADIX2_VECTOR_BYTES / 16);
  void load(int k, Cx<T>* x) const {
    prefetch_next(src, k, 0);
    const std::size_t apart = kPieceRowsApart * n;
    if constexpr (sizeof(T) == 4) {
#pragma GCC unroll 4
      for (int pair = 0; pair < kGroup / 2; ++pair) {
        const int m = k + 2 * pair;
        Reg<T> v[4];
#pragma GCC unroll 4
        for (int i = 0; i < 4; ++i) v[i] = load_pieces(src + i * n + m, apart);
        transpose_halves(v);
        x[2 * pair] = {(Vec<T>)v[0], (Vec<T>)v[1]};
        x[2 * pair + 1] = {(Vec<T>)v[2], (Vec<T>)v[3]};
      }
    } else {
#pragma GCC unroll 4
      for (int t = 0; t < kGroup; ++t) {
        const Reg<T> a = load_pieces(src + k + t, apart), b = load_pieces(src + n + k + t, apart);
        x[t] = {(Vec<T>)real_parts(a, b), (Vec<T>)imag_parts(a, b)};
      }
    }
  }
  void store(int k, const Cx<T>* x) const {
    prefetch_next(dst, k, 1);
    const std::size_t apart = kPieceRowsApart * n;
    if constexpr (sizeof(T) == 4) {
#pragma GCC unroll 4
      for (int pair = 0; pair < kGroup / 2; ++pair) {
        const int m = k + 2 * pair;
        Reg<T> v[4] = {(Reg<T>)x[2 * pair].re, (Reg<T>)x[2 * pair].im, (Reg<T>)x[2 * pair + 1].re,
                       (Reg<T>)x[2 * pair + 1].im};
        transpose_halves(v);
#pragma GCC unroll 4
        for (int i = 0; i < 4; ++i) store_pieces(dst + i * n + m, apart, v[i]);
      }
    } else {
#pragma GCC unroll 4
      for (int t = 0; t < kGroup; ++t) {
        const Reg<T> re = (Reg<T>)x[t].re, im = (Reg<T>)x[t].im;
        store_pieces(dst + k + t, apart, interleave_low(re, im));
        store_pieces(dst + n + k + t, apart, interleave_high(re, im));
      }
    }
  }
#else
  void load(int k, Cx<T>* x) const {
    for (int t = 0; t < kGroup; ++t) x[t] = load1(k + t);
  }
  void store(int k, const Cx<T>* x) const {
    for (int t = 0; t < kGroup; ++t) store1(k + t, x[t]);
  }
#endif
};

// L adjacent columns of an array with row stride `stride`, in place: sample m of the block is
// the L complex values (128 bytes) at data + m·stride.
template <typename T>
struct ColumnsIO {
  static constexpr int L = kLanes<T>;
  static constexpr int kGroup = L / 2;
  // Rows ahead to prefetch: enough to cover memory latency at 16 KB strides, few enough
  // for the miss buffers.
  static constexpr int kAhead = 8;
  std::complex<T>* data;
  std::size_t stride;
  int n;  // rows

#if defined(__AVX512F__)
  Cx<T> load1(int m) const {
    const std::complex<T>* p = data + m * stride;
    const Vec<T> a = load_vec(p), b = load_vec(p + L / 2);
    const auto& tab = kShuffles<T>;
    return {permute2(a, index_vector(tab.even), b), permute2(a, index_vector(tab.odd), b)};
  }
  void store1(int m, const Cx<T>& x) const {
    std::complex<T>* p = data + m * stride;
    const auto& tab = kShuffles<T>;
    store_vec(p, permute2(x.re, index_vector(tab.low), x.im));
    store_vec(p + L / 2, permute2(x.re, index_vector(tab.high), x.im));
  }
#elif defined(__SSE2__)
  // Two loads, a = the block's first L/2 columns and b = the rest, split into re and im within
  // 128-bit halves (real_parts, imag_parts). With 32-byte vectors the lanes hold the columns out
  // of order; store1 undoes exactly that, and the columns are independent signals.
  Cx<T> load1(int m) const {
    const std::complex<T>* p = data + m * stride;
    const auto a = (Reg<T>)load_vec(p), b = (Reg<T>)load_vec(p + L / 2);
    return {(Vec<T>)real_parts(a, b), (Vec<T>)imag_parts(a, b)};
  }
  void store1(int m, const Cx<T>& x) const {
    std::complex<T>* p = data + m * stride;
    const auto re = (Reg<T>)x.re, im = (Reg<T>)x.im;
    store_vec(p, (Vec<T>)interleave_low(re, im));
    store_vec(p + L / 2, (Vec<T>)interleave_high(re, im));
  }
#else
  Cx<T> load1(int m) const {
    const std::complex<T>* p = data + m * stride;
    Cx<T> x;
    for (int l = 0; l < L; ++l) {
      x.re[l] = p[l].real();
      x.im[l] = p[l].imag();
    }
    return x;
  }
  void store1(int m, const Cx<T>& x) const {
    std::complex<T>* p = data + m * stride;
    for (int l = 0; l < L; ++l) p[l] = std::complex<T>(x.re[l], x.im[l]);
  }
#endif
  // The block's L complex values in one row: two 64-byte lines with AVX-512, one with AVX, half a
  // line (prefetched by each of the two blocks in it) with 16-byte vectors.
  static constexpr int kLines = std::max(1, L * int(sizeof(std::complex<T>)) / 64);
  void prefetch(int m, int rw) const {
    if (m >= n) return;
    const char* p = reinterpret_cast<const char*>(data + m * stride);
#pragma GCC unroll 2
    for (int line = 0; line < kLines; ++line) {
      if (rw) {
        __builtin_prefetch(p + 64 * line, 1);
      } else {
        __builtin_prefetch(p + 64 * line, 0);
      }
    }
  }
  void load(int k, Cx<T>* x) const {
    for (int t = 0; t < kGroup; ++t) {
      prefetch(k + t + kAhead, 0);
      x[t] = load1(k + t);
    }
  }
  void store(int k, const Cx<T>* x) const {
    for (int t = 0; t < kGroup; ++t) {
      prefetch(k + t + kAhead, 1);
      store1(k + t, x[t]);
    }
  }
};

// Up to L signals with any strides, scalar: leftover rows of a batch, narrow columns. Lanes
// beyond `count` are zero and never stored.
template <typename T>
struct StridedIO {
  static constexpr int kGroup = kLanes<T> / 2;
  const std::complex<T>* src;
  std::complex<T>* dst;
  std::ptrdiff_t sample_stride, signal_stride;
  int count;

  Cx<T> load1(int m) const {
    Cx<T> x{};
    for (int l = 0; l < count; ++l) {
      const std::complex<T> z = src[m * sample_stride + l * signal_stride];
      x.re[l] = z.real();
      x.im[l] = z.imag();
    }
    return x;
  }
  void store1(int m, const Cx<T>& x) const {
    for (int l = 0; l < count; ++l) {
      dst[m * sample_stride + l * signal_stride] = std::complex<T>(x.re[l], x.im[l]);
    }
  }
  void load(int k, Cx<T>* x) const {
    for (int t = 0; t < kGroup; ++t) x[t] = load1(k + t);
  }
  void store(int k, const Cx<T>* x) const {
    for (int t = 0; t < kGroup; ++t) store1(k + t, x[t]);
  }
};

// ------------------------------------------------------------------ one block of L signals

// Scratch per thread, reused across calls: a fresh allocation of this size per block would be
// an mmap and page faults every time.
template <typename T>
Cx<T>* scratch(std::size_t count) {
  thread_local std::vector<Cx<T>> buffer;
  if (buffer.size() < count) buffer.resize(count);
  return buffer.data();
}

// Elements per chunk for the middle stages: 128 × 128 bytes = 16 KB, inside L1 with the
// twiddles beside it on cores with 32 KB (AMD Zen 4) as well as 48 KB (Zen 5, recent Intel).
// 256 measured the same within this machine's noise.
constexpr int kChunk = 128;

// The last log2 R stages, spans n/R … n/2, fused with the scatter. With q = n/R, the R
// elements j + r·q (r < R) form a closed group under those stages, and they are exactly the
// outputs at those natural positions: each is read once from scratch and written to the signals.
// P blocks at once (scratch p at x + p·n), step by step: see transform_blocks.
template <typename T, int R, typename IO, int P>
void scatter_last(const std::array<IO, P> ios, const Cx<T>* __restrict x, int n, const T* wr,
                  const T* wi) {
  constexpr int G = IO::kGroup;
  const int q = n / R;
  for (int k = 0; k < q; k += G) {
    for (int p = 0; p < P; ++p) {
      const Cx<T>* __restrict xp = x + p * n;
      Cx<T> out[R][G];
      for (int t = 0; t < G; ++t) {
        const int j = k + t;
        Cx<T> e[R];
#pragma GCC unroll 16
        for (int r = 0; r < R; ++r) e[r] = xp[j + r * q];
        // Stage of span h = step·q pairs r with r + step; position j + r·q sits at offset
        // j + (r mod step)·q in its group of 2h, which indexes the twiddle.
#pragma GCC unroll 4
        for (int step = 1; step < R; step *= 2) {
          const int h = step * q;
#pragma GCC unroll 16
          for (int r = 0; r < R; ++r) {
            if (r & step) continue;
            const int w = h + j + (r & (step - 1)) * q;
            butterfly(e[r], e[r + step], wr[w], wi[w]);
          }
        }
#pragma GCC unroll 16
        for (int r = 0; r < R; ++r) out[r][t] = e[r];
      }
      for (int r = 0; r < R; ++r) ios[p].store(k + r * q, out[r]);
    }
  }
}

// P blocks of L signals each (P = 1, or kColumnBlocksTogether adjacent column blocks: 2 with
// AVX, 4 with 16-byte vectors, so that a row's 128 bytes are used together, as AVX-512's one
// block uses them), each with its own scratch; the gather and the scatter go step by step
// through the blocks, the middle stages block by block.
template <typename T, typename IO, int P>
void transform_blocks(const std::array<IO, P> ios, const Axis<T>& axis, bool inverse) {
  const int n = axis.n;
  Cx<T>* __restrict x = scratch<T>(std::size_t(P) * n);
  const T* wr = axis.w_re.data();
  const T* wi = inverse ? axis.w_im_inverse.data() : axis.w_im_forward.data();
  constexpr int G = IO::kGroup;

  if (n < 16 || n / 4 < G) {
    // Small: plain bit-reversed gather, every stage, natural-order scatter.
    for (int p = 0; p < P; ++p) {
      Cx<T>* xp = x + p * n;
      for (int m = 0; m < n; ++m) xp[axis.bit_reversed[m]] = ios[p].load1(m);
      stages(xp, 0, n, 1, n / 2, wr, wi);
      for (int m = 0; m < n; ++m) ios[p].store1(m, xp[m]);
    }
    return;
  }

  int first_middle = 4;  // span of the first stage the gather has not done
  // The eight-point gather (spans 1, 2, 4) needs G samples in each eighth, and room above span 4
  // for the scatter's two stages at the least (spans n/4, n/2): n ≥ 32.
  if (n / 8 < G || n < 32) {
    // Gather with stages 1 and 2. Scratch position 4p + r holds sample bitrev(4p + r), which
    // is s + {0, n/2, n/4, 3n/4}[r] with s = bitrev over log2 n − 2 bits of p: the four
    // quarters of the input at the same offset s make one group of four.
    const int q = n / 4;
    for (int k = 0; k < q; k += G) {
      for (int p = 0; p < P; ++p) {
        Cx<T> in[4][G];
        for (int r = 0; r < 4; ++r) ios[p].load(k + r * q, in[r]);
        for (int t = 0; t < G; ++t) {
          Cx<T> a = in[0][t], b = in[2][t], c = in[1][t], d = in[3][t];
          butterfly_one(a, b);  // span 1, w = 1
          butterfly_one(c, d);
          butterfly_one(a, c);  // span 2, w = 1 and ∓i
          butterfly_i(b, d, inverse);
          Cx<T>* out = x + p * n + 4 * axis.quarter_reversed[k + t];
          out[0] = a;
          out[1] = b;
          out[2] = c;
          out[3] = d;
        }
      }
    }
  } else {
    // Gather with stages 1, 2 and 4: scratch position 8p + r holds sample bitrev(8p + r) =
    // s + bitrev₃(r)·n/8 with s = bitrev over log2 n − 3 bits of p, so the eight eighths of the
    // input at offset s make one group, and its three stages are an 8-point transform.
    const int q = n / 8;
    for (int k = 0; k < q; k += G) {
      for (int p = 0; p < P; ++p) {
        Cx<T> in[8][G];
        for (int r = 0; r < 8; ++r) ios[p].load(k + r * q, in[r]);
        for (int t = 0; t < G; ++t) {
          Cx<T> e[8] = {in[0][t], in[4][t], in[2][t], in[6][t], in[1][t], in[5][t], in[3][t], in[7][t]};
          butterfly_one(e[0], e[1]);  // span 1, w = 1
          butterfly_one(e[2], e[3]);
          butterfly_one(e[4], e[5]);
          butterfly_one(e[6], e[7]);
          butterfly_one(e[0], e[2]);  // span 2, w = 1 and ∓i
          butterfly_i(e[1], e[3], inverse);
          butterfly_one(e[4], e[6]);
          butterfly_i(e[5], e[7], inverse);
          butterfly_one(e[0], e[4]);  // span 4, w = e^(∓iπj/4): 1, table, ∓i, table
          butterfly(e[1], e[5], wr[5], wi[5]);
          butterfly_i(e[2], e[6], inverse);
          butterfly(e[3], e[7], wr[7], wi[7]);
          Cx<T>* out = x + p * n + 8 * axis.eighth_reversed[k + t];
#pragma GCC unroll 8
          for (int r = 0; r < 8; ++r) out[r] = e[r];
        }
      }
    }
    first_middle = 8;
  }

  // The last log2 R stages (spans n/R … n/2) go with the scatter. R is the smallest of 4, 8, 16
  // that leaves at most three stages between the gather and the scatter (one sweep over the
  // scratch, by stage_group<8>); from n = 2048 more are left.
  int groups = 4;
  while (groups < 16 && n / (2 * groups) > 4 * first_middle) groups *= 2;
  const int last_middle = n / groups / 2;
  // Middle stages, spans first_middle … last_middle: those whose pairs lie within a chunk (span
  // ≤ kChunk/2) chunk by chunk while it sits in L1, then (from n = 4096) the rest over the whole
  // scratch.
  int local_last = first_middle / 2;
  while (2 * local_last <= last_middle && 2 * (2 * local_last) <= kChunk) local_last *= 2;
  for (int p = 0; p < P; ++p) {
    Cx<T>* xp = x + p * n;
    if (local_last >= first_middle) {
      const int chunk = std::min(n, kChunk);
      for (int c = 0; c < n; c += chunk) stages(xp, c, c + chunk, first_middle, local_last, wr, wi);
    }
    if (2 * local_last <= last_middle) stages(xp, 0, n, 2 * local_last, last_middle, wr, wi);
  }

  switch (groups) {
    case 4: return scatter_last<T, 4, IO, P>(ios, x, n, wr, wi);
    case 8: return scatter_last<T, 8, IO, P>(ios, x, n, wr, wi);
    default: return scatter_last<T, 16, IO, P>(ios, x, n, wr, wi);
  }
}

template <typename T, typename IO>
void transform_block(const IO io, const Axis<T>& axis, bool inverse) {
  transform_blocks<T, IO, 1>({io}, axis, inverse);
}

// When the threads pay (never slower with 2 threads than with 1). A pass is split by
// blocks of L signals, each thread its share. A batch of 1-D rows (one pass) is split from 2¹⁵
// points with ≥ 2 blocks a thread. A 2-D transform is split in both passes or in neither — the
// row pass leaves each thread's rows in its own caches and the column pass reads every row, so
// a threaded pass beside a serial one moves half the array between the cores for nothing — from
// 2¹⁵ points, with ≥ 2 row blocks and ≥ 4 column blocks a thread (a column pass of few wide
// blocks loses on its own). Measured on the 2-core reference VM (2026-12-04, fp32 c2c unless
// marked, medians of 2001, µs one thread / two), with every pass from 64² threaded, the rule
// before (set when the transposes were slower): 64² 7.5 / 10.9, fp64 64² 14.8 / 23.5, 128²
// 21.0 / 22.4 in one hour and 20.7 / 14.7 in the next (the second core comes and goes on this
// host), 32×1024 43.9 / 72.5 and 47.1 / 57.8, 64×512 42.4 / 47.2, fp64 128×256 80.5 / 95.2;
// with one pass threaded and the other not, 128×256 42.1 / 47.6, fp64 128×256 83.1 / 117.1.
constexpr std::size_t kThreadedFromPoints = std::size_t(1) << 15;
constexpr int kThreadedFromRowBlocksPerThread = 2;
constexpr int kThreadedFromColumnBlocksPerThread = 4;

// Column blocks transformed together (transform_blocks): with AVX (no AVX-512) a block is 64 bytes
// of each row, one cache line, and two adjacent blocks use both lines of a 128-byte pair while
// they are in the caches, as one AVX-512 block does. On AMD Zen 1 (2026-12-04, minima, one
// process alternating): fp64 2048² 104 → 92 ms, 4096² 522–556 → 462–475 ms, 1024² 20.1–20.5
// → 18.0–19.9 ms; fp32 2048² 46.6–48.4 → 45.7–46.6 ms; 256² and 512² the same within noise.
// With 16-byte vectors (the portable build) a block is 32 bytes of a row, and four go together.
constexpr int kColumnBlocksTogether = 128 / (2 * SWELL_RADIX2_VECTOR_BYTES);  // 1, 2, 4

template <typename T>
class Radix2Engine final : public detail::ComplexEngine<T> {
 public:
  static constexpr int kL = kLanes<T>;

  Radix2Engine(int nx, int ny, int threads) : x_(nx), y_(ny), threads_(threads) {}

  // Whether a batch of `rows` 1-D rows, and a whole 2-D transform, run on the threads.
  bool rows_threaded(int rows) const {
    return threads_ > 1 && std::size_t(x_.n) * rows >= kThreadedFromPoints &&
           rows / kL >= kThreadedFromRowBlocksPerThread * threads_;
  }
  bool two_d_threaded() const {
    return rows_threaded(y_.n) && x_.n / kL >= kThreadedFromColumnBlocksPerThread * threads_;
  }

  // `rows` rows of length nx from src to dst (may alias).
  void rows(const std::complex<T>* src, std::complex<T>* dst, int rows, bool inverse,
            bool threaded) const {
    const std::size_t nx = x_.n;
    const int blocks = rows / kL;
#pragma omp parallel for num_threads(threads_) schedule(static) if (threaded)
    for (int b = 0; b < blocks; ++b) {
      const std::size_t offset = std::size_t(b) * kL * nx;
      transform_block<T>(RowsIO<T>{src + offset, dst + offset, nx}, x_, inverse);
    }
    if (const int left = rows - blocks * kL; left > 0) {
      const std::size_t offset = std::size_t(blocks) * kL * nx;
      transform_block<T>(StridedIO<T>{src + offset, dst + offset, 1, std::ptrdiff_t(nx), left}, x_,
                         inverse);
    }
  }

  void columns(std::complex<T>* data, bool inverse, bool threaded) const {
    const int nx = x_.n;
    const int blocks = nx / kL;
    const auto block = [&](int b) { return ColumnsIO<T>{data + b * kL, std::size_t(nx), y_.n}; };
    constexpr int P = kColumnBlocksTogether;
    const int groups = blocks / P;
#pragma omp parallel for num_threads(threads_) schedule(static) if (threaded)
    for (int g = 0; g < groups; ++g) {
      std::array<ColumnsIO<T>, P> ios;
      for (int p = 0; p < P; ++p) ios[p] = block(g * P + p);
      transform_blocks<T, ColumnsIO<T>, P>(ios, y_, inverse);
    }
    for (int b = groups * P; b < blocks; ++b) transform_block<T>(block(b), y_, inverse);
    if (const int left = nx - blocks * kL; left > 0) {
      std::complex<T>* p = data + blocks * kL;
      transform_block<T>(StridedIO<T>{p, p, nx, 1, left}, y_, inverse);
    }
  }

  void c2c(const std::complex<T>* in, std::complex<T>* out, Direction d) const override {
    const bool inverse = d == Direction::inverse;
    if (y_.n == 1) return rows(in, out, 1, inverse, false);
    const bool threaded = two_d_threaded();  // both passes or neither
    rows(in, out, y_.n, inverse, threaded);
    columns(out, inverse, threaded);
  }

  int nx() const { return x_.n; }

 private:
  Axis<T> x_, y_;
  int threads_;
};

template <typename T>
class Radix2Plan final : public Plan {
 public:
  Radix2Plan(const TransformSpec& spec, int threads)
      : Plan(spec), engine_(spec.nx, spec.ny, threads) {}

  void execute(const void* in, void* out) const override {
    const auto& s = spec();
    if (s.kind == Kind::c2c && s.rank() == 1) {
      // A batch of 1-D transforms is one pass over all its rows.
      engine_.rows(static_cast<const std::complex<T>*>(in), static_cast<std::complex<T>*>(out),
                   s.howmany, s.direction == Direction::inverse, engine_.rows_threaded(s.howmany));
      return;
    }
    detail::run_via_complex<T>(s, engine_, in, out);
  }
  using Plan::execute;

 private:
  Radix2Engine<T> engine_;
};

class Radix2Backend final : public Backend {
 public:
  explicit Radix2Backend(const BackendOptions& options) : threads_(options.threads) {
    if (!options.planner.empty()) {
      throw InvalidInput("radix2 takes no planner option (got planner=" + options.planner + ")");
    }
  }
  std::string name() const override { return "radix2"; }
  Capabilities capabilities() const override {
    Capabilities c;
    c.precisions = {Precision::f32, Precision::f64};
    c.any_size = false;
    c.size_rule = "powers of two";
    c.multi_threaded = true;
    return c;
  }
  std::unique_ptr<Plan> plan(const TransformSpec& spec) const override {
    validate(spec);
    if (spec.precision == Precision::f32) return std::make_unique<Radix2Plan<float>>(spec, threads_);
    return std::make_unique<Radix2Plan<double>>(spec, threads_);
  }

 private:
  int threads_;
};

// The kernel rate (radix2_kernel.hpp): stage_group<8> over one chunk at spans 8, 16, 32, as
// the middle stages sweep it. The chunk holds zeros: the cost of IEEE arithmetic on these cores
// does not depend on the values save for subnormals, and zeros neither overflow over thousands
// of sweeps (each multiplies the norm by up to 2³) nor underflow.
template <typename T>
Radix2KernelRate measure_kernel_rate(int repetitions) {
  constexpr int kSweeps = 2000;
  constexpr int kSpan = 8;
  const Axis<T> axis(kChunk);
  std::vector<Cx<T>> chunk(kChunk, Cx<T>(Vec<T>{}, Vec<T>{}));
  double best = 1e300;
  for (int repetition = 0; repetition < std::max(1, repetitions); ++repetition) {
    const auto start = std::chrono::steady_clock::now();
    for (int sweep = 0; sweep < kSweeps; ++sweep) {
      stage_group<T, 8>(chunk.data(), 0, kChunk, kSpan, axis.w_re.data(), axis.w_im_inverse.data());
      // The chunk is read after every sweep, as far as the compiler knows.
      __asm__ volatile("" : : "r"(chunk.data()) : "memory");
    }
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  const double vector_butterflies = double(kSweeps) * (kChunk / 2) * 3;  // three stages a sweep
  return {kLanes<T>, best / vector_butterflies};
}

}  // namespace

std::unique_ptr<Backend> make_radix2_backend(const BackendOptions& options) {
  return std::make_unique<Radix2Backend>(options);
}

Radix2KernelRate measure_radix2_kernel_rate(Precision precision, int repetitions) {
  if (precision == Precision::f32) return measure_kernel_rate<float>(repetitions);
  if (precision == Precision::f64) return measure_kernel_rate<double>(repetitions);
  throw InvalidInput("radix2 has no " + to_string(precision) + " kernel (fp32 and fp64 only)");
}

}  // namespace swell::impls
