#include "render/film/render_size.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rimu {

void check_render_count(long long value, long long lo, long long hi, const SourceLocation& where) {
  if (value < lo || value > hi)
    throw InputError(where, "expected a whole number in " + std::to_string(lo) + "-" + std::to_string(hi) + ", got " +
                                std::to_string(value));
}

std::pair<int, int> resolution_keeping_aspect(int scene_width, int scene_height, std::optional<long long> width,
                                              std::optional<long long> height, const SourceLocation& width_where,
                                              const SourceLocation& height_where) {
  if (width) check_render_count(*width, 1, kMaxImageDimension, width_where);
  if (height) check_render_count(*height, 1, kMaxImageDimension, height_where);
  // The other side, scaled by the scene's aspect ratio and rounded to the nearest pixel.
  auto scaled = [](long long given, int from, int to) {
    return std::max(1LL, std::llround(double(given) * double(to) / double(from)));
  };
  const long long w = width ? *width : height ? scaled(*height, scene_height, scene_width) : scene_width;
  const long long h = height ? *height : width ? scaled(*width, scene_width, scene_height) : scene_height;
  if (!width) check_render_count(w, 1, kMaxImageDimension, width_where);
  if (!height) check_render_count(h, 1, kMaxImageDimension, height_where);
  return {int(w), int(h)};
}

}  // namespace rimu
