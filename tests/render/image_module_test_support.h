// What the tests of the in-process image decoders (stb_image, OpenEXR) share: the OpenImageIO module's decode to
// compare with, a file's bytes to damage, and a fresh process for the checks that the module stays unloaded.
#pragma once

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "render/image/image_library.h"
#include "render/render_job.h"

namespace rimu::test {

/// The OpenImageIO module's decode of `path` (floats, or bytes if asked), as read_image_file made it before the
/// in-process decoders.
inline DecodedImage module_decode(const std::filesystem::path& path, bool as_stored, bool bytes_if_8bit) {
  DecodedImage image;
  image.as_stored = as_stored;
  image.bytes_if_8bit = bytes_if_8bit;
  std::string error;
  REQUIRE_MESSAGE(image_library().read_pixels(path.string(), image, error), error);
  return image;
}

/// A decoder's header fields are those the OpenImageIO module gives for the same file.
inline void check_same_header(const DecodedImage& decoded, const DecodedImage& oiio) {
  CHECK(decoded.width == oiio.width);
  CHECK(decoded.height == oiio.height);
  CHECK(decoded.channels == oiio.channels);
  CHECK(decoded.alpha_channel == oiio.alpha_channel);
  CHECK(decoded.bits_per_sample == oiio.bits_per_sample);
  CHECK(decoded.stored_as_float == oiio.stored_as_float);
  CHECK(decoded.format_name == oiio.format_name);
}

/// Values that vary from pixel to pixel and channel to channel over many octaves (HDR: 1e-3 to 1e4), some
/// negative: a decoder that swapped bytes, channels or rows, or rescaled, would show.
inline std::vector<float> hdr_test_values(size_t count) {
  std::vector<float> v(count);
  uint32_t h = 0x2545f491u;
  for (size_t i = 0; i < count; ++i) {
    h ^= uint32_t(i) * 0x85ebca6bu;
    h = (h ^ (h >> 13)) * 0xc2b2ae35u;
    h ^= h >> 16;
    const float octave = float(h % 8) - 3.0f;
    v[i] = std::pow(10.0f, octave) * float((h >> 8) % 1000) / 999.0f * ((h & 0x10000) && i % 7 == 0 ? -1.0f : 1.0f);
  }
  return v;
}

/// The smallest render job: the embedded Cornell box at 8 × 8 pixels, 1 sample, 1 thread, quiet, to `exr`; for the
/// checks of which modules a render loads.
inline RenderJob tiny_render_job(const std::filesystem::path& exr) {
  RenderJob job;
  job.exr_output = exr;
  job.width = 8;
  job.height = 8;
  job.samples_per_pixel = 1;
  job.threads = 1;
  job.quiet = true;
  return job;
}

/// The whole content of `path`.
inline std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// For a test that checks a module stays unloaded: if an earlier test of this process loaded it (`already_loaded`;
/// ctest runs each test alone, a plain run of the binary does not), runs the test cases matching `test_case_pattern` again by
/// themselves in a new process, checks that they pass and returns true (the caller then returns).
inline bool reran_alone_if(bool already_loaded, const std::string& test_case_pattern) {
  if (!already_loaded) return false;
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  const std::string command = "'" + self + "' '--test-case=" + test_case_pattern + "' >/dev/null 2>&1";
  CHECK(std::system(command.c_str()) == 0);
  return true;
}

/// reran_alone_if for the OpenImageIO module.
inline bool reran_alone_as_module_is_loaded(const std::string& test_case_pattern) {
  return reran_alone_if(image_library_loaded(), test_case_pattern);
}

}  // namespace rimu::test
