// Frames on disk (docs/case_files.md §Frames): EXR and TIFF through OpenImageIO, .npy through
// npy.hpp, headerless .raw. Readers check everything against the case and name the file.
#include "swell/validation/frame_io.hpp"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <thread>

#include "exr_scanlines.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/npy.hpp"

namespace swell::validation {
namespace {

namespace fs = std::filesystem;
using reference::Field;
using reference::FieldFrame;
using reference::FrameSequence;
using reference::Grid;

// Unit roundoff of the stored number types (conventions: the floor the checks cannot go below).
constexpr double kHalfRoundoff = 0x1p-11;
constexpr double kFloatRoundoff = 0x1p-24;
constexpr double kDoubleRoundoff = 0x1p-53;

// TIFF has no channel names; swell keeps them in the ImageDescription tag after this prefix.
constexpr const char* kTiffChannelsPrefix = "swell channels:";

enum class StoredFormat { exr, tiff, png, npy, raw };

std::string lowercase(std::string text) {
  for (auto& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

StoredFormat stored_format_of(const std::string& pattern, const std::string& origin) {
  const std::string ext = lowercase(fs::path(pattern).extension().string());
  if (ext == ".exr") return StoredFormat::exr;
  if (ext == ".tif" || ext == ".tiff") return StoredFormat::tiff;
  if (ext == ".png") return StoredFormat::png;
  if (ext == ".npy") return StoredFormat::npy;
  if (ext == ".raw") return StoredFormat::raw;
  throw InvalidInput(fmt::format("{}: files = \"{}\" has extension '{}'; swell reads .exr, .tif, "
                                 ".tiff, .png, .npy and .raw frames",
                                 origin, pattern, ext));
}

bool one_file_per_field(StoredFormat format) {
  return format == StoredFormat::npy || format == StoredFormat::raw;
}

// A printf pattern with at most one integer conversion, taken apart.
struct Pattern {
  std::string before, after;  // literal text around the conversion (%% already unescaped)
  bool has_conversion = false;
  bool zero_pad = false;
  int width = 0;
};

Pattern parse_pattern(const std::string& pattern) {
  Pattern out;
  std::string* text = &out.before;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      *text += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      *text += '%';
      ++i;
      continue;
    }
    const std::size_t start = i++;
    bool zero = false;
    if (i < pattern.size() && pattern[i] == '0') {
      zero = true;
      ++i;
    }
    int width = 0;
    while (i < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[i]))) {
      width = width * 10 + (pattern[i] - '0');
      if (width > 32) {
        throw InvalidInput(fmt::format("file pattern \"{}\": field width above 32", pattern));
      }
      ++i;
    }
    if (i >= pattern.size() || (pattern[i] != 'd' && pattern[i] != 'i' && pattern[i] != 'u')) {
      const std::string conversion = pattern.substr(start, std::min(i + 1, pattern.size()) - start);
      throw InvalidInput(fmt::format("file pattern \"{}\": unsupported conversion '{}'; use one "
                                     "integer conversion such as %04d (%% for a literal %)",
                                     pattern, conversion));
    }
    if (out.has_conversion) {
      throw InvalidInput(fmt::format("file pattern \"{}\" has more than one conversion; it takes "
                                     "one integer, the frame index",
                                     pattern));
    }
    out.has_conversion = true;
    out.zero_pad = zero;
    out.width = width;
    text = &out.after;
  }
  return out;
}

std::string expand(const Pattern& p, int index) {
  if (!p.has_conversion) return p.before;
  std::string number = std::to_string(index);
  if (static_cast<int>(number.size()) < p.width) {
    number.insert(0, p.width - number.size(), p.zero_pad ? '0' : ' ');
  }
  return p.before + number + p.after;
}

std::string with_suffix(const std::string& file, const std::string& suffix) {
  if (suffix.empty()) return file;
  fs::path path(file);
  const std::string name = path.stem().string() + "_" + suffix + path.extension().string();
  return path.replace_filename(name).string();
}

double roundoff_of(OIIO::TypeDesc type) {
  switch (type.basetype) {
    case OIIO::TypeDesc::HALF: return kHalfRoundoff;
    case OIIO::TypeDesc::FLOAT: return kFloatRoundoff;
    case OIIO::TypeDesc::DOUBLE: return kDoubleRoundoff;
    default: return 0;  // not a floating-point type
  }
}

std::string describe_field(Field field, const std::string& channel) {
  return fmt::format("{} ({})", reference::field_name(field), channel);
}

// The message for a field with `count` non-finite samples, the first at flat index `at`.
[[noreturn]] void fail_non_finite(const Grid& grid, const std::string& file, const std::string& what,
                                  std::size_t at, double value, std::size_t count) {
  const std::size_t i = at % static_cast<std::size_t>(grid.nx);
  const std::size_t j = at / static_cast<std::size_t>(grid.nx);
  throw InvalidInput(fmt::format("{}: {} is {} at (i, j) = ({}, {}) ({} non-finite value{} in "
                                 "all); every value must be finite",
                                 file, what, std::isnan(value) ? "NaN" : (value > 0 ? "+Inf" : "-Inf"),
                                 i, j, count, count == 1 ? "" : "s"));
}

// NaN or ±Inf anywhere: the first bad sample, by (i, j) (i along x).
void require_finite(const std::vector<double>& values, const Grid& grid, const std::string& file,
                    const std::string& what) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (std::isfinite(values[k])) continue;
    std::size_t count = 0;
    for (double x : values) count += std::isfinite(x) ? 0 : 1;
    fail_non_finite(grid, file, what, k, values[k], count);
  }
}

// ------------------------------------------------------------------ reading images

// Channel index of each requested field in an image with these channel names.
std::map<Field, int> locate_channels(const std::string& file, StoredFormat format,
                                     const OIIO::ImageSpec& spec,
                                     const std::map<Field, std::string>& channels) {
  std::vector<std::string> names(spec.channelnames.begin(), spec.channelnames.end());
  bool named_by_swell = false;
  if (format == StoredFormat::tiff) {
    const std::string description = spec.get_string_attribute("ImageDescription");
    if (description.rfind(kTiffChannelsPrefix, 0) == 0) {
      std::vector<std::string> stored;
      std::istringstream words(description.substr(std::strlen(kTiffChannelsPrefix)));
      for (std::string word; words >> word;) stored.push_back(word);
      if (stored.size() == names.size()) {
        names = stored;
        named_by_swell = true;
      }
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
  if ((format == StoredFormat::tiff || format == StoredFormat::png) && !named_by_swell &&
      found.empty() &&
      static_cast<int>(channels.size()) == spec.nchannels) {
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
                                   file, channel, reference::field_name(field), spec.nchannels,
                                   spec.nchannels == 1 ? "" : "s", list()));
  }
  return found;  // unreachable: some field was missing
}

// The interleaved pixels of one image read, kept by each reading thread from one frame to the
// next: a fresh array per frame (6 MiB at 512² with six float channels, above malloc's mmap
// threshold) was mapped, faulted in page by page and unmapped again on every frame.
struct PixelScratch {
  std::vector<float> f32;
  std::vector<double> f64;
  detail::ExrScratch exr;
};

// Reads the fields of one image into `frame` and returns their unit roundoff. The rounding of
// a field stored as integers: a uniform quantization error of step q = (high − low)/levels,
// variance q²/12, white — as a unit roundoff u relative to the field's rms (the checks'
// rounding budget is u² mean(v²), conventions §Tolerances), u = q/√(12 mean v²).
double read_image_frame(const fs::path& path, StoredFormat format, const Grid& grid,
                        const InputSpec& input, const std::function<bool(Field)>& keep,
                        FieldFrame& frame, PixelScratch& scratch) {
  const std::string file = path.string();
  const auto& channels = input.channels;
  // Keep the bytes of a TIFF or PNG with unassociated alpha as stored (no premultiplication).
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto image = OIIO::ImageInput::open(file, &config);
  if (!image) {
    std::string why = OIIO::geterror();
    if (why.empty()) why = "unknown error";
    throw InvalidInput(fmt::format("{}: cannot read the image: {}", file, why));
  }
  const OIIO::ImageSpec& spec = image->spec();
  if (spec.deep) throw InvalidInput(file + ": deep images are not supported");
  if (spec.width != grid.nx || spec.height != grid.ny || spec.depth != 1) {
    throw InvalidInput(fmt::format("{}: wrong size: {}×{}{} pixels, the case's grid is {}×{} "
                                   "([grid] n)",
                                   file, spec.width, spec.height,
                                   spec.depth != 1 ? fmt::format("×{}", spec.depth) : "", grid.nx,
                                   grid.ny));
  }
  const auto located = locate_channels(file, format, spec, channels);
  const std::size_t count = static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny);
  double roundoff = 0;
  int first = spec.nchannels, last = -1;
  bool all_float = true;
  std::map<Field, double> integer_levels;  // 255 or 65535 for a field stored as integers
  for (const auto& [field, index] : located) {
    const OIIO::TypeDesc type = spec.channelformat(index);
    const std::string& name = spec.channelnames[index];
    const bool has_range = input.value_ranges.count(field) > 0;
    const double u = roundoff_of(type);
    if (u > 0) {
      if (has_range) {
        throw InvalidInput(fmt::format("{}: channel '{}' for {} stores {} floating-point values, "
                                       "which need no [input] value_range (it is for 8- and "
                                       "16-bit integer images); remove it",
                                       file, name, reference::field_name(field), type.c_str()));
      }
      roundoff = std::max(roundoff, u);
      all_float = all_float && type.basetype != OIIO::TypeDesc::DOUBLE;
    } else if (type.basetype == OIIO::TypeDesc::UINT8 || type.basetype == OIIO::TypeDesc::UINT16) {
      const double levels = type.basetype == OIIO::TypeDesc::UINT8 ? 255.0 : 65535.0;
      if (!has_range) {
        throw InvalidInput(fmt::format("{}: channel '{}' for {} stores {}-bit integers, which carry "
                                       "no unit: give [input] value_range = [low, high], the "
                                       "values (metres) that pixel 0 and pixel {} stand for "
                                       "(docs/case_files.md)",
                                       file, name, reference::field_name(field),
                                       levels == 255.0 ? 8 : 16, levels));
      }
      integer_levels[field] = levels;
    } else {
      throw InvalidInput(fmt::format("{}: channel '{}' for {} stores {} values; swell reads "
                                     "floating-point channels (half, float, double) and 8- or "
                                     "16-bit unsigned integers with [input] value_range",
                                     file, name, reference::field_name(field), type.c_str()));
    }
    first = std::min(first, index);
    last = std::max(last, index);
  }
  // Every channel from the first wanted to the last in one read: a compressed file (EXR ZIP
  // blocks hold all channels of 16 scanlines) is then decompressed once, not once per field.
  // Half, float and integer values (OpenImageIO scales 8- and 16-bit integers to [0, 1]) are
  // exact in float, which halves the buffer; double stays double. The whole image in one
  // read: OpenEXR then decodes its blocks on all of its threads (reading bands of ~85 rows
  // instead, to keep the buffer in cache, made gate/512/64 0.15–0.2 s slower).
  const int span = last - first + 1;
  auto read_all = [&](auto* buffer, OIIO::TypeDesc type) {
    const bool ok = image->read_image(0, 0, first, last + 1, type, buffer);
    // OpenImageIO's TIFF reader returns true for a strip it could not read, with the error
    // pending (and garbage in the buffer): an error message counts as a failure too.
    std::string why = image->geterror();
    if (!ok || !why.empty()) {
      if (why.empty()) why = "unknown error";
      std::string names;
      for (int c = first; c <= last; ++c) {
        names += (names.empty() ? "'" : ", '") + spec.channelnames[c] + "'";
      }
      throw InvalidInput(fmt::format("{}: cannot read channel{} {} (truncated or corrupt file?): "
                                     "{}",
                                     file, span == 1 ? "" : "s", names, why));
    }
  };
  // Per field: its values when kept (or stored as integers, whose rms sets the rounding), and
  // its non-finite samples: how many, and the first.
  struct Taken {
    Field field = Field::height;
    std::size_t offset = 0;
    bool kept = true;
    const IntegerRange* range = nullptr;
    double levels = 0;
    std::vector<double> values;
    std::size_t bad = 0, first_bad = 0;
    double first_bad_value = 0;
  };
  std::vector<Taken> taken;
  for (const auto& [field, index] : located) {
    Taken t;
    t.field = field;
    t.offset = static_cast<std::size_t>(index - first);
    t.kept = !keep || keep(field);
    if (const auto levels = integer_levels.find(field); levels != integer_levels.end()) {
      t.range = &input.value_ranges.at(field);
      t.levels = levels->second;
    }
    if (t.kept || t.range) t.values.resize(count);
    taken.push_back(std::move(t));
  }
  auto take = [&](auto& buffer, OIIO::TypeDesc type) {
    buffer.resize(count * span);
    read_all(buffer.data(), type);
    for (Taken& t : taken) {
      const auto* pixels = buffer.data() + t.offset;
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
  };
  // A scanline EXR goes from its blocks straight into the fields, a line at a time
  // (exr_scanlines.hpp: 11 ms a frame of 512² with six float channels, against ~40 ms through
  // OpenImageIO, one thread each); whatever that reader does not take, OpenImageIO
  // reads whole below.
  bool direct = false;
  if (format == StoredFormat::exr && all_float && integer_levels.empty()) {
    std::vector<std::string> names;  // taken[k]'s channel is names[k]
    for (const auto& [field, index] : located) names.push_back(spec.channelnames[index]);
    const std::size_t width = std::size_t(grid.nx);
    direct = detail::read_exr_scanlines(
        file, names, grid.nx, grid.ny,
        [&](std::size_t slot, std::size_t row, const float* values) {
          Taken& t = taken[slot];
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
        scratch.exr);
    if (!direct) {
      for (Taken& t : taken) t.bad = 0;  // counted again by the read below
    }
  }
  if (!direct && all_float) take(scratch.f32, OIIO::TypeDesc::FLOAT);
  if (!direct && !all_float) take(scratch.f64, OIIO::TypeDesc::DOUBLE);
  image->close();
  for (Taken& t : taken) {
    if (t.bad > 0) {
      fail_non_finite(grid, file, describe_field(t.field, channels.at(t.field)), t.first_bad,
                      t.first_bad_value, t.bad);
    }
    if (t.range) roundoff = std::max(roundoff, quantization_roundoff(*t.range, t.levels, t.values));
    if (t.kept) frame.fields[t.field] = std::move(t.values);
  }
  return roundoff;
}

// ------------------------------------------------------------------ reading arrays

// `lattice`: the case samples a lattice of grid.nx points (grid.ny = 1), one (N,) array a field.
double read_npy_field(const fs::path& path, const Grid& grid, Field field, FieldFrame& frame,
                      bool lattice = false) {
  const std::string file = path.string();
  const NpyArray array = read_npy(path);  // names the file and the problem
  const std::vector<std::size_t> want =
      lattice ? std::vector<std::size_t>{static_cast<std::size_t>(grid.nx)}
              : std::vector<std::size_t>{static_cast<std::size_t>(grid.ny),
                                         static_cast<std::size_t>(grid.nx)};
  if (array.shape != want) {
    if (lattice) {
      throw InvalidInput(fmt::format("{}: wrong shape {}: the case's lattice needs (N,) = {} "
                                     "([sampling] points = {})",
                                     file, shape_string(array.shape), shape_string(want), grid.nx));
    }
    throw InvalidInput(fmt::format("{}: wrong shape {}: the case's grid needs (ny, nx) = {} "
                                   "([grid] n = [{}, {}])",
                                   file, shape_string(array.shape), shape_string(want), grid.nx,
                                   grid.ny));
  }
  const std::string what = reference::field_name(field);
  std::vector<double> real, imaginary;
  double roundoff = kDoubleRoundoff;
  auto split = [&](const auto& values) {
    real.reserve(values.size());
    imaginary.reserve(values.size());
    for (const auto& z : values) {
      real.push_back(static_cast<double>(z.real()));
      imaginary.push_back(static_cast<double>(z.imag()));
    }
  };
  switch (array.dtype) {
    case NpyArray::Dtype::f4: {
      const auto values = array.values<float>();
      real.assign(values.begin(), values.end());
      roundoff = kFloatRoundoff;
      break;
    }
    case NpyArray::Dtype::f8: real = array.values<double>(); break;
    case NpyArray::Dtype::c8:
      split(array.values<std::complex<float>>());
      roundoff = kFloatRoundoff;
      break;
    case NpyArray::Dtype::c16: split(array.values<std::complex<double>>()); break;
  }
  require_finite(real, grid, file, what + (array.is_complex() ? " (real part)" : ""));
  frame.fields[field] = std::move(real);
  if (array.is_complex()) {
    require_finite(imaginary, grid, file, what + " (imaginary part)");
    frame.imaginary[field] = std::move(imaginary);
  }
  return roundoff;
}

double read_raw_field(const fs::path& path, const Grid& grid, Field field,
                      const std::string& raw_type, FieldFrame& frame) {
  const std::string file = path.string();
  const bool is_double = raw_type == "float64";
  if (!is_double && raw_type != "float32") {
    throw InvalidInput(fmt::format("{}: raw_type \"{}\" is not float32 or float64", file, raw_type));
  }
  const std::size_t item = is_double ? 8 : 4;
  const std::size_t count = static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny);
  std::error_code error;
  if (!fs::is_regular_file(path, error)) throw InvalidInput(file + ": not a regular file");
  const auto size = fs::file_size(path, error);
  if (error) throw InvalidInput(file + ": cannot determine the file size: " + error.message());
  if (size != count * item) {
    throw InvalidInput(fmt::format("{}: wrong size: {} bytes, expected ny·nx·{} = {}·{}·{} = {} "
                                   "({} little-endian, [grid] n = [{}, {}])",
                                   file, size, item, grid.ny, grid.nx, item, count * item,
                                   raw_type, grid.nx, grid.ny));
  }
  std::ifstream stream(path, std::ios::binary);
  std::vector<unsigned char> bytes(count * item);
  if (!stream || !stream.read(reinterpret_cast<char*>(bytes.data()),
                              static_cast<std::streamsize>(bytes.size()))) {
    throw InvalidInput(file + ": read error");
  }
  // The bytes are little-endian, as the machine (npy.hpp asserts it).
  std::vector<double> values(count);
  for (std::size_t k = 0; k < count; ++k) {
    if (is_double) {
      std::memcpy(&values[k], bytes.data() + k * 8, 8);
    } else {
      float x;
      std::memcpy(&x, bytes.data() + k * 4, 4);
      values[k] = x;
    }
  }
  require_finite(values, grid, file, reference::field_name(field));
  frame.fields[field] = std::move(values);
  return is_double ? kDoubleRoundoff : kFloatRoundoff;
}

// ------------------------------------------------------------------ writing

std::string extension_of(FrameFormat format) {
  switch (format) {
    case FrameFormat::exr: return ".exr";
    case FrameFormat::npy: return ".npy";
    case FrameFormat::tiff: return ".tif";
    case FrameFormat::png: return ".png";
  }
  return "";
}

constexpr const char* kWritePattern = "frame_%04d";

// PNG holds 1 to 4 channels, named by their count as OpenImageIO reads them back.
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
  const bool png = options.format == FrameFormat::png;
  auto output = OIIO::ImageOutput::create(file);
  if (!output) {
    throw InvalidInput(fmt::format("{}: cannot write: {}", file, OIIO::geterror()));
  }
  const int channels = static_cast<int>(fields.size());
  const OIIO::TypeDesc type = !png                   ? OIIO::TypeDesc::FLOAT
                             : options.png_bits == 8 ? OIIO::TypeDesc::UINT8
                                                     : OIIO::TypeDesc::UINT16;
  const double top = options.png_bits == 8 ? 255.0 : 65535.0;
  OIIO::ImageSpec spec(grid.nx, grid.ny, channels, type);
  spec.channelnames.clear();
  std::string names;
  const auto png_names = png ? png_channel_names(fields.size()) : std::vector<std::string>{};
  for (std::size_t c = 0; c < fields.size(); ++c) {
    spec.channelnames.push_back(png ? png_names[c] : reference::channel_name(fields[c]));
    names += " " + reference::channel_name(fields[c]);
  }
  spec.alpha_channel = -1;  // no channel is alpha: nothing may be premultiplied
  if (!png) spec.attribute("compression", "zip");  // lossless in both formats
  if (options.format == FrameFormat::tiff) {
    spec.attribute("ImageDescription", kTiffChannelsPrefix + names);
  }
  spec.attribute("Software", "swell");
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
  if (!output->open(file, spec)) {
    throw InvalidInput(fmt::format("{}: cannot write: {}", file, output->geterror()));
  }
  auto pixel_of = [&](double v) -> std::uint16_t {
    const double p = pixel(v);  // in [0, top]: checked above
    return static_cast<std::uint16_t>(top == 255.0 ? p * 257 : p);
  };
  // Interleaved rows, a block at a time, so that a large frame never needs a second copy.
  const std::size_t nx = static_cast<std::size_t>(grid.nx);
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
    const bool ok = png ? output->write_scanlines(y0, y1, 0, OIIO::TypeDesc::UINT16, pixels.data())
                        : output->write_scanlines(y0, y1, 0, type, block.data());
    if (!ok) throw InvalidInput(fmt::format("{}: write failed: {}", file, output->geterror()));
  }
  if (!output->close()) {
    throw InvalidInput(fmt::format("{}: write failed: {}", file, output->geterror()));
  }
  return {path};
}

// A grid's field as a (ny, nx) array; a lattice's (grid.ny == 0, the case's own grid) as (N,).
template <typename Real>
NpyArray npy_of(const Grid& grid, const std::vector<double>& real, const std::vector<double>* imaginary) {
  const std::vector<std::size_t> shape =
      grid.ny == 0 ? std::vector<std::size_t>{real.size()}
                   : std::vector<std::size_t>{static_cast<std::size_t>(grid.ny),
                                              static_cast<std::size_t>(grid.nx)};
  if (imaginary) {
    std::vector<std::complex<Real>> values(real.size());
    for (std::size_t k = 0; k < real.size(); ++k) {
      values[k] = {static_cast<Real>(real[k]), static_cast<Real>((*imaginary)[k])};
    }
    return NpyArray::from_values(shape, values);
  }
  std::vector<Real> values(real.begin(), real.end());
  return NpyArray::from_values(shape, values);
}

}  // namespace

double quantization_roundoff(const IntegerRange& range, double levels,
                             const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v * v;
  const double rms = std::sqrt(sum / double(std::max<std::size_t>(1, values.size())));
  const double step = (range.high - range.low) / levels;
  return rms > 0 ? std::min(1.0, step / std::sqrt(12.0) / rms) : 1.0;
}


FrameFormat frame_format_from_string(const std::string& name) {
  if (name == "exr") return FrameFormat::exr;
  if (name == "npy") return FrameFormat::npy;
  if (name == "tiff" || name == "tif") return FrameFormat::tiff;
  if (name == "png") return FrameFormat::png;
  throw InvalidInput("unknown frame format '" + name + "'; valid: exr, npy, tiff, png");
}

std::string to_string(FrameFormat format) {
  switch (format) {
    case FrameFormat::exr: return "exr";
    case FrameFormat::npy: return "npy";
    case FrameFormat::tiff: return "tiff";
    case FrameFormat::png: return "png";
  }
  return "?";
}

std::string frame_file_name(const std::string& pattern, int index, const std::string& suffix) {
  return with_suffix(expand(parse_pattern(pattern), index), suffix);
}

InputSpec frame_input_spec(const std::vector<Field>& fields, const FrameWriteOptions& options) {
  InputSpec spec;
  spec.files = std::string(kWritePattern) + extension_of(options.format);
  if (options.format != FrameFormat::png) {
    for (Field field : fields) spec.channels[field] = reference::channel_name(field);
    return spec;
  }
  // In swell's field order, as write_image_frame stores them.
  std::vector<Field> ordered;
  for (Field field : reference::kAllFields) {
    if (std::find(fields.begin(), fields.end(), field) != fields.end()) ordered.push_back(field);
  }
  const auto names = png_channel_names(ordered.size());
  for (std::size_t c = 0; c < ordered.size(); ++c) {
    spec.channels[ordered[c]] = names[c];
    spec.value_ranges[ordered[c]] = options.png_range;
  }
  return spec;
}

std::vector<fs::path> write_frame(const fs::path& directory, const Grid& grid,
                                  const FieldFrame& frame, int index,
                                  const FrameWriteOptions& options) {
  if (index < 0) throw InvalidInput(fmt::format("frame index {} is negative", index));
  if (frame.fields.empty()) throw InvalidInput(fmt::format("frame {} has no fields to write", index));
  // A lattice's frame (grid.nx = grid.ny = 0, reference::FrameSequence) is one array of the
  // N points a field, only as .npy: an image needs a grid.
  const bool lattice = grid.nx == 0 && grid.ny == 0;
  if (lattice && options.format != FrameFormat::npy) {
    throw InvalidInput(fmt::format("lattice frames are written as .npy (one array of the N "
                                   "points per field); {} images need a grid",
                                   to_string(options.format)));
  }
  const std::size_t count = lattice ? frame.fields.begin()->second.size()
                                    : static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny);
  std::vector<Field> fields;
  for (Field field : reference::kAllFields) {
    const auto it = frame.fields.find(field);
    if (it == frame.fields.end()) continue;
    if (it->second.size() != count) {
      throw InvalidInput(fmt::format("frame {}: {} holds {} values, the {}×{} grid needs {}", index,
                                     reference::field_name(field), it->second.size(), grid.nx,
                                     grid.ny, count));
    }
    const auto im = frame.imaginary.find(field);
    if (im != frame.imaginary.end() && im->second.size() != count) {
      throw InvalidInput(fmt::format("frame {}: the imaginary part of {} holds {} values, the "
                                     "{}×{} grid needs {}",
                                     index, reference::field_name(field), im->second.size(),
                                     grid.nx, grid.ny, count));
    }
    fields.push_back(field);
  }
  if (options.format == FrameFormat::png) {
    require_png_options(options);
    (void)png_channel_names(fields.size());  // at most 4 fields
  }
  if (options.format != FrameFormat::npy) {
    if (options.float64) {
      throw InvalidInput("float64 frames are written as .npy only (EXR and TIFF frames are "
                         "float32, PNG frames 16-bit integers)");
    }
    if (!frame.imaginary.empty()) {
      throw InvalidInput(fmt::format("frame {} carries imaginary parts, which {} channels cannot "
                                     "hold; write .npy (complex) instead",
                                     index, to_string(options.format)));
    }
  }
  std::error_code error;
  fs::create_directories(directory, error);
  if (error) {
    throw InvalidInput(fmt::format("{}: cannot create the directory: {}", directory.string(),
                                   error.message()));
  }

  const std::string name = frame_file_name(std::string(kWritePattern) + extension_of(options.format), index);
  if (options.format != FrameFormat::npy) {
    return write_image_frame(directory / name, grid, fields, frame, options);
  }
  std::vector<fs::path> written;
  for (Field field : fields) {
    const fs::path path = directory / with_suffix(name, reference::channel_name(field));
    const auto im = frame.imaginary.find(field);
    const std::vector<double>* imaginary = im == frame.imaginary.end() ? nullptr : &im->second;
    const auto& real = frame.fields.at(field);
    write_npy(path, options.float64 ? npy_of<double>(grid, real, imaginary)
                                    : npy_of<float>(grid, real, imaginary));
    written.push_back(path);
  }
  return written;
}

InputSpec write_frames(const fs::path& directory, const FrameSequence& frames,
                       const FrameWriteOptions& options) {
  if (frames.frames.empty()) throw InvalidInput("no frames to write");
  std::vector<Field> fields;
  for (const auto& [field, values] : frames.frames.front().fields) fields.push_back(field);
  for (std::size_t f = 0; f < frames.frames.size(); ++f) {
    const auto& frame = frames.frames[f];
    std::vector<Field> here;
    for (const auto& [field, values] : frame.fields) here.push_back(field);
    if (here != fields) {
      throw InvalidInput(fmt::format("frame {} has other fields than frame 0; every frame must "
                                     "carry the same fields",
                                     f));
    }
    write_frame(directory, frames.grid, frame, static_cast<int>(f), options);
  }
  return frame_input_spec(fields, options);
}

reference::FrameSequence read_frames(const CaseFile& case_file, const std::string& pattern_override,
                                     const FieldFilter& keep) {
  const auto& ocean = case_file.ocean;
  const auto& input = case_file.input;
  const std::string origin = pattern_override.empty() ? "[input] files" : "--input";
  if (pattern_override.empty() && input.files.empty()) {
    throw InvalidInput("the case has no frames to read: give [input] files = \"frame_%04d.exr\" "
                       "(or an input pattern on the command line)");
  }
  if (input.channels.empty()) {
    throw InvalidInput("the case's [input] names no field: give at least one of height, slope_x, "
                       "slope_y, disp_x, disp_y, jacobian with its channel or file suffix");
  }
  for (const auto& [field, range] : input.value_ranges) {
    if (!input.channels.count(field)) {
      throw InvalidInput(fmt::format("[input] value_range gives a range for {}, which [input] does "
                                     "not provide",
                                     reference::field_name(field)));
    }
  }
  // OpenImageIO's EXR reader on OpenEXRCore: the classic one converts each float of an
  // interleaved multi-channel read byte by byte (Xdr), which made reading six fields of 64
  // frames of 512² take 0.4 s of CPU more than reading one; through the core it costs about
  // the same as one field (bench gate/512/64).
  static const bool use_openexr_core = OIIO::attribute("openexr:core", 1);
  (void)use_openexr_core;
  const std::string pattern =
      pattern_override.empty() ? (case_file.directory / input.files).string() : pattern_override;
  const StoredFormat format = stored_format_of(pattern, origin);
  Pattern parsed;
  try {
    parsed = parse_pattern(pattern);
  } catch (const InvalidInput& e) {
    throw InvalidInput(origin + ": " + e.what());
  }
  if (!parsed.has_conversion && ocean.frames > 1) {
    throw InvalidInput(fmt::format("{}: \"{}\" has no frame number (such as %04d) but the case has "
                                   "{} frames ([time] frames)",
                                   origin, pattern, ocean.frames));
  }
  // A lattice's N points are read as one row of N samples.
  const bool lattice = ocean.is_lattice();
  const Grid grid = lattice ? Grid{static_cast<int>(ocean.lattice->points()), 1, ocean.grid.lx,
                                   ocean.grid.ly}
                            : ocean.grid;
  if (lattice && format != StoredFormat::npy && format != StoredFormat::raw) {
    throw InvalidInput(fmt::format("{}: \"{}\": a lattice case reads .npy or .raw frames (one "
                                   "array of the N points per field); images need a grid",
                                   origin, pattern));
  }
  auto file_of = [&](int f, Field field) {
    return fs::path(with_suffix(expand(parsed, f),
                                one_file_per_field(format) ? input.channels.at(field) : ""));
  };

  FrameSequence sequence;
  sequence.grid = ocean.grid;
  sequence.lattice = ocean.lattice;
  const Field first_field = input.channels.begin()->first;
  auto read_frame = [&](int f, FieldFrame& frame, PixelScratch& scratch) {
    double roundoff = 0;
    const std::function<bool(Field)> keep_here = [&](Field field) { return !keep || keep(f, field); };
    frame.time = ocean.time(f);
    for (const auto& [field, channel] : input.channels) {
      if (!one_file_per_field(format) && field != first_field) break;  // one file for all fields
      const fs::path path = file_of(f, field);
      std::error_code error;
      if (!fs::exists(path, error)) {
        throw InvalidInput(fmt::format("{}: missing frame file (frame {} of {}{})", path.string(), f,
                                       ocean.frames,
                                       one_file_per_field(format)
                                           ? ", " + reference::field_name(field)
                                           : std::string()));
      }
      if (fs::is_directory(path, error)) {
        throw InvalidInput(path.string() + ": is a directory, not a frame file");
      }
      double u = 0;
      switch (format) {
        case StoredFormat::exr:
        case StoredFormat::tiff:
        case StoredFormat::png:
          u = read_image_frame(path, format, grid, input, keep_here, frame, scratch);
          break;
        case StoredFormat::npy: u = read_npy_field(path, grid, field, frame, lattice); break;
        case StoredFormat::raw: u = read_raw_field(path, grid, field, input.raw_type, frame); break;
      }
      roundoff = std::max(roundoff, u);
    }
    // One file per field: each was read whole (and checked); drop those not wanted.
    for (const auto& [field, channel] : input.channels) {
      if (!keep_here(field)) {
        frame.fields.erase(field);
        frame.imaginary.erase(field);
      }
    }
    return roundoff;
  };
  // Frames are independent files: read on as many threads as OpenImageIO's "threads"
  // attribute says (default: every hardware thread; swell gate --threads sets it), each thread
  // taking every T-th frame. The error reported is that of the lowest frame that failed, as a
  // sequential read would report it.
  int threads = 1;
  OIIO::getattribute("threads", threads);
  threads = std::clamp(threads, 1, std::max(1, ocean.frames));
  sequence.frames.resize(static_cast<std::size_t>(ocean.frames));
  std::vector<double> roundoffs(sequence.frames.size(), 0.0);
  std::vector<std::exception_ptr> errors(sequence.frames.size());
  auto work = [&](int first) {
    PixelScratch scratch;
    for (int f = first; f < ocean.frames; f += threads) {
      try {
        roundoffs[f] = read_frame(f, sequence.frames[f], scratch);
      } catch (...) {
        errors[f] = std::current_exception();
        return;  // this thread's later frames would only fail after the same one
      }
    }
  };
  if (threads == 1) {
    work(0);
  } else {
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
    work(0);
    for (auto& thread : pool) thread.join();
  }
  for (const auto& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  const double roundoff = *std::max_element(roundoffs.begin(), roundoffs.end());
  // More frames on disk than the case says: the case and the files disagree.
  if (parsed.has_conversion) {
    const fs::path next = file_of(ocean.frames, first_field);
    std::error_code error;
    if (fs::exists(next, error)) {
      throw InvalidInput(fmt::format("{}: a frame beyond the case's {} ([time] frames = {}): the "
                                     "files hold more frames than the case says",
                                     next.string(), ocean.frames, ocean.frames));
    }
  }
  sequence.unit_roundoff = roundoff;
  return sequence;
}

}  // namespace swell::validation
