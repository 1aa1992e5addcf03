// FreeImage behind the ImageModuleApi (image_module_api.h), for PFM and Radiance HDR files only (HDR in the standard
// orientation, radiance_header.h): loaded by render/image/image_library.cpp the first time a scene reads one (an
// environment map, most often). They used to go to the OpenImageIO module, whose loading alone costs ~120 MiB of
// resident memory (docs/pbrt-import.md, "Memory"); FreeImage and the libraries it links cost ~4 MiB. The module
// gives what the OpenImageIO module gives for the same file (tests/render/freeimage_module_test.cpp): the same header
// fields, rows top first, and a PFM's samples multiplied by the magnitude of the header's scale, as OpenImageIO and
// pbrt-v4 do (FreeImage reads the scale only for its sign, the byte order, so the module applies the magnitude).
#include <FreeImage.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <mutex>
#include <string>

#include "render/image/image_module/image_module_api.h"
#include "render/image/image_module/radiance_header.h"

namespace {

using rimu::DecodedImage;

// FreeImage reports errors through one process-wide callback; each thread keeps its own last message.
thread_local std::string last_message;

void on_message(FREE_IMAGE_FORMAT, const char* message) { last_message = message ? message : ""; }

void initialise() {
  static std::once_flag once;
  std::call_once(once, [] {
    FreeImage_Initialise(TRUE);  // TRUE: only the plugins built into the library, none found on disk
    FreeImage_SetOutputMessage(on_message);
  });
}

// What the header says, read by the module itself besides FreeImage: FreeImage reads the scale only for its sign
// (the byte order) and skips a minus sign before the width or height ("2 -1" reads as 2 × 1), so the module takes
// the scale's magnitude from here and refuses a header whose size FreeImage read differently.
struct FileHeader {
  FREE_IMAGE_FORMAT format = FIF_PFM;
  long long width = 0, height = 0;
  float scale = 1.0f;  // a PFM's magnitude: a factor on every sample
};

bool read_pfm_header(const std::string& path, FileHeader& header, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  double scale = 0.0;
  if (!(in >> magic >> header.width >> header.height >> scale) || (magic != "PF" && magic != "Pf")) {
    error = "not a PFM header (expected \"PF\" or \"Pf\", the width, the height and the scale)";
    return false;
  }
  if (header.width <= 0 || header.height <= 0) {
    error = "the PFM header says " + std::to_string(header.width) + " x " + std::to_string(header.height) +
            " pixels (expected positive numbers)";
    return false;
  }
  if (!std::isfinite(scale) || scale == 0.0) {
    error = "the PFM header's scale is " + std::to_string(scale) + " (expected a finite number other than 0)";
    return false;
  }
  header.scale = float(std::fabs(scale));
  return true;
}

// The header of a PFM or of a Radiance HDR in the standard orientation (the files the router sends here).
bool read_file_header(const std::string& path, FileHeader& header, std::string& error) {
  if (const std::optional<rimu::RadianceSize> size = rimu::radiance_standard_size(path)) {
    header.format = FIF_HDR;
    header.width = size->width;
    header.height = size->height;
    return true;
  }
  return read_pfm_header(path, header, error);
}

// Loads `path` (header only unless `pixels`); fills the header fields. nullptr with `error` on failure.
FIBITMAP* load(const std::string& path, bool pixels, const FileHeader& header, DecodedImage& image,
               std::string& error) {
  initialise();
  last_message.clear();
  const char* kind = header.format == FIF_HDR ? "a Radiance HDR" : "a PFM";
  FIBITMAP* bitmap = FreeImage_Load(header.format, path.c_str(), pixels ? 0 : FIF_LOAD_NOPIXELS);
  if (!bitmap) {
    error = last_message.empty() ? std::string("FreeImage cannot read it as ") + kind : last_message;
    return nullptr;
  }
  const FREE_IMAGE_TYPE type = FreeImage_GetImageType(bitmap);
  if (type != FIT_RGBF && !(type == FIT_FLOAT && header.format == FIF_PFM)) {
    FreeImage_Unload(bitmap);
    error = "FreeImage read it as an image of type " + std::to_string(int(type)) + ", not " + kind;
    return nullptr;
  }
  image.width = int(FreeImage_GetWidth(bitmap));
  image.height = int(FreeImage_GetHeight(bitmap));
  if (image.width != header.width || image.height != header.height) {
    FreeImage_Unload(bitmap);
    error = "FreeImage read " + std::to_string(image.width) + " x " + std::to_string(image.height) +
            " pixels where the header says " + std::to_string(header.width) + " x " +
            std::to_string(header.height);
    return nullptr;
  }
  image.channels = type == FIT_RGBF ? 3 : 1;
  image.alpha_channel = -1;
  image.bits_per_sample = 32;
  image.stored_as_float = true;
  // OpenImageIO's names: "pnm" for PPM, PGM, PBM and PFM alike, "hdr" for Radiance.
  image.format_name = header.format == FIF_HDR ? "hdr" : "pnm";
  return bitmap;
}

bool can_write(const std::string& format, std::string& error) {
  error = "Rimu's FreeImage module reads PFM and HDR files only; it has no " + format + " writer";
  return false;
}

bool write_rgb8(const std::string&, const std::string& format, int, int, const std::vector<uint8_t>&,
                const std::string&, const std::string&, bool, std::string& error) {
  return can_write(format, error);
}

bool read_header(const std::string& path, DecodedImage& image, std::string& error) {
  FileHeader header;
  if (!read_file_header(path, header, error)) return false;
  FIBITMAP* bitmap = load(path, false, header, image, error);
  if (!bitmap) return false;
  FreeImage_Unload(bitmap);
  return true;
}

bool read_pixels(const std::string& path, DecodedImage& image, std::string& error) {
  FileHeader header;
  if (!read_file_header(path, header, error)) return false;
  FIBITMAP* bitmap = load(path, true, header, image, error);
  if (!bitmap) {
    error = "cannot read the image: " + error;
    return false;
  }
  if (!FreeImage_HasPixels(bitmap)) {  // the size is the header's, checked positive
    FreeImage_Unload(bitmap);
    error = "cannot read the image: FreeImage returned no pixels";
    return false;
  }
  // PFM stores rows bottom first; FreeImage's PFM reader puts the file's last row, the image's top, into scan line
  // 0, so scan line y is row y counted from the top, as DecodedImage holds it. Its HDR reader keeps FreeImage's own
  // convention, scan line 0 at the bottom: row y is scan line height − 1 − y (the tests compare with OpenImageIO).
  const size_t row_samples = size_t(image.width) * size_t(image.channels);
  image.pixels.resize(row_samples * size_t(image.height));
  image.bytes.clear();
  for (int y = 0; y < image.height; ++y) {
    const int scan_line = header.format == FIF_HDR ? image.height - 1 - y : y;
    const auto* row = reinterpret_cast<const float*>(FreeImage_GetScanLine(bitmap, scan_line));
    float* out = image.pixels.data() + size_t(y) * row_samples;
    if (header.scale == 1.0f) {
      std::memcpy(out, row, row_samples * sizeof(float));
    } else {
      for (size_t i = 0; i < row_samples; ++i) out[i] = row[i] * header.scale;
    }
  }
  FreeImage_Unload(bitmap);
  return true;
}

const rimu::ImageModuleApi kApi{rimu::kImageModuleApiVersion, can_write, write_rgb8, read_header, read_pixels};

}  // namespace

extern "C" __attribute__((visibility("default"))) const rimu::ImageModuleApi* rimu_image_module_api() { return &kApi; }
