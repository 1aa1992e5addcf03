// The limits on an image's size, its samples per pixel and its worker threads wherever a render is requested (the
// `rimu` options, the Python module's render()), and the size a request gives when it names only one dimension.
#pragma once

#include <optional>
#include <utility>

#include "spectral/error.h"

namespace rimu {

inline constexpr int kMaxImageDimension = 32768;      ///< pixels, either side (as --resolution)
inline constexpr int kMaxSamplesPerPixel = 1 << 24;   ///< as --spp
inline constexpr int kMaxRenderThreads = 1024;        ///< as --threads

/// Throws InputError at `where` unless lo <= value <= hi: "expected a whole number in 1-32768, got 0".
void check_render_count(long long value, long long lo, long long hi, const SourceLocation& where);

/// The image size for a requested width and/or height over a scene of scene_width × scene_height. A dimension given
/// alone keeps the scene's aspect ratio: the other one is scaled and rounded (at least 1 pixel). Throws InputError
/// at `width_where` / `height_where` for a dimension outside 1-kMaxImageDimension, given or derived.
std::pair<int, int> resolution_keeping_aspect(int scene_width, int scene_height, std::optional<long long> width,
                                              std::optional<long long> height, const SourceLocation& width_where,
                                              const SourceLocation& height_where);

}  // namespace rimu
