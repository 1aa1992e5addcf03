// The film's sample clamp (Film::set_max_sample_value, film "max_sample_value", `--max-sample-value`): each sample is
// scaled so that its largest channel after exposure is at most the value, its spectral bins and light groups with
// it; clamped samples are counted, written into the EXR and kept apart in merges.
#include <ImfDoubleAttribute.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/film/film.h"
#include "render/output/merge_partials.h"
#include "render/output/partial_exr.h"
#include "render/render_job.h"
#include "render/scene/scene.h"
#include "spectral/error.h"
#include "light_groups_support.h"  // read_channels
#include "test_support.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace {

// One sample's channel values by a scalar reference of FilmTile::add_sample's estimator: (1/4) Σ_j L_j c(λ_j)/p_j.
std::array<double, 3> clamp_test_sample_value(const SpectralResponse& response, const SampledSpectrum& radiance,
                                              const SampledWavelengths& lambda) {
  std::array<double, 3> v{};
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < kLaneCount; ++j)
      v[c] += double(radiance[j]) * response.value(c, lambda.lambda_nm(j)) / double(lambda.pdf()[j]) / kLaneCount;
  return v;
}

RenderJob clamp_test_job(const fs::path& out) {
  RenderJob job;  // the embedded Cornell box
  job.width = 24;
  job.height = 16;
  job.samples_per_pixel = 1;
  job.seed = 3;
  job.threads = 2;
  job.quiet = true;
  job.exr_output = out;
  return job;
}

}  // namespace

TEST_CASE("sample clamp: a sample brighter than the clamp is scaled to it, bins and light groups with it") {
  const SpectralResponse response = SpectralResponse::cie_xyz(test::library());
  Film film(FilmOptions{1, 1, {}, 8}, response, {"key", "fill"});
  const double clamp = 3.0;
  film.set_max_sample_value(clamp);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::array<double, 3> expected{}, unclamped{};
  std::array<double, 8> expected_bins{};
  const double bin_width = 470.0 / 8.0;
  uint64_t expected_clamped = 0;
  const int n = 400;
  for (int i = 0; i < n; ++i) {
    const SampledWavelengths lambda = SampledWavelengths::sample_visible(u(rng) * 0.999f);
    // Radiances spread over three decades, so that some samples are clamped and some are not.
    const float scale = std::pow(10.0f, 3.0f * u(rng) - 2.0f);
    const SampledSpectrum key(scale * u(rng), scale * u(rng), scale * u(rng), scale * u(rng));
    const SampledSpectrum fill = key * Float4(0.5f);
    const SampledSpectrum groups[2] = {key, fill};
    film.add_sample(0, 0, key + fill, lambda, 1.0f, groups);
    const std::array<double, 3> v = clamp_test_sample_value(response, key + fill, lambda);
    const double largest = std::max({v[0], v[1], v[2]});
    const double factor = largest > clamp ? clamp / largest : 1.0;
    expected_clamped += largest > clamp;
    for (int j = 0; j < kLaneCount; ++j) {
      const int b = int(std::floor((lambda.lambda_nm(j) - 360.0) / bin_width));
      expected_bins[size_t(b)] += factor * double((key + fill)[j]) / double(lambda.pdf()[j]) / kLaneCount /
                                  bin_width / n;
    }
    for (int c = 0; c < 3; ++c) {
      expected[size_t(c)] += factor * v[size_t(c)] / n;
      unclamped[size_t(c)] += v[size_t(c)] / n;
    }
  }
  REQUIRE(expected_clamped > 20);  // the case must exercise both branches
  REQUIRE(expected_clamped < uint64_t(n) - 20);
  CHECK(film.sample_counts().clamped == expected_clamped);
  CHECK(film.sample_counts().accepted == uint64_t(n));
  CHECK(film.weight_sum(0, 0) == n);  // the clamp scales values, not the sample's weight
  const auto value = film.pixel_value(0, 0);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    // Float lane sums against the double reference: 1e-5 relative.
    CHECK(value[size_t(c)] == doctest::Approx(expected[size_t(c)]).epsilon(1e-5));
    CHECK(value[size_t(c)] < unclamped[size_t(c)]);
    // The groups keep summing to the beauty (key is 2/3 of every sample, fill 1/3).
    const double key = film.group_value(0, 0, 0)[size_t(c)], fill = film.group_value(0, 0, 1)[size_t(c)];
    CHECK(key + fill == doctest::Approx(value[size_t(c)]).epsilon(1e-5));
    CHECK(key == doctest::Approx(2.0 * fill).epsilon(1e-5));
  }
  // The spectral bins are scaled alike.
  for (int b = 0; b < 8; ++b) {
    CAPTURE(b);
    CHECK(film.spectral_value(0, 0, b) == doctest::Approx(expected_bins[size_t(b)]).epsilon(1e-5));
  }
}

TEST_CASE("sample clamp: in the written image's units (after exposure), and no clamp leaves the film as it was") {
  const SpectralResponse response = SpectralResponse::cie_xyz(test::library());
  const SampledWavelengths lambda = SampledWavelengths::sample_visible(0.37f);
  const SampledSpectrum radiance(40.0f, 35.0f, 50.0f, 45.0f);
  const std::array<double, 3> v = clamp_test_sample_value(response, radiance, lambda);
  const double largest = std::max({v[0], v[1], v[2]});

  FilmOutputTransform exposure;
  exposure.scale = 0.25;
  // The written value's largest channel is 0.25·largest: a clamp of half that halves the sample.
  Film film(FilmOptions{1, 1, {}, 0}, response);
  film.set_output_transform(exposure);
  film.set_max_sample_value(0.125 * largest);
  film.add_sample(0, 0, radiance, lambda);
  const auto written = film.output_value(0, 0);
  CHECK(std::max({written[0], written[1], written[2]}) == doctest::Approx(0.125 * largest).epsilon(1e-5));
  CHECK(film.sample_counts().clamped == 1);

  // Tiles made by the film carry the same threshold.
  Film tiled(FilmOptions{1, 1, {}, 0}, response);
  tiled.set_output_transform(exposure);
  tiled.set_max_sample_value(0.125 * largest);
  FilmTile tile = tiled.make_tile({0, 0, 1, 1});
  tile.add_sample(0, 0, radiance, lambda);
  tiled.merge_tile(tile);
  CHECK(tiled.pixel_value(0, 0) == film.pixel_value(0, 0));
  CHECK(tiled.sample_counts().clamped == 1);

  // A clamp above the sample, or none: bit for bit the film without a clamp.
  Film plain(FilmOptions{1, 1, {}, 0}, response), high(FilmOptions{1, 1, {}, 0}, response);
  high.set_max_sample_value(1.0001 * largest);
  plain.add_sample(0, 0, radiance, lambda);
  high.add_sample(0, 0, radiance, lambda);
  CHECK(plain.pixel_value(0, 0) == high.pixel_value(0, 0));
  CHECK(high.sample_counts().clamped == 0);
  // A discarded sample is not clamped.
  high.add_sample(0, 0, SampledSpectrum(NAN, 1.0f, 1.0f, 1.0f), lambda);
  CHECK(high.sample_counts().nan == 1);
  CHECK(high.sample_counts().clamped == 0);
}

TEST_CASE("sample clamp: a render's pixels stay below it, the EXR says how many samples it clamped") {
  const test::ScratchFolder dir("sample_clamp_render");
  // One sample per pixel through a box filter: every pixel is one sample's value, so none may exceed the clamp.
  RenderJob job = clamp_test_job(dir / "clamped.exr");
  job.max_sample_value = 0.05;
  std::ostringstream log;
  run_render_job(job, log);
  RenderJob plain_job = clamp_test_job(dir / "plain.exr");
  run_render_job(plain_job, log);

  double mean_clamped = 0.0, mean_plain = 0.0;
  size_t above = 0;
  const char* names[3] = {"X", "Y", "Z"};
  std::vector<std::vector<float>> clamped, plain;
  const test::ExrChannels clamped_file = test::read_channels(dir / "clamped.exr");
  const test::ExrChannels plain_channels = test::read_channels(dir / "plain.exr");
  for (const char* name : names) {
    clamped.push_back(clamped_file.channels.at(name));
    plain.push_back(plain_channels.channels.at(name));
  }
  // The embedded box has a Gaussian filter (radius 1.5): a pixel averages several samples, each clamped, so its
  // value is at most the clamp too (a weighted mean of values ≤ the clamp with positive weights).
  for (size_t i = 0; i < clamped[0].size(); ++i) {
    const float largest = std::max({clamped[0][i], clamped[1][i], clamped[2][i]});
    CHECK(largest <= 0.05f * 1.00001f);
    mean_clamped += clamped[1][i];
    mean_plain += plain[1][i];
    above += std::max({plain[0][i], plain[1][i], plain[2][i]}) > 0.05f;
  }
  REQUIRE(above > 0);  // the unclamped render does exceed it (the clamp does something here)
  CHECK(mean_clamped < mean_plain);

  Imf::InputFile file((dir / "clamped.exr").c_str());
  const auto* value = file.header().findTypedAttribute<Imf::DoubleAttribute>("rimu:maxSampleValue");
  const auto* count = file.header().findTypedAttribute<Imf::DoubleAttribute>("rimu:samplesClamped");
  REQUIRE(value);
  REQUIRE(count);
  CHECK(value->value() == 0.05);
  CHECK(count->value() > 0.0);
  CHECK(log.str().find("clamped samples") == std::string::npos);  // quiet
  Imf::InputFile plain_file((dir / "plain.exr").c_str());
  CHECK_FALSE(plain_file.header().findTypedAttribute<Imf::DoubleAttribute>("rimu:samplesClamped"));
}

TEST_CASE("sample clamp: partials with different clamps are not merged") {
  const test::ScratchFolder dir("sample_clamp_merge");
  RenderJob a = clamp_test_job(dir / "a.exr");
  a.samples_per_pixel = 4;
  a.samples = SampleRange{0, 2};
  a.max_sample_value = 0.05;
  RenderJob b = a;
  b.exr_output = dir / "b.exr";
  b.samples = SampleRange{2, 4};
  RenderJob c = b;
  c.exr_output = dir / "c.exr";
  c.max_sample_value = 0.5;
  std::ostringstream log;
  run_render_job(a, log);
  run_render_job(b, log);
  run_render_job(c, log);
  CHECK(read_partial_exr(dir / "a.exr", false).max_sample_value == 0.05);
  MergeResult merged = merge_partials({dir / "a.exr", dir / "b.exr"}, dir / "ab.exr", {}, log);
  CHECK(merged.samples_per_pixel == 4);
  Imf::InputFile file((dir / "ab.exr").c_str());
  REQUIRE(file.header().findTypedAttribute<Imf::DoubleAttribute>("rimu:maxSampleValue"));
  try {
    merge_partials({dir / "a.exr", dir / "c.exr"}, dir / "ac.exr", {}, log);
    FAIL("merged");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("sample clamp") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(dir / "ac.exr"));
}

TEST_CASE("sample clamp: the scene key is checked") {
  const fs::path box = default_scene_path(test::library());
  const nlohmann::json document = nlohmann::json::parse(std::ifstream(box));
  for (const char* bad : {"0", "-1", "\"high\""}) {
    CAPTURE(bad);
    nlohmann::json scene = document;
    scene["film"]["max_sample_value"] = nlohmann::json::parse(bad);
    CHECK_THROWS_WITH_AS(load_scene(scene, "box.json", box.parent_path(), test::library()),
                         doctest::Contains("/film/max_sample_value"), InputError);
  }
  nlohmann::json scene = document;
  scene["film"]["max_sample_value"] = 20;
  CHECK(load_scene(scene, "box.json", box.parent_path(), test::library())->settings.max_sample_value == 20.0);
}
