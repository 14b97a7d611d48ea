#pragma once
// One plan-based interface for every transform backend (docs/transforms.md).
//
// Conventions (docs/conventions.md §Transforms): forward is e^(−i…), inverse e^(+i…), both
// unnormalized as FFTW. Arrays are row-major with x fastest: a 2-D transform of ny rows × nx
// columns; a batch of `howmany` transforms lies back to back. Real-to-complex keeps FFTW's
// half spectrum along x: (nx/2 + 1) complex values per row.
//
// A plan is immutable and its execute() is const and safe to call from several threads at once.
// Plans run either on host pointers or on backend buffers; a device backend keeps its buffers on
// the device, so a chain of transforms on Buffers never copies through the host.
#include <complex>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "swell/reference/errors.hpp"

namespace swell::impls {

enum class Precision { f32, f64, f80 };  // float, double, long double
enum class Kind { c2c, r2c, c2r };
enum class Direction { forward, inverse };  // r2c is always forward, c2r always inverse
enum class Placement { out_of_place, in_place };

std::string to_string(Precision p);  // "fp32", "fp64", "fp80"
std::string to_string(Kind k);       // "c2c", "r2c", "c2r"
std::string to_string(Direction d);  // "forward", "inverse"
Precision precision_from_string(const std::string& name);  // throws InvalidInput
std::size_t real_size(Precision p);  // bytes of one real number

struct TransformSpec {
  int nx = 0;        // samples along x (fastest); a 1-D transform has ny = 1
  int ny = 1;        // rows; 1 for 1-D
  int howmany = 1;   // transforms in the batch
  Kind kind = Kind::c2c;
  Direction direction = Direction::forward;
  Precision precision = Precision::f64;
  Placement placement = Placement::out_of_place;

  int rank() const { return ny == 1 ? 1 : 2; }
  // Elements (real or complex, per kind) of one transform's input and output.
  std::size_t input_elements() const;
  std::size_t output_elements() const;
  std::size_t input_bytes() const;   // whole batch
  std::size_t output_bytes() const;  // whole batch
  bool input_is_complex() const { return kind != Kind::r2c; }
  bool output_is_complex() const { return kind != Kind::c2r; }
  std::string describe() const;      // "c2c inverse fp32 256×256 ×1 out-of-place"
};

// What a backend cannot do: names the backend, the size and the rule. The CLI exits 2 on it.
class UnsupportedTransform : public InvalidInput {
 public:
  using InvalidInput::InvalidInput;
};

// Memory a backend's plans run on: host memory for CPU backends, device memory for a GPU one.
class Buffer {
 public:
  virtual ~Buffer() = default;
  virtual std::size_t bytes() const = 0;
  virtual void upload(const void* host, std::size_t bytes) = 0;
  virtual void download(void* host, std::size_t bytes) const = 0;
  // Host address of the data, or nullptr when it lives on a device.
  virtual void* host_data() = 0;
  virtual const void* host_data() const = 0;
};

class Plan {
 public:
  explicit Plan(TransformSpec spec) : spec_(spec) {}
  virtual ~Plan() = default;
  const TransformSpec& spec() const { return spec_; }

  // Host memory holding spec().input_bytes() and output_bytes(); `in` == `out` for in-place.
  // An out-of-place transform leaves its input unchanged, bit for bit.
  virtual void execute(const void* in, void* out) const = 0;
  // A c2c plan's transform of `data` written back over it: bit for bit what execute(data, out)
  // writes into another array, out of place or in place as planned, without the caller holding
  // a second array. The default goes through a temporary one; a backend whose plan already
  // passes through its own array (FFTW's padded rows) copies back from there.
  virtual void execute_over_input(void* data) const;
  // Buffers from the same backend. The default uses their host memory.
  virtual void execute(const Buffer& in, Buffer& out) const;

  // Typed host execution, with the element types and sizes checked against the spec.
  template <typename In, typename Out>
  void execute(std::span<const In> in, std::span<Out> out) const {
    check_span(sizeof(In), in.size(), sizeof(Out), out.size(), in.data() == (const void*)out.data());
    execute(static_cast<const void*>(in.data()), static_cast<void*>(out.data()));
  }

 protected:
  void check_span(std::size_t in_element_bytes, std::size_t in_count,
                  std::size_t out_element_bytes, std::size_t out_count, bool aliased) const;

 private:
  TransformSpec spec_;
};

struct Capabilities {
  std::vector<Precision> precisions;
  bool any_size = false;          // false: powers of two only
  bool real_transforms = true;    // r2c and c2r
  bool in_place = true;           // c2c in place
  bool multi_threaded = false;
  bool exact = true;              // false for `null`, which copies instead of transforming
  bool device_resident = false;   // buffers live on a device
  // Its own 1-D plans of sizes beyond the caches are already blocked (FFTW's), so a lattice
  // frame runs them in one pass rather than through the synthesizer's four-step transform,
  // which pays only where they are not (radix2: 1.8–2.7× faster from 2^18 points on,
  // docs/lattice.md §Measured). null's copy is no transform to block.
  bool blocked_large_1d = false;
  std::string size_rule;          // "any N ≥ 1", "powers of two"
};

// Backend options from a name such as "fftw:planner=estimate,threads=2".
struct BackendOptions {
  std::string planner;   // fftw: estimate | measure | patient | exhaustive
  int threads = 1;
  int device = -1;       // vulkan: index of the Vulkan device; −1 chooses (docs/vulkan.md)
  bool subgroups = true;  // vulkan: the subgroup-shuffle kernel where the device allows it
};

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string name() const = 0;
  virtual Capabilities capabilities() const = 0;
  // Throws UnsupportedTransform when the spec breaks a rule of this backend.
  virtual std::unique_ptr<Plan> plan(const TransformSpec& spec) const = 0;
  // A buffer of `bytes` bytes that this backend's plans run on (host memory, 64-byte aligned,
  // unless the backend is device resident).
  virtual std::unique_ptr<Buffer> allocate(std::size_t bytes) const;
  // Checks the rules common to every backend and this backend's capabilities.
  void validate(const TransformSpec& spec) const;
};

// ------------------------------------------------------------------ registry

// Every backend name known to this build, in a stable order: naive, radix2, fftw, null, ….
std::vector<std::string> backend_names();
// "radix2", "fftw:planner=estimate,threads=2": the name selects the backend, the options
// after ':' configure it. Unknown names or options throw InvalidInput listing what is valid.
std::unique_ptr<Backend> make_backend(const std::string& name_and_options);

// Host memory aligned to 64 bytes (one cache line; AVX-512 width).
class HostBuffer final : public Buffer {
 public:
  // Fill::zero (the default) zeroes the bytes; Fill::none leaves them as the allocator gives
  // them, for a caller that writes every byte before reading any.
  enum class Fill { zero, none };
  explicit HostBuffer(std::size_t bytes, Fill fill = Fill::zero);
  ~HostBuffer() override;
  HostBuffer(const HostBuffer&) = delete;
  HostBuffer& operator=(const HostBuffer&) = delete;
  std::size_t bytes() const override { return bytes_; }
  void upload(const void* host, std::size_t bytes) override;
  void download(void* host, std::size_t bytes) const override;
  void* host_data() override { return data_; }
  const void* host_data() const override { return data_; }

 private:
  std::size_t bytes_;
  void* data_;
};

bool is_power_of_two(long n);

}  // namespace swell::impls
