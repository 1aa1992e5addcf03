// Light groups through the ways a render is continued or stopped early: a checkpoint resumed (`--resume`), partials
// merged (`rimu merge`, with and without their sums), adaptive sampling (`--noise-threshold`). In each, the layers
// still sum to the beauty within float rounding and `rimu display --group x=0` removes x's light exactly. And a scene
// may have more groups than the 32 an earlier version allowed.
#include <ImfHeader.h>
#include <ImfStringAttribute.h>
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "light_groups_support.h"
#include "render/output/merge_partials.h"
#include "render/output/partial_exr.h"

using namespace rimu;
using namespace rimu::test;
namespace fs = std::filesystem;
using json = nlohmann::json;

TEST_CASE("light groups: a resumed checkpoint keeps layers that sum to the beauty, equal to one render") {
  ScratchFolder folder("light_groups_resume");
  // What `rimu --checkpoint … --spp 8` leaves when stopped after 3 samples: samples 0:3 of a job asking for 0:8.
  // Rendered as the partial 0:3 and given the record an interrupted checkpoint has (the same sums: a pixel's samples
  // do not depend on where the render stops).
  render(tiny_job(light_groups_example(), folder / "first.exr", SampleRange{0, 3}));
  copy_exr_with_header(folder / "first.exr", folder / "checkpoint.exr", [](Imf::Header& h) {
    auto* job_text = h.findTypedAttribute<Imf::StringAttribute>("rimu:partial:job");
    REQUIRE(job_text);
    json job = json::parse(job_text->value());
    REQUIRE(job.contains("samples"));
    job.erase("samples");
    job["checkpoint_s"] = 3600.0;
    h.insert("rimu:partial:job", Imf::StringAttribute(job.dump()));
    h.insert("rimu:partial:requested", Imf::StringAttribute("0:8"));
    h.insert("rimu:interrupted", Imf::StringAttribute("interrupted at 3 spp"));
  });
  RenderJob resume;
  resume.resume = folder / "checkpoint.exr";
  resume.exr_output = folder / "resumed.exr";
  resume.threads = 2;
  resume.quiet = true;
  render(resume);
  render(tiny_job(light_groups_example(), folder / "whole.exr"));

  const PartialImage resumed = read_partial_exr(folder / "resumed.exr", false);
  CHECK(resumed.record.samples == std::vector<SampleRange>{{0, 8}});
  CHECK(resumed.light_groups == kExampleGroups);
  const ExrChannels channels = read_channels(folder / "resumed.exr");
  check_layers_sum_to_beauty(channels, kExampleGroups);
  check_same_image(read_channels(folder / "whole.exr"), channels);
  for (const std::string& group : kExampleGroups) check_group_removed_exactly(folder / "resumed.exr", group);
}

TEST_CASE("light groups: --group x=0 removes x exactly on merged partials, with and without their sums") {
  ScratchFolder folder("light_groups_merged_display");
  render(tiny_job(light_groups_example(), folder / "a.exr", SampleRange{0, 3}));
  render(tiny_job(light_groups_example(), folder / "b.exr", SampleRange{3, 8}));
  std::ostringstream log;
  merge_partials({folder / "a.exr", folder / "b.exr"}, folder / "merged_sums.exr", MergeOptions{}, log);
  MergeOptions image_only;
  image_only.keep_sums = false;
  merge_partials({folder / "a.exr", folder / "b.exr"}, folder / "merged_image.exr", image_only, log);
  for (const char* name : {"merged_sums.exr", "merged_image.exr"}) {
    CAPTURE(name);
    check_layers_sum_to_beauty(read_channels(folder / name), kExampleGroups);
    for (const std::string& group : kExampleGroups) check_group_removed_exactly(folder / name, group);
  }
}

TEST_CASE("light groups: adaptive sampling keeps layers that sum to the beauty") {
  ScratchFolder folder("light_groups_adaptive");
  RenderJob job = tiny_job(light_groups_example(), folder / "adaptive.exr");
  job.samples_per_pixel = 64;
  // 0.1 stopped every pixel in the same pass once the constant sky was left to BSDF sampling (less noise): 0.05
  // keeps some pixels sampling longer than others, which is what this test needs.
  job.noise_threshold = 0.05;
  render(job);
  const ExrChannels exr = read_channels(folder / "adaptive.exr");
  // Adaptive sampling was at work: some pixels stopped before the maximum (the sky converges at once).
  const auto& spp = exr.channels.at("spp");
  const auto [fewest, most] = std::minmax_element(spp.begin(), spp.end());
  CHECK(*fewest < *most);
  CHECK(*fewest >= 16.0f);  // adaptive_min_spp(64)
  check_layers_sum_to_beauty(exr, kExampleGroups);
  for (const std::string& group : kExampleGroups) check_group_removed_exactly(folder / "adaptive.exr", group);
}

TEST_CASE("light groups: more than 32 groups render, sum to the beauty and survive a partial") {
  ScratchFolder folder("light_groups_many");
  json scene = json::parse(std::ifstream(light_groups_example()));
  // 36 point lights in a ring above the block, each its own group: 40 groups with the example's four.
  std::vector<std::string> groups = kExampleGroups;
  groups.pop_back();  // "ungrouped" stays last
  for (int i = 0; i < 36; ++i) {
    const double angle = 2.0 * M_PI * i / 36.0;
    const std::string name = "ring" + std::to_string(i);
    scene["lights"].push_back({{"type", "point"}, {"light_group", name},
                               {"position", {1.2 * std::cos(angle), 1.2, 1.2 * std::sin(angle)}},
                               {"intensity", {{"constant", 0.5}}}});
    groups.push_back(name);
  }
  groups.push_back("ungrouped");
  std::ofstream(folder / "ring.json") << scene.dump();
  RenderJob job = tiny_job(folder / "ring.json", folder / "ring.exr", SampleRange{0, 16});
  job.samples_per_pixel = 16;
  render(job);
  const PartialImage partial = read_partial_exr(folder / "ring.exr", false);
  REQUIRE(partial.light_groups == groups);
  CHECK(partial.accumulators_per_pixel == 4 + 3 * 40);
  const ExrChannels exr = read_channels(folder / "ring.exr");
  check_layers_sum_to_beauty(exr, groups);
  check_group_removed_exactly(folder / "ring.exr", "ring7");
}
