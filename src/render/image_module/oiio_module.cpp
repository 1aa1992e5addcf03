// OpenImageIO behind the ImageModuleApi (image_module_api.h): loaded by render/image_library.cpp on first use.
#include <OpenImageIO/imageio.h>

#include <fstream>
#include <memory>

#include "render/image_module/image_module_api.h"

namespace {

using rimu::DecodedImage;

bool can_write(const std::string& format, std::string& error) {
  if (OIIO::ImageOutput::create(format)) return true;
  error = OIIO::geterror();
  return false;
}

bool write_rgb8(const std::string& path, const std::string& format, int width, int height,
                const std::vector<uint8_t>& pixels, const std::string& software, const std::string& view,
                bool srgb_encoded, std::string& error) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(format);
  if (!out) {
    error = "OpenImageIO has no " + format + " writer: " + OIIO::geterror();
    return false;
  }
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("Software", software);
  spec.attribute("rimu:view", view);
  if (srgb_encoded) spec.attribute("oiio:ColorSpace", "sRGB");
  if (!out->open(path, spec)) {
    error = out->geterror();
    return false;
  }
  if (!out->write_image(OIIO::TypeDesc::UINT8, pixels.data())) {
    error = out->geterror();
    out->close();
    return false;
  }
  if (!out->close()) {
    error = out->geterror();
    return false;
  }
  return true;
}

std::unique_ptr<OIIO::ImageInput> open_header(const std::string& path, DecodedImage& image, std::string& error) {
  OIIO::ImageSpec config;
  if (image.as_stored) config.attribute("oiio:UnassociatedAlpha", 1);
  auto input = OIIO::ImageInput::open(path, &config);
  if (!input) {
    error = OIIO::geterror();
    return input;
  }
  const OIIO::ImageSpec& spec = input->spec();
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  image.alpha_channel = spec.alpha_channel;
  image.bits_per_sample = spec.get_int_attribute("oiio:BitsPerSample", int(spec.format.size() * 8));
  image.format_name = input->format_name();
  // OpenImageIO reports a binary PBM (magic "P4", one bit per pixel, rows padded to a byte) as 8-bit.
  if (image.format_name == "pnm") {
    char magic[2] = {0, 0};
    std::ifstream(path, std::ios::binary).read(magic, 2);
    if (magic[0] == 'P' && magic[1] == '4') image.bits_per_sample = 1;
  }
  const auto base = spec.format.basetype;
  image.stored_as_float =
      base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::HALF || base == OIIO::TypeDesc::DOUBLE;
  return input;
}

bool read_header(const std::string& path, DecodedImage& image, std::string& error) {
  auto input = open_header(path, image, error);
  if (!input) return false;
  input->close();
  return true;
}

bool read_pixels(const std::string& path, DecodedImage& image, std::string& error) {
  auto input = open_header(path, image, error);
  if (!input) {
    error = "cannot read the image: " + error;
    return false;
  }
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0) {
    error = "the image is empty";
    return false;
  }
  image.pixels.resize(size_t(image.width) * size_t(image.height) * size_t(image.channels));
  if (!input->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    const std::string reason = input->geterror();
    error = "cannot read the pixels: " +
            (reason.empty() ? std::string("OpenImageIO gives no reason (is the file truncated or damaged?)") : reason);
    return false;
  }
  input->close();
  return true;
}

const rimu::ImageModuleApi kApi{rimu::kImageModuleApiVersion, can_write, write_rgb8, read_header, read_pixels};

}  // namespace

extern "C" __attribute__((visibility("default"))) const rimu::ImageModuleApi* rimu_image_module_api() {
  return &kApi;
}
