// libswell_openimageio.so: image_module.hpp's table over OpenImageIO. Loaded by image_module()
// on first use; nothing of swell is linked in.
#include <OpenImageIO/imageio.h>

#include "image_module.hpp"

namespace swell::validation::detail {
namespace {

SampleType sample_type_of(OIIO::TypeDesc type) {
  switch (type.basetype) {
    case OIIO::TypeDesc::UINT8: return SampleType::uint8;
    case OIIO::TypeDesc::UINT16: return SampleType::uint16;
    case OIIO::TypeDesc::HALF: return SampleType::half;
    case OIIO::TypeDesc::FLOAT: return SampleType::float32;
    case OIIO::TypeDesc::DOUBLE: return SampleType::float64;
    default: return SampleType::other;
  }
}

OIIO::TypeDesc type_desc_of(SampleType type) {
  switch (type) {
    case SampleType::uint8: return OIIO::TypeDesc::UINT8;
    case SampleType::uint16: return OIIO::TypeDesc::UINT16;
    case SampleType::half: return OIIO::TypeDesc::HALF;
    case SampleType::float32: return OIIO::TypeDesc::FLOAT;
    case SampleType::float64: return OIIO::TypeDesc::DOUBLE;
    case SampleType::other: break;
  }
  return OIIO::TypeDesc::UNKNOWN;
}

std::string pending_error(std::string why) { return why.empty() ? "unknown error" : why; }

class Reader final : public ImageReader {
 public:
  Reader(std::unique_ptr<OIIO::ImageInput> image) : image_(std::move(image)) {
    const OIIO::ImageSpec& spec = image_->spec();
    header_.width = spec.width;
    header_.height = spec.height;
    header_.depth = spec.depth;
    header_.deep = spec.deep;
    for (int c = 0; c < spec.nchannels; ++c) {
      header_.channel_names.push_back(spec.channelnames[std::size_t(c)]);
      header_.channel_types.push_back(sample_type_of(spec.channelformat(c)));
      header_.channel_type_names.push_back(spec.channelformat(c).c_str());
    }
    header_.description = spec.get_string_attribute("ImageDescription");
  }
  ~Reader() override { image_->close(); }

  const ImageHeader& header() const override { return header_; }

  std::string read(int first, int last, SampleType type, void* pixels) override {
    const bool ok = image_->read_image(0, 0, first, last, type_desc_of(type), pixels);
    // OpenImageIO's TIFF reader returns true for a strip it could not read, with the error
    // pending (and garbage in the buffer): an error message counts as a failure too.
    std::string why = image_->geterror();
    if (ok && why.empty()) return "";
    return pending_error(why);
  }

 private:
  std::unique_ptr<OIIO::ImageInput> image_;
  ImageHeader header_;
};

class Writer final : public ImageWriter {
 public:
  explicit Writer(std::unique_ptr<OIIO::ImageOutput> output) : output_(std::move(output)) {}

  std::string write_scanlines(int y0, int y1, SampleType type, const void* pixels) override {
    if (output_->write_scanlines(y0, y1, 0, type_desc_of(type), pixels)) return "";
    return pending_error(output_->geterror());
  }
  std::string close() override {
    if (output_->close()) return "";
    return pending_error(output_->geterror());
  }

 private:
  std::unique_ptr<OIIO::ImageOutput> output_;
};

std::unique_ptr<ImageReader> open(const std::string& file, int threads, std::string& error) {
  // Keep the bytes of a TIFF or PNG with unassociated alpha as stored (no premultiplication).
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto image = OIIO::ImageInput::open(file, &config);
  if (!image) {
    error = pending_error(OIIO::geterror());
    return nullptr;
  }
  image->threads(threads);
  return std::make_unique<Reader>(std::move(image));
}

std::unique_ptr<ImageWriter> create(const std::string& file, const ImageWriteSpec& wanted,
                                    int threads, std::string& error) {
  auto output = OIIO::ImageOutput::create(file);
  if (!output) {
    error = pending_error(OIIO::geterror());
    return nullptr;
  }
  output->threads(threads);
  OIIO::ImageSpec spec(wanted.width, wanted.height, int(wanted.channel_names.size()),
                       type_desc_of(wanted.stored));
  spec.channelnames.assign(wanted.channel_names.begin(), wanted.channel_names.end());
  spec.alpha_channel = -1;  // no channel is alpha: nothing may be premultiplied
  if (!wanted.compression.empty()) spec.attribute("compression", wanted.compression);
  if (!wanted.description.empty()) spec.attribute("ImageDescription", wanted.description);
  spec.attribute("Software", "swell");
  if (!output->open(file, spec)) {
    error = pending_error(output->geterror());
    return nullptr;
  }
  return std::make_unique<Writer>(std::move(output));
}

// OpenImageIO's EXR reader on OpenEXRCore: the classic one converts each float of an
// interleaved multi-channel read byte by byte (Xdr), which made reading six fields of 64
// frames of 512² take 0.4 s of CPU more than reading one.
[[maybe_unused]] const bool use_openexr_core = OIIO::attribute("openexr:core", 1);

constexpr ImageModule kModule{kImageModuleInterfaceVersion, &open, &create};

}  // namespace
}  // namespace swell::validation::detail

extern "C" const swell::validation::detail::ImageModule* swell_openimageio_module() {
  return &swell::validation::detail::kModule;
}
