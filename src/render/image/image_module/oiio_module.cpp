// OpenImageIO behind the ImageModuleApi (image_module_api.h): loaded by render/image/image_library.cpp on first use.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>

#include "render/image/image_module/image_module_api.h"

namespace {

using rimu::DecodedImage;

// Some of the libraries behind OpenImageIO print their own messages on standard error besides returning an error
// (libpng: "libpng error: IHDR: CRC error", naming no file), so the user saw a stray line before Rimu's message.
// While the module reads or writes, standard error goes to an unnamed temporary file; what was written there is
// then added to the module's error (which Rimu reports naming the file) or, after a read that succeeded, printed as
// one warning naming the file. A mutex keeps two threads from redirecting at once; Rimu reads images while it
// loads a scene, when nothing else writes to standard error.
class CapturedStandardError {
 public:
  CapturedStandardError() : lock_(mutex()) {
    std::fflush(stderr);
    file_ = std::tmpfile();
    saved_ = file_ ? ::dup(STDERR_FILENO) : -1;
    if (saved_ >= 0 && ::dup2(::fileno(file_), STDERR_FILENO) < 0) {
      ::close(saved_);
      saved_ = -1;
    }
  }
  ~CapturedStandardError() {
    release();
    if (file_) std::fclose(file_);
  }
  CapturedStandardError(const CapturedStandardError&) = delete;
  CapturedStandardError& operator=(const CapturedStandardError&) = delete;

  /// Restores standard error and returns what was written to it meanwhile, its lines joined by "; ".
  std::string release() {
    if (saved_ < 0) return {};
    std::fflush(stderr);
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
    saved_ = -1;
    std::string text;
    std::rewind(file_);
    char buffer[4096];
    size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, file_)) > 0 && text.size() < 4000) text.append(buffer, n);
    std::string joined;
    size_t start = 0;
    while (start < text.size()) {
      size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      std::string line = text.substr(start, end - start);
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
      if (!line.empty()) joined += (joined.empty() ? "" : "; ") + line;
      start = end + 1;
    }
    return joined;
  }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

// The library's own text, captured while `ok` was decided: added to a failure's message (unless the message holds
// it already), or printed as a warning naming `path` after a read that succeeded.
// OpenImageIO joins the errors of one call with line breaks: they become "; " so Rimu's message stays one line.
bool with_library_text(bool ok, const std::string& text, const std::string& path, std::string& error, bool warn) {
  if (!ok && !text.empty() && error.find(text) == std::string::npos)
    error += (error.empty() ? "" : " (") + text + (error.empty() ? "" : ")");
  if (!ok) {
    while (!error.empty() && (error.back() == '\n' || error.back() == ' ')) error.pop_back();
    for (size_t at = error.find('\n'); at != std::string::npos; at = error.find('\n', at)) error.replace(at, 1, "; ");
  }
  if (ok && warn && !text.empty()) std::fprintf(stderr, "rimu: warning: %s: %s\n", path.c_str(), text.c_str());
  return ok;
}

bool can_write(const std::string& format, std::string& error) {
  if (OIIO::ImageOutput::create(format)) return true;
  error = OIIO::geterror();
  return false;
}

bool write_rgb8_uncaptured(const std::string& path, const std::string& format, int width, int height,
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

// The EXIF orientation (1-8) a Radiance HDR file's size line gives ("+Y h +X w": 4, rows stored bottom first;
// "-Y h -X w": 2, right to left; "+Y h -X w": 3), which OpenImageIO only reports: its reader returns the pixels in
// the order stored. For a Radiance file the orientation is part of the pixel data, not a display hint, so Rimu
// applies it (pbrt-v4's reader, stb_image, refuses every orientation but the standard one). Size lines whose
// scanlines are columns ("+X w -Y h" …, 5-8) are refused: OpenImageIO's reorientation of them disagrees with the
// Radiance format's definition (the first axis the order of the scanlines, the second the order within one; checked
// on a 2 × 2 file, tests/render/freeimage_module_test.cpp), and no tool writes them. Other formats' orientation tags
// (a camera JPEG's or TIFF's EXIF Orientation) are left as stored, as pbrt-v4 and most renderers leave them.
int radiance_orientation(const OIIO::ImageInput& input) {
  if (std::string(input.format_name()) != "hdr") return 1;
  const int orientation = input.spec().get_int_attribute("Orientation", 1);
  return orientation >= 1 && orientation <= 8 ? orientation : 1;
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
  if (const int orientation = radiance_orientation(*input); orientation >= 5) {
    error = "a Radiance HDR file whose scanlines are columns (a size line \"+X …\" or \"-X …\", orientation " +
            std::to_string(orientation) + ") is not supported: write it in the standard orientation \"-Y height +X width\"";
    input.reset();
    return input;
  }
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

bool read_header_uncaptured(const std::string& path, DecodedImage& image, std::string& error) {
  auto input = open_header(path, image, error);
  if (!input) return false;
  input->close();
  return true;
}

bool read_pixels_uncaptured(const std::string& path, DecodedImage& image, std::string& error) {
  auto input = open_header(path, image, error);
  if (!input) {
    error = "cannot read the image: " + error;
    return false;
  }
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0) {
    error = "the image is empty";
    return false;
  }
  const size_t samples = size_t(image.width) * size_t(image.height) * size_t(image.channels);
  // 8-bit files are read as they are stored: OpenImageIO then needs no conversion buffer (it allocates up to 64 MiB
  // to convert to floats) and the caller keeps a quarter of the floats' memory.
  const bool bytes = image.bytes_if_8bit && input->spec().format == OIIO::TypeDesc::UINT8;
  void* destination = nullptr;
  if (bytes) {
    image.bytes.resize(samples);
    destination = image.bytes.data();
  } else {
    image.pixels.resize(samples);
    destination = image.pixels.data();
  }
  if (!input->read_image(0, 0, 0, image.channels, bytes ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT, destination)) {
    const std::string reason = input->geterror();
    error = "cannot read the pixels: " +
            (reason.empty() ? std::string("OpenImageIO gives no reason (is the file truncated or damaged?)") : reason);
    return false;
  }
  if (const int orientation = radiance_orientation(*input); orientation != 1 && !bytes) {
    // The pixels as stored, in an ImageBuf that wraps them with the file's orientation (2-4: open_header refused
    // the others); reorient() turns them upright (rows top first, left to right).
    OIIO::ImageSpec stored = input->spec();
    stored.set_format(OIIO::TypeDesc::FLOAT);
    stored.attribute("Orientation", orientation);
    const OIIO::ImageBuf as_stored(stored, image.pixels.data());
    const OIIO::ImageBuf upright = OIIO::ImageBufAlgo::reorient(as_stored);
    if (upright.has_error() || upright.spec().width != image.width || upright.spec().height != image.height ||
        !upright.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.pixels.data())) {
      error = "cannot turn the pixels of orientation " + std::to_string(orientation) + " upright: " + upright.geterror();
      return false;
    }
  }
  input->close();
  return true;
}

bool write_rgb8(const std::string& path, const std::string& format, int width, int height,
                const std::vector<uint8_t>& pixels, const std::string& software, const std::string& view,
                bool srgb_encoded, std::string& error) {
  CapturedStandardError captured;
  const bool ok = write_rgb8_uncaptured(path, format, width, height, pixels, software, view, srgb_encoded, error);
  // `path` is the writer's temporary file, not a name the user knows: a warning of a write is not printed.
  return with_library_text(ok, captured.release(), path, error, false);
}

bool read_header(const std::string& path, DecodedImage& image, std::string& error) {
  CapturedStandardError captured;
  const bool ok = read_header_uncaptured(path, image, error);
  return with_library_text(ok, captured.release(), path, error, true);
}

bool read_pixels(const std::string& path, DecodedImage& image, std::string& error) {
  CapturedStandardError captured;
  const bool ok = read_pixels_uncaptured(path, image, error);
  return with_library_text(ok, captured.release(), path, error, true);
}

const rimu::ImageModuleApi kApi{rimu::kImageModuleApiVersion, can_write, write_rgb8, read_header, read_pixels};

}  // namespace

extern "C" __attribute__((visibility("default"))) const rimu::ImageModuleApi* rimu_image_module_api() {
  return &kApi;
}
