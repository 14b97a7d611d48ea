// Frames on disk (docs/case_files.md §Frames): images (EXR, TIFF, PNG) through
// image_frames.hpp, .npy through npy.hpp, headerless .raw; file patterns and frame sequences.
// Readers check everything against the case and name the file.
#include "swell/validation/io/frame_io.hpp"

#include "swell/validation/io/half.hpp"

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

#include "common/parallel_tasks.hpp"
#include "image_frames.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/io/npy.hpp"

namespace swell::validation {
namespace {

namespace fs = std::filesystem;
using reference::Field;
using reference::FieldFrame;
using reference::FrameSequence;
using reference::Grid;

using detail::fail_non_finite;
using detail::kDoubleRoundoff;
using detail::kFloatRoundoff;
using detail::kHalfRoundoff;

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

detail::ImageKind image_kind_of(StoredFormat format) {
  return format == StoredFormat::exr    ? detail::ImageKind::exr
         : format == StoredFormat::tiff ? detail::ImageKind::tiff
                                        : detail::ImageKind::png;
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

// ------------------------------------------------------------------ reading arrays

// `lattice`: the case samples a lattice of grid.nx points (grid.ny = 1), one (N,) array a field.
// `file` names the array in messages: the .npy file, or the array handed over in memory.
double npy_field(const NpyArray& array, const std::string& file, const Grid& grid, Field field,
                 FieldFrame& frame, bool lattice) {
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
    case NpyArray::Dtype::f2:
      real = half_values(array);
      roundoff = kHalfRoundoff;
      break;
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

double read_npy_field(const fs::path& path, const Grid& grid, Field field, FieldFrame& frame,
                      bool lattice = false) {
  // read_npy names the file and the problem.
  return npy_field(read_npy(path), path.string(), grid, field, frame, lattice);
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

bool all_half_values(const FieldFrame& frame) {
  for (const auto* part : {&frame.fields, &frame.imaginary}) {
    for (const auto& [field, values] : *part) {
      if (!std::all_of(values.begin(), values.end(), is_half_value)) return false;
    }
  }
  return true;
}

FramePrecision storage_precision(double stored, bool all_halves, const std::string& declared,
                                 const std::string& origin) {
  const bool floating = stored == kHalfRoundoff || stored == kFloatRoundoff || stored == kDoubleRoundoff;
  const FramePrecision half{kFloatRoundoff, kHalfUlp};
  if (declared.empty()) {
    if (stored == kHalfRoundoff || (stored == kFloatRoundoff && all_halves)) return half;
    return {stored, 0};
  }
  if (!floating) {
    throw InvalidInput(fmt::format("{}: [input] precision = \"{}\" applies to floating-point "
                                   "frames; these are stored as integers (their value_range sets "
                                   "their rounding)",
                                   origin, declared));
  }
  const double declared_roundoff = declared == "half"    ? kHalfRoundoff
                                   : declared == "float" ? kFloatRoundoff
                                                         : kDoubleRoundoff;
  if (declared_roundoff < stored) {
    throw InvalidInput(fmt::format("{}: [input] precision = \"{}\", but the frames are stored in {}, "
                                   "which cannot hold {} values",
                                   origin, declared,
                                   stored == kHalfRoundoff ? "half" : "float", declared));
  }
  if (declared == "half") return half;
  return {declared_roundoff, 0};
}

namespace {

void set_storage_precision(FrameSequence& sequence, double stored, const std::string& declared,
                           const std::string& origin) {
  // Whether every value is a half matters only for undeclared float frames: scanned only then.
  const bool scan = declared.empty() && stored == kFloatRoundoff;
  const bool halves = scan && std::all_of(sequence.frames.begin(), sequence.frames.end(), all_half_values);
  const FramePrecision precision = storage_precision(stored, halves, declared, origin);
  sequence.unit_roundoff = precision.unit_roundoff;
  sequence.storage_roundoff = precision.storage_roundoff;
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


reference::FrameSequence frames_from_arrays(const reference::OceanCase& ocean,
                                            const std::string& declared_precision,
                                            const std::map<Field, std::vector<NpyArray>>& arrays) {
  if (arrays.empty()) {
    throw InvalidInput("no field given: give at least one of height, slope_x, slope_y, disp_x, "
                       "disp_y, jacobian");
  }
  const bool lattice = ocean.is_lattice();
  const Grid grid = lattice ? Grid{static_cast<int>(ocean.lattice->points()), 1, ocean.grid.lx,
                                   ocean.grid.ly}
                            : ocean.grid;
  FrameSequence sequence;
  sequence.grid = ocean.grid;
  sequence.lattice = ocean.lattice;
  sequence.frames.resize(static_cast<std::size_t>(ocean.frames));
  double roundoff = 0;
  for (const auto& [field, frames] : arrays) {
    const std::string name = reference::field_name(field);
    if (frames.size() != sequence.frames.size()) {
      throw InvalidInput(fmt::format("{}: {} frame{} where the case has [time] frames = {}", name,
                                     frames.size(), frames.size() == 1 ? "" : "s", ocean.frames));
    }
    for (std::size_t f = 0; f < frames.size(); ++f) {
      sequence.frames[f].time = ocean.time(int(f));
      const std::string source =
          frames.size() == 1 ? name : fmt::format("{}, frame {}", name, f);
      roundoff = std::max(roundoff, npy_field(frames[f], source, grid, field, sequence.frames[f], lattice));
    }
  }
  set_storage_precision(sequence, roundoff, declared_precision, "the arrays");
  return sequence;
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
  const auto names = detail::png_channel_names(ordered.size());
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
    detail::require_png_options(options);
    (void)detail::png_channel_names(fields.size());  // at most 4 fields
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
    return detail::write_image_frame(directory / name, grid, fields, frame, options);
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

struct FrameFileReader::Layout {
  std::string origin, pattern;
  StoredFormat format = StoredFormat::exr;
  Pattern parsed;
  Grid grid;  // a lattice's N points as one row
  bool lattice = false;
  Field first_field = Field::height;
};

FrameReadScratch::FrameReadScratch() : pixels_(std::make_unique<detail::PixelScratch>()) {}
FrameReadScratch::~FrameReadScratch() = default;

FrameFileReader::FrameFileReader(const CaseFile& case_file, const std::string& pattern_override,
                                 int threads_per_file)
    : ocean_(case_file.ocean), input_(case_file.input), layout_(std::make_shared<Layout>()),
      threads_per_file_(std::max(1, threads_per_file)) {
  Layout& l = *layout_;
  l.origin = pattern_override.empty() ? "[input] files" : "--input";
  if (pattern_override.empty() && input_.files.empty()) {
    throw InvalidInput("the case has no frames to read: give [input] files = \"frame_%04d.exr\" "
                       "(or an input pattern on the command line)");
  }
  if (input_.channels.empty()) {
    throw InvalidInput("the case's [input] names no field: give at least one of height, slope_x, "
                       "slope_y, disp_x, disp_y, jacobian with its channel or file suffix");
  }
  for (const auto& [field, range] : input_.value_ranges) {
    if (!input_.channels.count(field)) {
      throw InvalidInput(fmt::format("[input] value_range gives a range for {}, which [input] does "
                                     "not provide",
                                     reference::field_name(field)));
    }
  }
  l.pattern = pattern_override.empty() ? (case_file.directory / input_.files).string() : pattern_override;
  l.format = stored_format_of(l.pattern, l.origin);
  try {
    l.parsed = parse_pattern(l.pattern);
  } catch (const InvalidInput& e) {
    throw InvalidInput(l.origin + ": " + e.what());
  }
  if (!l.parsed.has_conversion && ocean_.frames > 1) {
    throw InvalidInput(fmt::format("{}: \"{}\" has no frame number (such as %04d) but the case has "
                                   "{} frames ([time] frames)",
                                   l.origin, l.pattern, ocean_.frames));
  }
  l.lattice = ocean_.is_lattice();
  l.grid = l.lattice ? Grid{static_cast<int>(ocean_.lattice->points()), 1, ocean_.grid.lx, ocean_.grid.ly}
                     : ocean_.grid;
  if (l.lattice && l.format != StoredFormat::npy && l.format != StoredFormat::raw) {
    throw InvalidInput(fmt::format("{}: \"{}\": a lattice case reads .npy or .raw frames (one "
                                   "array of the N points per field); images need a grid",
                                   l.origin, l.pattern));
  }
  l.first_field = input_.channels.begin()->first;
}

FrameFileReader::~FrameFileReader() = default;

int FrameFileReader::frames() const { return ocean_.frames; }
const std::string& FrameFileReader::origin() const { return layout_->origin; }

FrameSequence FrameFileReader::empty_sequence() const {
  FrameSequence sequence;
  sequence.grid = ocean_.grid;
  sequence.lattice = ocean_.lattice;
  return sequence;
}

fs::path FrameFileReader::file_of(int f, Field field) const {
  const Layout& l = *layout_;
  return fs::path(with_suffix(expand(l.parsed, f),
                              one_file_per_field(l.format) ? input_.channels.at(field) : ""));
}

double FrameFileReader::read(int f, FieldFrame& frame, FrameReadScratch& scratch,
                             const FieldFilter& keep) const {
  const Layout& l = *layout_;
  double roundoff = 0;
  const std::function<bool(Field)> keep_here = [&](Field field) { return !keep || keep(f, field); };
  frame.time = ocean_.time(f);
  // Each field read replaces its values; the arrays of a frame read before are reused
  // (image_frames.cpp) and the fields not read dropped below.
  frame.imaginary.clear();
  for (const auto& [field, channel] : input_.channels) {
    if (!one_file_per_field(l.format) && field != l.first_field) break;  // one file for all fields
    const fs::path path = file_of(f, field);
    std::error_code error;
    if (!fs::exists(path, error)) {
      throw InvalidInput(fmt::format("{}: missing frame file (frame {} of {}{})", path.string(), f,
                                     ocean_.frames,
                                     one_file_per_field(l.format)
                                         ? ", " + reference::field_name(field)
                                         : std::string()));
    }
    if (fs::is_directory(path, error)) {
      throw InvalidInput(path.string() + ": is a directory, not a frame file");
    }
    double u = 0;
    switch (l.format) {
      case StoredFormat::exr:
      case StoredFormat::tiff:
      case StoredFormat::png:
        u = detail::read_image_frame(path, image_kind_of(l.format), l.grid, input_, keep_here, frame,
                                     scratch.pixels(), threads_per_file_);
        break;
      case StoredFormat::npy: u = read_npy_field(path, l.grid, field, frame, l.lattice); break;
      case StoredFormat::raw: u = read_raw_field(path, l.grid, field, input_.raw_type, frame); break;
    }
    roundoff = std::max(roundoff, u);
  }
  // One file per field: each was read whole (and checked); drop those not wanted, and any a
  // frame read before into `frame` held.
  std::erase_if(frame.fields, [&](const auto& entry) {
    return !input_.channels.count(entry.first) || !keep_here(entry.first);
  });
  std::erase_if(frame.imaginary, [&](const auto& entry) {
    return !input_.channels.count(entry.first) || !keep_here(entry.first);
  });
  return roundoff;
}

void FrameFileReader::require_no_extra_frame() const {
  // More frames on disk than the case says: the case and the files disagree.
  if (!layout_->parsed.has_conversion) return;
  const fs::path next = file_of(ocean_.frames, layout_->first_field);
  std::error_code error;
  if (fs::exists(next, error)) {
    throw InvalidInput(fmt::format("{}: a frame beyond the case's {} ([time] frames = {}): the "
                                   "files hold more frames than the case says",
                                   next.string(), ocean_.frames, ocean_.frames));
  }
}

FramePrecision FrameFileReader::precision(double stored, bool all_halves) const {
  return storage_precision(stored, all_halves, input_.precision, layout_->origin);
}

bool FrameFileReader::needs_half_scan(double stored) const {
  return input_.precision.empty() && stored == kFloatRoundoff;
}

reference::FrameSequence read_frames(const CaseFile& case_file, const std::string& pattern_override,
                                     const FieldFilter& keep, int threads) {
  const auto& ocean = case_file.ocean;
  // Frames are independent files: read on `threads` threads (0: every hardware thread), each
  // taking every T-th frame; what threads are left over decode within a file. The error
  // reported is that of the lowest frame that failed, as a sequential read would report it.
  const int all_threads = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  const int reading_threads = std::clamp(all_threads, 1, std::max(1, ocean.frames));
  const FrameFileReader reader(case_file, pattern_override, std::max(1, all_threads / reading_threads));
  FrameSequence sequence = reader.empty_sequence();
  sequence.frames.resize(static_cast<std::size_t>(ocean.frames));
  std::vector<double> roundoffs(sequence.frames.size(), 0.0);
  std::vector<std::exception_ptr> errors(sequence.frames.size());
  // One task per reading thread, each with its own decoding scratch, taking every T-th frame.
  detail::run_tasks(std::size_t(reading_threads), reading_threads, [&](std::size_t first) {
    FrameReadScratch scratch;
    for (int f = int(first); f < ocean.frames; f += reading_threads) {
      try {
        roundoffs[f] = reader.read(f, sequence.frames[f], scratch, keep);
      } catch (...) {
        errors[f] = std::current_exception();
        return;  // this thread's later frames would only fail after the same one
      }
    }
  });
  for (const auto& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  const double roundoff = *std::max_element(roundoffs.begin(), roundoffs.end());
  reader.require_no_extra_frame();
  set_storage_precision(sequence, roundoff, case_file.input.precision, reader.origin());
  return sequence;
}

}  // namespace swell::validation
