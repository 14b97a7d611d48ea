// fftw: FFTW 3 in single (fftw3f), double (fftw3) and long double (fftw3l) precision, with a
// selectable planner and threads. MEASURE-class plans are costly (about 1 s at 2048²), so
// their wisdom is kept on disk: $SWELL_FFTW_WISDOM_DIR, else $XDG_CACHE_HOME/swell, else
// ~/.cache/swell, one file per precision.
#include <fftw3.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "backends.hpp"

namespace swell::impls {
namespace {

// FFTW's planner is not thread safe; its execute functions are.
std::mutex& planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

std::filesystem::path wisdom_directory() {
  if (const char* dir = std::getenv("SWELL_FFTW_WISDOM_DIR"); dir && *dir) return dir;
  if (const char* cache = std::getenv("XDG_CACHE_HOME"); cache && *cache) {
    return std::filesystem::path(cache) / "swell";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return std::filesystem::path(home) / ".cache" / "swell";
  }
  return {};
}

// The three FFTW APIs behind one set of names.
template <typename T>
struct Fftw;

#define SWELL_FFTW_API(T, P, tag)                                                            \
  template <>                                                                                \
  struct Fftw<T> {                                                                           \
    using plan = P##_plan;                                                                   \
    using complex = P##_complex;                                                             \
    static constexpr const char* name = tag;                                                 \
    static void* malloc(std::size_t n) { return P##_malloc(n); }                             \
    static void free(void* p) { P##_free(p); }                                               \
    static int alignment_of(const void* p) {                                                 \
      return P##_alignment_of(reinterpret_cast<T*>(const_cast<void*>(p)));                   \
    }                                                                                        \
    static plan many_dft(int rank, const int* n, int howmany, void* in, int idist, void* out, \
                         int odist, int sign, unsigned flags, const int* in_embed = nullptr, \
                         const int* out_embed = nullptr) {                                  \
      return P##_plan_many_dft(rank, n, howmany, static_cast<complex*>(in), in_embed, 1,    \
                               idist, static_cast<complex*>(out), out_embed, 1, odist, sign, \
                               flags);                                                       \
    }                                                                                        \
    static plan many_r2c(int rank, const int* n, int howmany, void* in, int idist, void* out, \
                         int odist, unsigned flags) {                                        \
      return P##_plan_many_dft_r2c(rank, n, howmany, static_cast<T*>(in), nullptr, 1, idist, \
                                   static_cast<complex*>(out), nullptr, 1, odist, flags);   \
    }                                                                                        \
    static plan many_c2r(int rank, const int* n, int howmany, void* in, int idist, void* out, \
                         int odist, unsigned flags) {                                        \
      return P##_plan_many_dft_c2r(rank, n, howmany, static_cast<complex*>(in), nullptr, 1, \
                                   idist, static_cast<T*>(out), nullptr, 1, odist, flags);  \
    }                                                                                        \
    static void execute_dft(plan p, const void* in, void* out) {                             \
      P##_execute_dft(p, static_cast<complex*>(const_cast<void*>(in)),                       \
                      static_cast<complex*>(out));                                           \
    }                                                                                        \
    static void execute_r2c(plan p, const void* in, void* out) {                             \
      P##_execute_dft_r2c(p, static_cast<T*>(const_cast<void*>(in)),                         \
                          static_cast<complex*>(out));                                       \
    }                                                                                        \
    static void execute_c2r(plan p, const void* in, void* out) {                             \
      P##_execute_dft_c2r(p, static_cast<complex*>(const_cast<void*>(in)),                   \
                          static_cast<T*>(out));                                             \
    }                                                                                        \
    static void destroy(plan p) { P##_destroy_plan(p); }                                     \
    static void init_threads() { P##_init_threads(); }                                       \
    static void plan_with_nthreads(int n) { P##_plan_with_nthreads(n); }                     \
    static int import_wisdom(const char* f) { return P##_import_wisdom_from_filename(f); }   \
    static int export_wisdom(const char* f) { return P##_export_wisdom_to_filename(f); }     \
  };

SWELL_FFTW_API(float, fftwf, "fftw3f")
SWELL_FFTW_API(double, fftw, "fftw3")
#undef SWELL_FFTW_API

// Debian's fftw3l has no threads library: long double plans are single threaded.
template <>
struct Fftw<long double> {
  using plan = fftwl_plan;
  using complex = fftwl_complex;
  static constexpr const char* name = "fftw3l";
  static void* malloc(std::size_t n) { return fftwl_malloc(n); }
  static void free(void* p) { fftwl_free(p); }
  static int alignment_of(const void* p) {
    return fftwl_alignment_of(reinterpret_cast<long double*>(const_cast<void*>(p)));
  }
  static plan many_dft(int rank, const int* n, int howmany, void* in, int idist, void* out,
                       int odist, int sign, unsigned flags, const int* in_embed = nullptr,
                       const int* out_embed = nullptr) {
    return fftwl_plan_many_dft(rank, n, howmany, static_cast<complex*>(in), in_embed, 1, idist,
                               static_cast<complex*>(out), out_embed, 1, odist, sign, flags);
  }
  static plan many_r2c(int rank, const int* n, int howmany, void* in, int idist, void* out,
                       int odist, unsigned flags) {
    return fftwl_plan_many_dft_r2c(rank, n, howmany, static_cast<long double*>(in), nullptr, 1,
                                   idist, static_cast<complex*>(out), nullptr, 1, odist, flags);
  }
  static plan many_c2r(int rank, const int* n, int howmany, void* in, int idist, void* out,
                       int odist, unsigned flags) {
    return fftwl_plan_many_dft_c2r(rank, n, howmany, static_cast<complex*>(in), nullptr, 1,
                                   idist, static_cast<long double*>(out), nullptr, 1, odist, flags);
  }
  static void execute_dft(plan p, const void* in, void* out) {
    fftwl_execute_dft(p, static_cast<complex*>(const_cast<void*>(in)), static_cast<complex*>(out));
  }
  static void execute_r2c(plan p, const void* in, void* out) {
    fftwl_execute_dft_r2c(p, static_cast<long double*>(const_cast<void*>(in)),
                          static_cast<complex*>(out));
  }
  static void execute_c2r(plan p, const void* in, void* out) {
    fftwl_execute_dft_c2r(p, static_cast<complex*>(const_cast<void*>(in)),
                          static_cast<long double*>(out));
  }
  static void destroy(plan p) { fftwl_destroy_plan(p); }
  static void init_threads() {}
  static void plan_with_nthreads(int) {}
  static int import_wisdom(const char* f) { return fftwl_import_wisdom_from_filename(f); }
  static int export_wisdom(const char* f) { return fftwl_export_wisdom_to_filename(f); }
};

struct FftwFree {
  template <typename T>
  void operator()(T* p) const { fftw_free(p); }  // all three libraries free with free()
};

// Buffers of fftw_malloc'd memory reused across calls: acquire() hands out a free one of the
// size asked for (or a new one), which returns to the pool when the lease ends. Thread safe,
// so that a plan's execute() stays callable from several threads at once.
class ScratchPool {
 public:
  class Lease {
   public:
    Lease(ScratchPool& pool, std::unique_ptr<char, FftwFree> buffer, std::size_t bytes)
        : pool_(pool), buffer_(std::move(buffer)), bytes_(bytes) {}
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    ~Lease() { pool_.give_back(std::move(buffer_), bytes_); }
    char* get() const { return buffer_.get(); }

   private:
    ScratchPool& pool_;
    std::unique_ptr<char, FftwFree> buffer_;
    std::size_t bytes_;
  };

  Lease acquire(std::size_t bytes) {
    {
      std::lock_guard lock(mutex_);
      for (auto it = free_.begin(); it != free_.end(); ++it) {
        if (it->first != bytes) continue;
        auto buffer = std::move(it->second);
        free_.erase(it);
        return Lease(*this, std::move(buffer), bytes);
      }
    }
    auto* memory = static_cast<char*>(fftw_malloc(bytes));
    if (!memory) throw std::bad_alloc();
    return Lease(*this, std::unique_ptr<char, FftwFree>(memory), bytes);
  }

 private:
  void give_back(std::unique_ptr<char, FftwFree> buffer, std::size_t bytes) {
    std::lock_guard lock(mutex_);
    free_.emplace_back(bytes, std::move(buffer));
  }

  std::mutex mutex_;
  std::vector<std::pair<std::size_t, std::unique_ptr<char, FftwFree>>> free_;
};

unsigned planner_flag(const std::string& planner) {
  if (planner == "estimate") return FFTW_ESTIMATE;
  if (planner == "measure" || planner.empty()) return FFTW_MEASURE;
  if (planner == "patient") return FFTW_PATIENT;
  if (planner == "exhaustive") return FFTW_EXHAUSTIVE;
  throw InvalidInput("fftw: unknown planner '" + planner +
                     "'; valid: estimate, measure (default), patient, exhaustive");
}

template <typename T>
class FftwPlan final : public Plan {
 public:
  FftwPlan(const TransformSpec& spec, const std::string& planner, int threads,
           std::shared_ptr<ScratchPool> scratch)
      : Plan(spec), scratch_(std::move(scratch)) {
    using F = Fftw<T>;
    const unsigned flag = planner_flag(planner);
    const int n[2] = {spec.ny, spec.nx};  // FFTW: row-major, last dimension fastest
    const int rank = spec.rank();
    const int* dims = rank == 1 ? n + 1 : n;
    const int idist = int(spec.input_elements()), odist = int(spec.output_elements());
    const std::size_t in_bytes = spec.input_bytes(), out_bytes = spec.output_bytes();
    const bool in_place = spec.placement == Placement::in_place;

    std::lock_guard lock(planner_mutex());
    static std::once_flag threads_once;
    std::call_once(threads_once, [] {
      fftw_init_threads();
      fftwf_init_threads();
    });
    // Wisdom from disk only for the plans that measure: FFTW gives an estimate plan any wisdom
    // the process holds (FFTW manual §4.7), so loading it for one made the analysis transforms'
    // rounding — and the gate's reports in their last digits — depend on the machine's cache.
    if (flag != FFTW_ESTIMATE) load_wisdom_once();
    F::plan_with_nthreads(threads);
    // Plan on scratch arrays: MEASURE-class planning overwrites them. fftw_malloc aligns them
    // as FFTW's SIMD codelets like; execute() checks the caller's arrays match that alignment.
    std::unique_ptr<char, FftwFree> scratch_in(static_cast<char*>(F::malloc(in_bytes)));
    std::unique_ptr<char, FftwFree> scratch_out(
        in_place ? nullptr : static_cast<char*>(F::malloc(out_bytes)));
    void* pin = scratch_in.get();
    void* pout = in_place ? pin : scratch_out.get();
    const unsigned preserve = in_place ? 0u : FFTW_PRESERVE_INPUT;
    const int sign = spec.direction == Direction::forward ? FFTW_FORWARD : FFTW_BACKWARD;
    switch (spec.kind) {
      case Kind::c2c:
        if (pads_rows(spec, flag)) {
          // Into rows kPad elements longer (see pads_rows); execute() copies them back out.
          pitch_ = spec.nx + kPad;
          padded_bytes_ = std::size_t(spec.ny) * std::size_t(pitch_) * sizeof(typename F::complex);
          std::unique_ptr<char, FftwFree> padded(static_cast<char*>(F::malloc(padded_bytes_)));
          const int rows[2] = {spec.ny, spec.nx}, padded_rows[2] = {spec.ny, pitch_};
          plan_ = F::many_dft(2, n, 1, pin, 0, padded.get(), 0, sign, flag | preserve, rows,
                              padded_rows);
        } else {
          plan_ = F::many_dft(rank, dims, spec.howmany, pin, idist, pout, odist, sign,
                              flag | preserve);
        }
        break;
      case Kind::r2c:
        plan_ = F::many_r2c(rank, dims, spec.howmany, pin, idist, pout, odist, flag | preserve);
        break;
      case Kind::c2r:
        // FFTW cannot preserve the input of a multi-dimensional c2r; such plans run on a copy.
        plan_ = F::many_c2r(rank, dims, spec.howmany, pin, idist, pout, odist, flag | preserve);
        if (!plan_) {
          copy_input_ = true;
          plan_ = F::many_c2r(rank, dims, spec.howmany, pin, idist, pout, odist, flag);
        }
        break;
    }
    if (!plan_) throw UnsupportedTransform("fftw: " + spec.describe() + ": FFTW returned no plan");
    if (flag != FFTW_ESTIMATE) save_wisdom();
  }

  ~FftwPlan() override {
    std::lock_guard lock(planner_mutex());
    Fftw<T>::destroy(plan_);
  }

  void execute(const void* in, void* out) const override {
    using F = Fftw<T>;
    const auto& s = spec();
    if (pitch_ > 0) {
      auto padded = scratch_->acquire(padded_bytes_);
      execute_padded(in, padded.get());
      copy_out_of_padded_rows(padded.get(), out);
      return;
    }
    // New-array execution (thread safe) needs the planned alignment; otherwise go through
    // aligned copies. Buffers from allocate() and fftw_malloc always qualify.
    const bool aligned = F::alignment_of(in) == 0 && F::alignment_of(out) == 0;
    if (aligned && !copy_input_) {
      run(in, out);
      return;
    }
    auto in_copy = scratch_->acquire(s.input_bytes());
    std::memcpy(in_copy.get(), in, s.input_bytes());
    if (s.placement == Placement::in_place) {
      run(in_copy.get(), in_copy.get());
      std::memcpy(out, in_copy.get(), s.output_bytes());
    } else if (F::alignment_of(out) == 0) {
      run(in_copy.get(), out);
    } else {
      auto out_copy = scratch_->acquire(s.output_bytes());
      run(in_copy.get(), out_copy.get());
      std::memcpy(out, out_copy.get(), s.output_bytes());
    }
  }
  using Plan::execute;

  // A padded plan leaves its result in the padded rows and copies it out anyway: copied back
  // over the input, the caller needs no array of its own for it. Otherwise out of place into a
  // kept array of the pool and copied back (the same arithmetic: the plan's, at its alignment).
  void execute_over_input(void* data) const override {
    const auto& s = spec();
    if (s.kind != Kind::c2c || s.placement == Placement::in_place) {
      Plan::execute_over_input(data);
      return;
    }
    if (pitch_ > 0) {
      auto padded = scratch_->acquire(padded_bytes_);
      execute_padded(data, padded.get());
      copy_out_of_padded_rows(padded.get(), data);
      return;
    }
    auto out = scratch_->acquire(s.output_bytes());
    execute(data, out.get());
    std::memcpy(data, out.get(), s.output_bytes());
  }

 private:
  // The padded plan from `in` into `padded` (padded_bytes_, the pool's alignment).
  void execute_padded(const void* in, char* padded) const {
    using F = Fftw<T>;
    if (F::alignment_of(in) == 0) {
      F::execute_dft(plan_, in, padded);
    } else {  // the plan wants the alignment it was planned with
      auto in_copy = scratch_->acquire(spec().input_bytes());
      std::memcpy(in_copy.get(), in, spec().input_bytes());
      F::execute_dft(plan_, in_copy.get(), padded);
    }
  }
  void copy_out_of_padded_rows(const char* padded, void* out) const {
    using F = Fftw<T>;
    const std::size_t row = std::size_t(spec().nx) * sizeof(typename F::complex);
    const std::size_t padded_row = std::size_t(pitch_) * sizeof(typename F::complex);
    for (int y = 0; y < spec().ny; ++y) {
      std::memcpy(static_cast<char*>(out) + y * row, padded + y * padded_row, row);
    }
  }

  void run(const void* in, void* out) const {
    using F = Fftw<T>;
    switch (spec().kind) {
      case Kind::c2c: F::execute_dft(plan_, in, out); break;
      case Kind::r2c: F::execute_r2c(plan_, in, out); break;
      case Kind::c2r: F::execute_c2r(plan_, in, out); break;
    }
  }

  static std::string wisdom_file() {
    const auto dir = wisdom_directory();
    return dir.empty() ? "" : (dir / (std::string("fftw-wisdom-") + Fftw<T>::name)).string();
  }
  static void load_wisdom_once() {  // called with the planner mutex held
    static bool loaded = false;
    if (loaded) return;
    loaded = true;
    const auto file = wisdom_file();
    if (!file.empty() && std::filesystem::exists(file)) Fftw<T>::import_wisdom(file.c_str());
  }
  static void save_wisdom() {  // called with the planner mutex held
    const auto file = wisdom_file();
    if (file.empty()) return;
    std::error_code ignored;  // a read-only cache costs planning time, not correctness
    std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ignored);
    Fftw<T>::export_wisdom(file.c_str());
  }

  // FFTW's estimate planner splits a 2-D c2c transform into a pass along the rows and one down
  // the columns, each a loop of 1-D transforms; down the columns of rows whose length in bytes
  // is a multiple of 1 KiB every sample of a column falls into the same few cache sets, and the
  // pass thrashes (512² fp64: 12.5 ms, of which 10.9 the columns). The same plan writing rows
  // 16 bytes longer (FFTW's embedded layout) computes the same arithmetic — the same bits,
  // TransformConformance.FftwEstimateOnPaddedRowsIsBitForBitFftwsOwnPlan — in 2.2 ms with the
  // copy back to the caller's rows. MEASURE-class planners time their candidates and avoid
  // the thrashing themselves; they plan the array as given. Not fp80 (the long-double oracle):
  // its estimate plan of padded 128² rows factors differently and rounds otherwise.
  static bool pads_rows(const TransformSpec& spec, unsigned flag) {
    const std::size_t row_bytes = std::size_t(spec.nx) * sizeof(typename Fftw<T>::complex);
    return !std::is_same_v<T, long double> && flag == FFTW_ESTIMATE && spec.kind == Kind::c2c &&
           spec.rank() == 2 && spec.howmany == 1 && spec.placement == Placement::out_of_place &&
           spec.ny >= 16 && row_bytes % 1024 == 0;
  }

  // 16 bytes: rows stay 16-byte aligned (one fp64 or fp80 complex, two fp32 ones); FFTW picks
  // other codelets for fp32 rows 8 bytes off, and those round differently.
  static constexpr int kPad = std::max<int>(1, 16 / int(sizeof(typename Fftw<T>::complex)));

  typename Fftw<T>::plan plan_ = nullptr;
  bool copy_input_ = false;
  int pitch_ = 0;  // > 0: rows padded to this many elements (pads_rows)
  std::size_t padded_bytes_ = 0;
  // Aligned copies and padded rows for execute(), kept between calls: allocating them anew
  // each time cost more than the transform (fft2d/c2r/fftw/fp32/1024: 39 ms against 16.7 ms
  // for FFTW's own transform; fresh pages fault in on every call). Shared by the backend's
  // plans: a forward and an inverse transform of one size, run one after the other, use one
  // padded array between them (at 4096² fp64, 268 MB), not one each.
  std::shared_ptr<ScratchPool> scratch_;
};

class FftwBackend final : public Backend {
 public:
  explicit FftwBackend(const BackendOptions& options) : options_(options) {
    planner_flag(options.planner);  // rejects an unknown planner now, not at the first plan
  }
  std::string name() const override { return "fftw"; }
  Capabilities capabilities() const override {
    Capabilities c;
    c.precisions = {Precision::f32, Precision::f64, Precision::f80};
    c.any_size = true;
    c.size_rule = "any N ≥ 1";
    c.multi_threaded = true;
    c.blocked_large_1d = true;
    return c;
  }
  std::unique_ptr<Plan> plan(const TransformSpec& spec) const override {
    validate(spec);
    const std::string planner = options_.planner.empty() ? "measure" : options_.planner;
    const int threads = threads_for(spec);
    switch (spec.precision) {
      case Precision::f32: return std::make_unique<FftwPlan<float>>(spec, planner, threads, scratch_);
      case Precision::f64: return std::make_unique<FftwPlan<double>>(spec, planner, threads, scratch_);
      case Precision::f80:
        return std::make_unique<FftwPlan<long double>>(spec, planner, threads, scratch_);
    }
    return nullptr;
  }

  // Threads that pay: FFTW's threads cost about 0.1 ms a call to wake and join, so
  // below 4 MiB of complex data (512² in fp64, 1024×512 in fp32) two threads were slower than
  // one — measured on the 2-core reference VM, c2c inverse, FFTW_MEASURE: fp32 64² 0.108
  // against 0.005 ms, 128² 0.127 against 0.029, 256² 0.204 against 0.159; fp32 512² (2 MiB)
  // paid in one session (0.54 against 0.87 ms) and lost in a later one (2026-12-04: 0.682
  // against 0.628 ms, three benchmark runs alike), when fp64 512² (4 MiB) took 0.77 against
  // 0.99, fp32 1024×512 0.99 against 1.47, 512×1024 1.09 against 1.39 and 1024² 1.90 against
  // 3.58. Smaller transforms are planned with one thread.
  static constexpr double kThreadedFromBytes = 4.0 * 1024 * 1024;
  int threads_for(const TransformSpec& spec) const {
    const double points = double(spec.nx) * double(spec.rank() == 1 ? 1 : spec.ny) * spec.howmany;
    const double bytes = points * 2 * double(real_size(spec.precision));
    return options_.threads > 1 && bytes < kThreadedFromBytes ? 1 : options_.threads;
  }

 private:
  BackendOptions options_;
  std::shared_ptr<ScratchPool> scratch_ = std::make_shared<ScratchPool>();
};

}  // namespace

std::unique_ptr<Backend> make_fftw_backend(const BackendOptions& options) {
  return std::make_unique<FftwBackend>(options);
}

}  // namespace swell::impls
