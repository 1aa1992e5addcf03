// Rendering to a time budget (render/time_budget.h, `rimu --time`): whole passes until the budget is spent. The
// tests assert what the budget decides and what the render records (its spp, a complete image equal to a fixed-spp
// render of the same samples), never the wall time.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "render/film/film_tile.h"
#include "render/output/partial_exr.h"
#include "render/render_job.h"
#include "render/time_budget.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;
namespace fs = std::filesystem;

TEST_CASE("time budget: the first pass always, then a pass only if its predicted time fits") {
  TimeBudget budget(10.0, 0.0);
  CHECK(budget.allows_pass(50.0, 1, true));   // an empty film gets its pass even past the budget
  TimeBudget b(10.0, 0.0);
  CHECK(b.allows_pass(0.0, 1, true));
  CHECK(b.allows_pass(1.0, 2, false));        // 1 s per sample: 1 + 2 = 3 s fits
  CHECK(b.allows_pass(3.0, 4, false));        // 3 + 4 = 7 s fits
  CHECK_FALSE(b.allows_pass(7.0, 8, false));  // 7 + 8 = 15 s does not
  CHECK(b.spent());
}

TEST_CASE("time budget: a resumed render counts the time already spent") {
  TimeBudget fresh(10.0, 9.5);
  CHECK(fresh.allows_pass(0.0, 16, false));  // no pass timed yet: any budget left allows one
  CHECK_FALSE(fresh.allows_pass(1.0, 16, false));
  TimeBudget over(10.0, 10.0);
  CHECK_FALSE(over.allows_pass(0.0, 16, false));
  CHECK(over.spent());
}

namespace {


// A diffuse card under a distant light, 8×8, box filter (every sample has filter weight 1), `integrator` as given.
fs::path write_card_scene(const fs::path& folder, const json& integrator) {
  const json scene{{"camera", {{"from", {0.0, 0.0, 3.0}}, {"to", {0, 0, 0}}, {"up", {0, 1, 0}}, {"vertical_fov_deg", 20}}},
                   {"film", {{"resolution", {8, 8}}, {"filter", {{"type", "box"}}}}},
                   {"integrator", integrator},
                   {"materials", {{"card", {{"type", "diffuse"}, {"reflectance", 0.5}}}}},
                   {"lights", json::array({{{"type", "distant"}, {"direction", {0, 0, 1}},
                                            {"irradiance", 1.0}}})},
                   {"shapes", json::array({{{"type", "quad"},
                                            {"vertices", {{-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0}}},
                                            {"material", "card"}}})}};
  const fs::path path = folder / "card.json";
  std::ofstream(path) << scene.dump(2);
  return path;
}

// A job writing a partial (the sums are kept: --checkpoint with an interval no test reaches).
RenderJob partial_job(const fs::path& scene, const fs::path& output) {
  RenderJob job;
  job.scene = scene;
  job.exr_output = output;
  job.quiet = true;
  job.threads = 2;
  job.checkpoint_interval_s = 3600.0;
  return job;
}

// Every pixel holds exactly `spp` samples of weight 1: no pass was cut, no tile missed.
void check_complete(const PartialImage& image, int spp) {
  const size_t pixels = size_t(image.crop.area());
  int incomplete = 0;
  for (size_t p = 0; p < pixels; ++p)
    incomplete += image.sums[p * size_t(image.accumulators_per_pixel) + FilmTile::kWeight] != double(spp);
  CHECK(incomplete == 0);
}

}  // namespace

TEST_CASE("time budget: a tiny budget records whole passes and a complete image, equal to a fixed-spp render") {
  test::ScratchFolder folder("time_budget");
  const fs::path scene = write_card_scene(folder.path, {{"max_depth", 2}});
  RenderJob timed = partial_job(scene, folder.path / "timed.exr");
  timed.time_limit_s = 0.05;
  run_render_job(timed, std::cerr);
  const PartialImage image = read_partial_exr(timed.exr_output);
  REQUIRE(image.record.samples.size() == 1);
  const int spp = image.record.samples.front().end;
  INFO("spp reached: " << spp);
  CHECK(spp >= 1);
  CHECK(sample_pass_end(spp - 1) == spp);  // a pass boundary: whole passes only
  CHECK(image.metadata.samples_per_pixel == spp);
  CHECK(image.record.requested == SampleRange{0, spp});  // complete: --resume has nothing left to do
  CHECK(image.record.total_spp == spp);
  CHECK(!image.metadata.interrupted);
  check_complete(image, spp);

  // The same samples from a fixed-spp render: bit-identical sums.
  RenderJob fixed = partial_job(scene, folder.path / "fixed.exr");
  fixed.samples_per_pixel = spp;
  run_render_job(fixed, std::cerr);
  CHECK(read_partial_exr(fixed.exr_output).sums == image.sums);
}

TEST_CASE("time budget: --spp is the maximum, and the scene's time_limit_s is capped by its own spp") {
  test::ScratchFolder folder("time_budget");
  RenderJob capped = partial_job(write_card_scene(folder.path, {{"max_depth", 2}}), folder.path / "capped.exr");
  capped.time_limit_s = 600.0;
  capped.samples_per_pixel = 5;  // not a pass boundary: the last pass is cut at the maximum
  run_render_job(capped, std::cerr);
  PartialImage image = read_partial_exr(capped.exr_output);
  CHECK(image.record.samples == std::vector<SampleRange>{{0, 5}});
  check_complete(image, 5);

  RenderJob scene_budget =
      partial_job(write_card_scene(folder.path, {{"max_depth", 2}, {"spp", 4}, {"time_limit_s", 600}}),
                  folder.path / "scene_budget.exr");
  run_render_job(scene_budget, std::cerr);
  image = read_partial_exr(scene_budget.exr_output);
  CHECK(image.record.samples == std::vector<SampleRange>{{0, 4}});
  check_complete(image, 4);
}

TEST_CASE("time budget: --samples is refused with it, naming the option") {
  test::ScratchFolder folder("time_budget");
  RenderJob job = partial_job(write_card_scene(folder.path, {{"max_depth", 2}}), folder.path / "never.exr");
  job.time_limit_s = 1.0;
  job.samples = SampleRange{0, 8};
  job.samples_per_pixel = 8;
  try {
    run_render_job(job, std::cerr);
    FAIL("a time budget with --samples was accepted");
  } catch (const InputError& e) {
    const std::string message = e.what();
    CHECK(message.find("--samples") != std::string::npos);
    CHECK(message.find("--time") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(job.exr_output));
}
