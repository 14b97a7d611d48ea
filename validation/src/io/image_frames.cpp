#include "image_frames.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <type_traits>

#include "image_module.hpp"
#include "swell/reference/errors.hpp"

namespace swell::validation::detail {
namespace {

namespace fs = std::filesystem;
using reference::Field;
using reference::FieldFrame;
using reference::Grid;

// TIFF has no channel names; swell keeps them in the ImageDescription tag after this prefix.
constexpr const char* kTiffChannelsPrefix = "swell channels:";

double roundoff_of(SampleType type) {
  switch (type) {
    case SampleType::half: return kHalfRoundoff;
    case SampleType::float32: return kFloatRoundoff;
    case SampleType::float64: return kDoubleRoundoff;
    default: return 0;  // not a floating-point type
  }
}

std::string describe_field(Field field, const std::string& channel) {
  return fmt::format("{} ({})", reference::field_name(field), channel);
}

// Channel index of each requested field in an image with this header.
std::map<Field, int> locate_channels(const std::string& file, ImageKind kind,
                                     const ImageHeader& header,
                                     const std::map<Field, std::string>& channels) {
  std::vector<std::string> names = header.channel_names;
  const int count = int(names.size());
  bool named_by_swell = false;
  if (kind == ImageKind::tiff && header.description.rfind(kTiffChannelsPrefix, 0) == 0) {
    std::vector<std::string> stored;
    std::istringstream words(header.description.substr(std::strlen(kTiffChannelsPrefix)));
    for (std::string word; words >> word;) stored.push_back(word);
    if (stored.size() == names.size()) {
      names = stored;
      named_by_swell = true;
    }
  }
  auto list = [&] {
    std::string out;
    for (const auto& name : names) out += (out.empty() ? "" : ", ") + name;
    return out;
  };

  std::map<Field, int> found;
  for (const auto& [field, channel] : channels) {
    const auto it = std::find(names.begin(), names.end(), channel);
    if (it != names.end()) found[field] = static_cast<int>(it - names.begin());
  }
  if (found.size() == channels.size()) return found;

  // A TIFF from another writer, and any PNG, has no channel names of its own (OpenImageIO
  // calls them Y, or R, G, B, A, channel4, …): when none of the names match and the channel
  // count equals the number of fields listed, the fields are taken by position in swell's order
  // h, sx, sy, dx, dy, J.
  if ((kind == ImageKind::tiff || kind == ImageKind::png) && !named_by_swell && found.empty() &&
      static_cast<int>(channels.size()) == count) {
    int position = 0;
    for (Field field : reference::kAllFields) {
      if (channels.count(field)) found[field] = position++;
    }
    return found;
  }
  for (const auto& [field, channel] : channels) {
    if (found.count(field)) continue;
    throw InvalidInput(fmt::format("{}: missing channel '{}' for {} (the file has {} channel{}: "
                                   "{})",
                                   file, channel, reference::field_name(field), count,
                                   count == 1 ? "" : "s", list()));
  }
  return found;  // unreachable: some field was missing
}

// Per field: its values when kept (or stored as integers, whose rms sets the rounding), and
// its non-finite samples: how many, and the first.
struct Taken {
  Field field = Field::height;
  std::string channel;     // its name in the file
  std::size_t offset = 0;  // its place among the channels read together
  bool kept = true;
  const IntegerRange* range = nullptr;
  double levels = 0;
  std::vector<double> values;
  std::size_t bad = 0, first_bad = 0;
  double first_bad_value = 0;
};

// Where the wanted fields are in one image, and what they are stored as: every check of the
// header against the case, before any pixel is read.
struct Layout {
  std::vector<Taken> taken;
  int first = 0, last = -1;   // the channels from the first wanted to the last
  bool all_float = true;      // half and float only: read as float (exact), else as double
  bool any_integer = false;   // a field stored as 8- or 16-bit integers over a value_range
  double float_roundoff = 0;  // the largest unit roundoff of the floating-point fields
};

Layout lay_out(const std::string& file, ImageKind kind, const ImageHeader& header,
               const Grid& grid, const InputSpec& input,
               const std::function<bool(Field)>& keep) {
  if (header.deep) throw InvalidInput(file + ": deep images are not supported");
  if (header.width != grid.nx || header.height != grid.ny || header.depth != 1) {
    throw InvalidInput(fmt::format("{}: wrong size: {}×{}{} pixels, the case's grid is {}×{} "
                                   "([grid] n)",
                                   file, header.width, header.height,
                                   header.depth != 1 ? fmt::format("×{}", header.depth) : "",
                                   grid.nx, grid.ny));
  }
  const auto located = locate_channels(file, kind, header, input.channels);
  Layout layout;
  layout.first = int(header.channel_names.size());
  for (const auto& [field, index] : located) {
    const SampleType type = header.channel_types[std::size_t(index)];
    const std::string& type_name = header.channel_type_names[std::size_t(index)];
    const std::string& name = header.channel_names[std::size_t(index)];
    const bool has_range = input.value_ranges.count(field) > 0;
    Taken t;
    t.field = field;
    t.channel = name;
    t.kept = !keep || keep(field);
    if (const double u = roundoff_of(type); u > 0) {
      if (has_range) {
        throw InvalidInput(fmt::format("{}: channel '{}' for {} stores {} floating-point values, "
                                       "which need no [input] value_range (it is for 8- and "
                                       "16-bit integer images); remove it",
                                       file, name, reference::field_name(field), type_name));
      }
      layout.float_roundoff = std::max(layout.float_roundoff, u);
      layout.all_float = layout.all_float && type != SampleType::float64;
    } else if (type == SampleType::uint8 || type == SampleType::uint16) {
      const double levels = type == SampleType::uint8 ? 255.0 : 65535.0;
      if (!has_range) {
        throw InvalidInput(fmt::format("{}: channel '{}' for {} stores {}-bit integers, which carry "
                                       "no unit: give [input] value_range = [low, high], the "
                                       "values (metres) that pixel 0 and pixel {} stand for "
                                       "(docs/case_files.md)",
                                       file, name, reference::field_name(field),
                                       levels == 255.0 ? 8 : 16, levels));
      }
      t.range = &input.value_ranges.at(field);
      t.levels = levels;
      layout.any_integer = true;
    } else {
      throw InvalidInput(fmt::format("{}: channel '{}' for {} stores {} values; swell reads "
                                     "floating-point channels (half, float, double) and 8- or "
                                     "16-bit unsigned integers with [input] value_range",
                                     file, name, reference::field_name(field), type_name));
    }
    t.offset = std::size_t(index);  // made relative to `first` below
    layout.first = std::min(layout.first, index);
    layout.last = std::max(layout.last, index);
    layout.taken.push_back(std::move(t));
  }
  for (Taken& t : layout.taken) t.offset -= std::size_t(layout.first);
  return layout;
}

// A scanline EXR straight from its blocks into the fields, a line at a time (exr_scanlines.hpp:
// 11 ms a frame of 512² with six float channels, against ~40 ms through OpenImageIO, one thread
// each). False when that reader does not take the file.
bool read_exr_directly(const std::string& file, const Grid& grid, Layout& layout,
                       ExrScratch& scratch) {
  std::vector<std::string> names;  // taken[k]'s channel is names[k]
  for (const Taken& t : layout.taken) names.push_back(t.channel);
  const std::size_t width = std::size_t(grid.nx);
  const bool read = read_exr_scanlines(
      file, names, grid.nx, grid.ny,
      [&](std::size_t slot, std::size_t row, const float* values) {
        Taken& t = layout.taken[slot];
        const std::size_t start = row * width;
        // |v| ≤ FLT_MAX is false for ±∞ and NaN; an integer OR of it vectorizes (a bool &=
        // of std::isfinite did not: 3.5 % of the gate's CPU).
        constexpr float kLargest = std::numeric_limits<float>::max();
        int non_finite = 0;
        if (t.kept) {
          double* out = t.values.data() + start;
          for (std::size_t x = 0; x < width; ++x) {
            out[x] = values[x];
            non_finite |= !(std::fabs(values[x]) <= kLargest);
          }
        } else {
          for (std::size_t x = 0; x < width; ++x) non_finite |= !(std::fabs(values[x]) <= kLargest);
        }
        if (!non_finite) return;
        for (std::size_t x = 0; x < width; ++x) {
          if (std::isfinite(values[x])) continue;
          if (t.bad++ == 0) {  // rows arrive in order: the first is the lowest index
            t.first_bad = start + x;
            t.first_bad_value = values[x];
          }
        }
      },
      scratch);
  if (!read) {
    for (Taken& t : layout.taken) t.bad = 0;  // counted again when the file is read otherwise
  }
  return read;
}

// Every channel from the first wanted to the last in one read through OpenImageIO: a
// compressed file (EXR ZIP blocks hold all channels of 16 scanlines) is then decompressed once,
// not once per field. Half, float and integer values (OpenImageIO scales 8- and 16-bit
// integers to [0, 1]) are exact in float, which halves the buffer; double stays double. The
// whole image in one read: OpenEXR then decodes its blocks on all of its threads (reading bands
// of ~85 rows instead, to keep the buffer in cache, made gate/512/64 0.15–0.2 s slower).
template <typename Real>
void read_through_module(const std::string& file, ImageReader& image, const Grid& grid,
                         Layout& layout, std::vector<Real>& buffer) {
  const std::size_t count = static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny);
  const int span = layout.last - layout.first + 1;
  buffer.resize(count * std::size_t(span));
  const SampleType type = std::is_same_v<Real, float> ? SampleType::float32 : SampleType::float64;
  if (std::string why = image.read(layout.first, layout.last + 1, type, buffer.data()); !why.empty()) {
    std::string names;
    for (int c = layout.first; c <= layout.last; ++c) {
      names += (names.empty() ? "'" : ", '") + image.header().channel_names[std::size_t(c)] + "'";
    }
    throw InvalidInput(fmt::format("{}: cannot read channel{} {} (truncated or corrupt file?): "
                                   "{}",
                                   file, span == 1 ? "" : "s", names, why));
  }
  for (Taken& t : layout.taken) {
    const Real* pixels = buffer.data() + t.offset;
    if (t.range) {
      const double width = t.range->high - t.range->low;
      for (std::size_t k = 0; k < count; ++k) t.values[k] = t.range->low + width * pixels[k * span];
      continue;  // integers are finite
    }
    bool finite = true;
    if (t.kept) {
      for (std::size_t k = 0; k < count; ++k) {
        const double v = pixels[k * span];
        t.values[k] = v;
        finite &= std::isfinite(v);
      }
    } else {
      for (std::size_t k = 0; k < count; ++k) finite &= std::isfinite(pixels[k * span]);
    }
    if (finite) continue;
    for (std::size_t k = 0; k < count; ++k) {
      const double v = pixels[k * span];
      if (std::isfinite(v)) continue;
      if (t.bad++ == 0) {
        t.first_bad = k;
        t.first_bad_value = v;
      }
    }
  }
}

}  // namespace

[[noreturn]] void fail_non_finite(const Grid& grid, const std::string& file, const std::string& what,
                                  std::size_t at, double value, std::size_t count) {
  const std::size_t i = at % static_cast<std::size_t>(grid.nx);
  const std::size_t j = at / static_cast<std::size_t>(grid.nx);
  throw InvalidInput(fmt::format("{}: {} is {} at (i, j) = ({}, {}) ({} non-finite value{} in "
                                 "all); every value must be finite",
                                 file, what, std::isnan(value) ? "NaN" : (value > 0 ? "+Inf" : "-Inf"),
                                 i, j, count, count == 1 ? "" : "s"));
}

// A field stored as integers rounds as frame_io.hpp's quantization_roundoff says.
double read_image_frame(const fs::path& path, ImageKind kind, const Grid& grid,
                        const InputSpec& input, const std::function<bool(Field)>& keep,
                        FieldFrame& frame, PixelScratch& scratch, int threads) {
  const std::string file = path.string();
  // An EXR's header through OpenEXRCore; any other image, and an EXR that OpenEXRCore cannot
  // open or swell's reader does not take, through OpenImageIO.
  const std::optional<ImageHeader> exr_header =
      kind == ImageKind::exr ? read_exr_header(file) : std::nullopt;
  std::unique_ptr<ImageReader> image;
  auto open = [&]() -> const ImageHeader& {
    std::string why;
    image = image_module("reading " + file).open(file, threads, why);
    if (!image) throw InvalidInput(fmt::format("{}: cannot read the image: {}", file, why));
    return image->header();
  };
  // The values go into the arrays `frame` already holds for these fields where it holds them (a
  // stream reading frame after frame into the same frame): fresh arrays of that size cost their
  // page faults and the kernel's zeroing on every frame.
  const std::size_t count = static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny);
  auto take_arrays = [&](Layout& layout) {
    for (Taken& t : layout.taken) {
      if (!t.kept && !t.range) continue;
      if (auto it = frame.fields.find(t.field); it != frame.fields.end()) t.values.swap(it->second);
      t.values.resize(count);
    }
  };
  auto give_back = [&](Layout& layout) {
    for (Taken& t : layout.taken) {
      if (!t.values.empty()) frame.fields[t.field].swap(t.values);
    }
  };
  Layout layout = lay_out(file, kind, exr_header ? *exr_header : open(), grid, input, keep);
  take_arrays(layout);
  const bool direct = exr_header && layout.all_float && !layout.any_integer &&
                      read_exr_directly(file, grid, layout, scratch.exr);
  if (!direct) {
    // OpenImageIO orders an EXR's channels its own way (R, G, B, A first): laid out again.
    if (!image) {
      give_back(layout);
      layout = lay_out(file, kind, open(), grid, input, keep);
      take_arrays(layout);
    }
    if (layout.all_float) {
      read_through_module(file, *image, grid, layout, scratch.f32);
    } else {
      read_through_module(file, *image, grid, layout, scratch.f64);
    }
  }
  double roundoff = layout.float_roundoff;
  for (Taken& t : layout.taken) {
    if (t.bad > 0) {
      fail_non_finite(grid, file, describe_field(t.field, t.channel), t.first_bad,
                      t.first_bad_value, t.bad);
    }
    if (t.range) roundoff = std::max(roundoff, quantization_roundoff(*t.range, t.levels, t.values));
    if (t.kept) frame.fields[t.field].swap(t.values);
  }
  return roundoff;
}

std::vector<std::string> png_channel_names(std::size_t count) {
  switch (count) {
    case 1: return {"Y"};
    case 2: return {"Y", "A"};
    case 3: return {"R", "G", "B"};
    case 4: return {"R", "G", "B", "A"};
    default:
      throw InvalidInput(fmt::format("a PNG holds at most 4 channels; {} fields were given (write "
                                     "EXR, TIFF or .npy for more)",
                                     count));
  }
}

void require_png_options(const FrameWriteOptions& options) {
  if (options.png_bits != 8 && options.png_bits != 16) {
    throw InvalidInput(fmt::format("PNG frames are 8- or 16-bit (got {} bits)", options.png_bits));
  }
  const IntegerRange& range = options.png_range;
  if (!(std::isfinite(range.low) && std::isfinite(range.high) && range.low < range.high)) {
    throw InvalidInput(fmt::format("PNG frames need a value range [low, high] with low < high, "
                                   "both finite (got [{:g}, {:g}])",
                                   range.low, range.high));
  }
}

std::vector<fs::path> write_image_frame(const fs::path& path, const Grid& grid,
                                        const std::vector<Field>& fields, const FieldFrame& frame,
                                        const FrameWriteOptions& options) {
  const std::string file = path.string();
  const std::size_t nx = static_cast<std::size_t>(grid.nx);
  if (options.format == FrameFormat::exr) {
    std::vector<std::string> names;
    for (Field field : fields) names.push_back(reference::channel_name(field));
    write_exr_scanlines(file, grid.nx, grid.ny, names,
                        [&](std::size_t slot, std::size_t row, float* values) {
                          const double* line = frame.fields.at(fields[slot]).data() + row * nx;
                          for (std::size_t x = 0; x < nx; ++x) values[x] = static_cast<float>(line[x]);
                        });
    return {path};
  }
  const bool png = options.format == FrameFormat::png;
  const double top = options.png_bits == 8 ? 255.0 : 65535.0;
  ImageWriteSpec spec;
  spec.width = grid.nx;
  spec.height = grid.ny;
  spec.stored = !png ? SampleType::float32
                     : options.png_bits == 8 ? SampleType::uint8 : SampleType::uint16;
  std::string names;
  const auto png_names = png ? png_channel_names(fields.size()) : std::vector<std::string>{};
  for (std::size_t c = 0; c < fields.size(); ++c) {
    spec.channel_names.push_back(png ? png_names[c] : reference::channel_name(fields[c]));
    names += " " + reference::channel_name(fields[c]);
  }
  if (!png) {
    spec.compression = "zip";  // lossless
    spec.description = kTiffChannelsPrefix + names;
  }
  // A PNG pixel is round((v − low)/(high − low) · top), top = 2^bits − 1; a value outside
  // [low, high] (by more than half a step) has no pixel and is an error, never clipped. Every
  // value is checked before the file is created, so a refusal leaves no file. 8-bit pixels go
  // to OpenImageIO as 16-bit values p·257, which it stores back as p exactly.
  const IntegerRange range = options.png_range;
  auto pixel = [&](double v) { return std::nearbyint((v - range.low) / (range.high - range.low) * top); };
  if (png) {
    for (const Field field : fields) {
      const auto& values = frame.fields.at(field);
      for (std::size_t p = 0; p < values.size(); ++p) {
        const double level = pixel(values[p]);
        if (level >= 0 && level <= top) continue;
        throw InvalidInput(fmt::format("{}: {} = {:g} at (i, j) = ({}, {}) lies outside the PNG "
                                       "value range [{:g}, {:g}]",
                                       file, reference::field_name(field), values[p],
                                       p % grid.nx, p / grid.nx, range.low, range.high));
      }
    }
  }
  std::string why;
  const auto output = image_module("writing " + file).create(file, spec, 0, why);
  if (!output) throw InvalidInput(fmt::format("{}: cannot write: {}", file, why));
  auto pixel_of = [&](double v) -> std::uint16_t {
    const double p = pixel(v);  // in [0, top]: checked above
    return static_cast<std::uint16_t>(top == 255.0 ? p * 257 : p);
  };
  // Interleaved rows, a block at a time, so that a large frame never needs a second copy.
  const int rows_per_block = std::max(1, static_cast<int>((1u << 20) / (nx * fields.size())));
  std::vector<float> block;
  std::vector<std::uint16_t> pixels;
  for (int y0 = 0; y0 < grid.ny; y0 += rows_per_block) {
    const int y1 = std::min(grid.ny, y0 + rows_per_block);
    const std::size_t size = static_cast<std::size_t>(y1 - y0) * nx * fields.size();
    if (png) {
      pixels.assign(size, 0);
    } else {
      block.assign(size, 0.0f);
    }
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const auto& values = frame.fields.at(fields[c]);
      for (int y = y0; y < y1; ++y) {
        for (std::size_t x = 0; x < nx; ++x) {
          const double v = values[static_cast<std::size_t>(y) * nx + x];
          const std::size_t at = ((y - y0) * nx + x) * fields.size() + c;
          if (png) {
            pixels[at] = pixel_of(v);
          } else {
            block[at] = static_cast<float>(v);
          }
        }
      }
    }
    why = png ? output->write_scanlines(y0, y1, SampleType::uint16, pixels.data())
              : output->write_scanlines(y0, y1, SampleType::float32, block.data());
    if (!why.empty()) throw InvalidInput(fmt::format("{}: write failed: {}", file, why));
  }
  if (why = output->close(); !why.empty()) {
    throw InvalidInput(fmt::format("{}: write failed: {}", file, why));
  }
  return {path};
}

}  // namespace swell::validation::detail
