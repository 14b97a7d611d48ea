#include "swell/impls/transform.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>
#include <sstream>

#include "swell/reference/huge_pages.hpp"

namespace swell::impls {

std::string to_string(Precision p) {
  switch (p) {
    case Precision::f32: return "fp32";
    case Precision::f64: return "fp64";
    case Precision::f80: return "fp80";
  }
  return "?";
}

std::string to_string(Kind k) {
  switch (k) {
    case Kind::c2c: return "c2c";
    case Kind::r2c: return "r2c";
    case Kind::c2r: return "c2r";
  }
  return "?";
}

std::string to_string(Direction d) { return d == Direction::forward ? "forward" : "inverse"; }

Precision precision_from_string(const std::string& name) {
  if (name == "fp32" || name == "float") return Precision::f32;
  if (name == "fp64" || name == "double") return Precision::f64;
  if (name == "fp80" || name == "long-double") return Precision::f80;
  throw InvalidInput("unknown precision '" + name + "'; valid: fp32, fp64, fp80");
}

std::size_t real_size(Precision p) {
  switch (p) {
    case Precision::f32: return sizeof(float);
    case Precision::f64: return sizeof(double);
    case Precision::f80: return sizeof(long double);
  }
  return 0;
}

std::size_t TransformSpec::input_elements() const {
  const std::size_t rows = static_cast<std::size_t>(ny);
  return kind == Kind::c2r ? rows * (nx / 2 + 1) : rows * nx;
}

std::size_t TransformSpec::output_elements() const {
  const std::size_t rows = static_cast<std::size_t>(ny);
  return kind == Kind::r2c ? rows * (nx / 2 + 1) : rows * nx;
}

std::size_t TransformSpec::input_bytes() const {
  return howmany * input_elements() * real_size(precision) * (input_is_complex() ? 2 : 1);
}

std::size_t TransformSpec::output_bytes() const {
  return howmany * output_elements() * real_size(precision) * (output_is_complex() ? 2 : 1);
}

std::string TransformSpec::describe() const {
  std::ostringstream text;
  text << to_string(kind) << ' ' << to_string(direction) << ' ' << to_string(precision) << ' '
       << nx;
  if (ny != 1) text << "×" << ny;
  if (howmany != 1) text << " ×" << howmany;
  text << (placement == Placement::in_place ? " in-place" : " out-of-place");
  return text.str();
}

bool is_power_of_two(long n) { return n > 0 && (n & (n - 1)) == 0; }

// ------------------------------------------------------------------ Plan

void Plan::execute(const Buffer& in, Buffer& out) const {
  const void* in_data = in.host_data();
  void* out_data = out.host_data();
  if (!in_data || !out_data) {
    throw UnsupportedTransform(spec_.describe() + ": this plan runs on host memory only");
  }
  if (in.bytes() < spec_.input_bytes() || out.bytes() < spec_.output_bytes()) {
    throw InvalidInput(spec_.describe() + ": buffers of " + std::to_string(in.bytes()) + " and " +
                       std::to_string(out.bytes()) + " bytes, need " +
                       std::to_string(spec_.input_bytes()) + " and " +
                       std::to_string(spec_.output_bytes()));
  }
  execute(in_data, out_data);
}

void Plan::execute_over_input(void* data) const {
  if (spec_.kind != Kind::c2c) {
    throw UnsupportedTransform(spec_.describe() + ": only a c2c transform can be written back over its input");
  }
  if (spec_.placement == Placement::in_place) {
    execute(data, data);
    return;
  }
  HostBuffer out(spec_.output_bytes(), HostBuffer::Fill::none);
  execute(data, out.host_data());
  std::memcpy(data, out.host_data(), spec_.output_bytes());
}

void Plan::check_span(std::size_t in_element_bytes, std::size_t in_count,
                      std::size_t out_element_bytes, std::size_t out_count, bool aliased) const {
  const std::size_t real = real_size(spec_.precision);
  const std::size_t want_in = spec_.input_is_complex() ? 2 * real : real;
  const std::size_t want_out = spec_.output_is_complex() ? 2 * real : real;
  if (in_element_bytes != want_in || out_element_bytes != want_out) {
    throw InvalidInput(spec_.describe() + ": element types of " + std::to_string(in_element_bytes) +
                       " and " + std::to_string(out_element_bytes) + " bytes, the plan needs " +
                       std::to_string(want_in) + " and " + std::to_string(want_out));
  }
  const std::size_t need_in = spec_.howmany * spec_.input_elements();
  const std::size_t need_out = spec_.howmany * spec_.output_elements();
  if (in_count != need_in || out_count != need_out) {
    throw InvalidInput(spec_.describe() + ": buffers hold " + std::to_string(in_count) + " and " +
                       std::to_string(out_count) + " elements, the plan needs " +
                       std::to_string(need_in) + " and " + std::to_string(need_out));
  }
  if (aliased != (spec_.placement == Placement::in_place)) {
    throw InvalidInput(spec_.describe() + (aliased ? ": input and output are the same memory"
                                                   : ": in-place plan given two buffers"));
  }
}

// ------------------------------------------------------------------ Backend

std::unique_ptr<Buffer> Backend::allocate(std::size_t bytes) const {
  return std::make_unique<HostBuffer>(bytes);
}

void Backend::validate(const TransformSpec& spec) const {
  const auto caps = capabilities();
  const std::string who = name() + ": " + spec.describe() + ": ";
  auto refuse = [&](const std::string& rule) { throw UnsupportedTransform(who + rule); };
  if (spec.nx < 1 || spec.ny < 1) refuse("sizes must be ≥ 1 (got " + std::to_string(spec.nx) + "×" + std::to_string(spec.ny) + ")");
  if (spec.howmany < 1) refuse("the batch count must be ≥ 1");
  if (std::find(caps.precisions.begin(), caps.precisions.end(), spec.precision) ==
      caps.precisions.end()) {
    std::string valid;
    for (auto p : caps.precisions) valid += (valid.empty() ? "" : ", ") + to_string(p);
    refuse("precision " + to_string(spec.precision) + " is not offered (valid: " + valid + ")");
  }
  if (!caps.any_size && (!is_power_of_two(spec.nx) || !is_power_of_two(spec.ny))) {
    // Name the backends that would take it, so the refusal says what to do instead.
    std::string others;
    for (const auto& other : backend_names()) {
      if (other == "null" || other == name()) continue;
      try {
        if (make_backend(other)->capabilities().any_size) others += (others.empty() ? "" : ", ") + other;
      } catch (const std::exception&) {
        // a backend that cannot start here is no suggestion
      }
    }
    refuse("sizes must be " + caps.size_rule + " (got " + std::to_string(spec.nx) + "×" +
           std::to_string(spec.ny) + ")" +
           (others.empty() ? "" : "; for other sizes use --impl " + others));
  }
  if (spec.kind != Kind::c2c && !caps.real_transforms) refuse("real transforms are not offered");
  if (spec.kind == Kind::r2c && spec.direction != Direction::forward) refuse("r2c is forward only");
  if (spec.kind == Kind::c2r && spec.direction != Direction::inverse) refuse("c2r is inverse only");
  if (spec.placement == Placement::in_place &&
      (spec.kind != Kind::c2c || !caps.in_place)) {
    refuse("in-place is offered for c2c only (real transforms change the array's size)");
  }
}

// ------------------------------------------------------------------ HostBuffer

HostBuffer::HostBuffer(std::size_t bytes, Fill fill) : bytes_(bytes) {
  // Arrays of 2 MiB and more are placed on 2 MiB boundaries and offered transparent huge pages
  // (reference/huge_pages.hpp): a column pass steps a row (up to 64 KB) per sample, a new 4 KiB
  // page — and a TLB miss — every time, one 2 MiB page holds 32…512 rows; and one fault instead
  // of 512. Smaller ones on a cache line (aligned_alloc needs a size that is a multiple of it).
  const bool huge = bytes >= reference::kHugePageBytes;
  const std::size_t rounded = huge ? reference::round_to_huge_pages(bytes)
                                   : std::max<std::size_t>(64, (bytes + 63) / 64 * 64);
  data_ = huge ? reference::allocate_on_huge_pages(bytes) : std::aligned_alloc(64, rounded);
  if (!data_) throw std::bad_alloc();
  if (fill == Fill::zero) std::memset(data_, 0, rounded);
}

HostBuffer::~HostBuffer() { std::free(data_); }

void HostBuffer::upload(const void* host, std::size_t bytes) {
  if (bytes > bytes_) throw InvalidInput("upload of " + std::to_string(bytes) + " bytes into a buffer of " + std::to_string(bytes_));
  std::memcpy(data_, host, bytes);
}

void HostBuffer::download(void* host, std::size_t bytes) const {
  if (bytes > bytes_) throw InvalidInput("download of " + std::to_string(bytes) + " bytes from a buffer of " + std::to_string(bytes_));
  std::memcpy(host, data_, bytes);
}

}  // namespace swell::impls
