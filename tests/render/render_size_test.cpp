// A render request naming one dimension keeps the scene's aspect ratio; every dimension is held to 1-32768.
#include <doctest/doctest.h>

#include <utility>

#include "render/film/render_size.h"

using namespace rimu;

TEST_CASE("a width or height given alone keeps the scene's aspect ratio") {
  const SourceLocation w{"", 0, "width"}, h{"", 0, "height"};
  CHECK(resolution_keeping_aspect(640, 480, 96, std::nullopt, w, h) == std::pair{96, 72});
  CHECK(resolution_keeping_aspect(640, 480, std::nullopt, 120, w, h) == std::pair{160, 120});
  CHECK(resolution_keeping_aspect(640, 480, 10, 10, w, h) == std::pair{10, 10});            // both: as given
  CHECK(resolution_keeping_aspect(640, 480, std::nullopt, std::nullopt, w, h) == std::pair{640, 480});
  CHECK(resolution_keeping_aspect(1000, 1, 3, std::nullopt, w, h) == std::pair{3, 1});      // at least one pixel
  CHECK_THROWS_WITH_AS(resolution_keeping_aspect(640, 480, 0, std::nullopt, w, h),
                       "width: expected a whole number in 1-32768, got 0", InputError);
  // A height derived from the aspect ratio is held to the same limit, and named.
  CHECK_THROWS_WITH_AS(resolution_keeping_aspect(1, 1000, 100, std::nullopt, w, h),
                       "height: expected a whole number in 1-32768, got 100000", InputError);
}
