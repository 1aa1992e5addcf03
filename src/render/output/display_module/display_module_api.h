// The functions of Rimu's OpenColorIO module (librimu_ocio.so), shared by the module and its loader
// (render/output/display_transform.cpp). OpenColorIO is needed only to write a display image (PNG, JPEG, TIFF, the
// preview) or to check a display view; linked into every Rimu program it cost each process ~3 MiB of resident
// memory (libOpenColorIO, yaml-cpp, expat, pystring: the pages their relocation touches) whether it wrote a display
// image or not. Built by the same build with the same compiler, so std::string crosses the boundary; exceptions
// do not: create catches OpenColorIO's and reports through its `error` (apply has nothing to report).
#pragma once

#include <string>

namespace rimu {

/// Bumped whenever a signature below changes, so that a stale module is refused rather than called wrongly.
inline constexpr int kDisplayModuleApiVersion = 1;

/// Which step of DisplayModuleApi::create failed.
enum class DisplayModuleFailure { none, config, unknown_view, processor };

struct DisplayModuleApi {
  int api_version;
  /// A CPU processor from the colour space `source` to `display` and `view` of the config file `config_path`, or
  /// nullptr with `failure` and `error` set: the config cannot be loaded (OpenColorIO's message); the display has no
  /// such view (`error`: the display's views joined by ", ", empty if the display is unknown); the processor cannot
  /// be built (OpenColorIO's message).
  void* (*create)(const std::string& config_path, const std::string& source, const std::string& display,
                  const std::string& view, DisplayModuleFailure& failure, std::string& error);
  /// Applies the processor in place to `pixel_count` interleaved RGB floats.
  void (*apply)(const void* processor, float* rgb, long pixel_count);
  void (*destroy)(void* processor);
};

}  // namespace rimu

/// The one symbol the module exports.
extern "C" const rimu::DisplayModuleApi* rimu_display_module_api();
