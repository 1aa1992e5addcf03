// Light groups (render/scene/scene_light_groups.h, render/film/film.h, render/output/exr_relight.h): every light's
// emission lands in its group's EXR layer, the layers sum to the beauty within float rounding (surface and
// volumetric integrators, partials and their merge), `--group x=0` shows the beauty minus layer x exactly, a scene
// without groups writes no layers, and bad names or options are errors naming the key or option.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "input_error_check.h"
#include "light_groups_support.h"
#include "test_support.h"
#include "render/output/display_output.h"
#include "render/output/exr_display_source.h"
#include "render/output/exr_relight.h"
#include "render/output/merge_partials.h"
#include "render/render_job.h"
#include "render/scene/scene.h"
#include "render/camera/physical_camera.h"
#include "spectral/spectra/blackbody_spectrum.h"

using namespace rimu;
namespace fs = std::filesystem;
using json = nlohmann::json;

using namespace rimu::test;

namespace {

fs::path example_scene() { return light_groups_example(); }

}  // namespace

TEST_CASE("light groups: the layers sum to the beauty (surface integrator: environment, sun, spot, emissive shape)") {
  test::ScratchFolder folder("light_groups_sum");
  render(tiny_job(example_scene(), folder / "groups.exr"));
  const ExrChannels exr = read_channels(folder / "groups.exr");
  CHECK(exr.light_groups == "sky,sun,lamps,ungrouped");
  check_layers_sum_to_beauty(exr, {"sky", "sun", "lamps", "ungrouped"});
}

TEST_CASE("light groups: the layers sum to the beauty in a medium (volumetric integrator, equiangular sampling)") {
  test::ScratchFolder folder("light_groups_medium");
  json scene = json::parse(std::ifstream(example_scene()));
  // Haze in an invisible box around the camera and the scene (the sky and sun come in through it): the volumetric
  // integrator, with equiangular sampling towards the point and spot lights.
  scene["materials"]["haze_boundary"] = {{"type", "diffuse"}, {"reflectance", 0.5}};
  scene["media"] = {{"haze", {{"type", "homogeneous"}, {"sigma_a", {{"constant", 0.02}}},
                              {"sigma_s", {{"constant", 0.3}}}, {"boundary_material", "haze_boundary"},
                              {"index_matched", true}, {"contains_camera", true}}}};
  scene["shapes"].push_back({{"type", "box"}, {"material", "haze_boundary"}, {"min", {-3.5, -0.1, -3.5}},
                             {"max", {3.5, 3.0, 3.5}}});
  std::ofstream(folder / "hazy.json") << scene.dump();
  render(tiny_job(folder / "hazy.json", folder / "hazy.exr"));
  check_layers_sum_to_beauty(read_channels(folder / "hazy.exr"), {"sky", "sun", "lamps", "ungrouped"});
}

TEST_CASE("light groups: a scene without light_group keys writes no layers") {
  test::ScratchFolder folder("light_groups_none");
  render(tiny_job(test::library().root() / "scenes" / "cornell_box" / "scene.json", folder / "plain.exr"));
  const ExrChannels exr = read_channels(folder / "plain.exr");
  CHECK(exr.light_groups.empty());
  CHECK_FALSE(exr.has_layer);
  CHECK(exr.channels.size() == 3);
}

TEST_CASE("light groups: two partials merged keep layers that sum to the beauty and match one render") {
  test::ScratchFolder folder("light_groups_merge");
  render(tiny_job(example_scene(), folder / "a.exr", SampleRange{0, 3}));
  render(tiny_job(example_scene(), folder / "b.exr", SampleRange{3, 8}));
  render(tiny_job(example_scene(), folder / "whole.exr"));
  std::ostringstream log;
  merge_partials({folder / "a.exr", folder / "b.exr"}, folder / "merged.exr", MergeOptions{}, log);
  const ExrChannels merged = read_channels(folder / "merged.exr");
  const ExrChannels whole = read_channels(folder / "whole.exr");
  CHECK(merged.light_groups == "sky,sun,lamps,ungrouped");
  check_layers_sum_to_beauty(merged, {"sky", "sun", "lamps", "ungrouped"});
  // The merge adds the same per-sample values in another grouping of the double sums: the written floats agree to
  // within one float32 rounding (2⁻²⁴ relative) plus the doubles' (negligible): 2⁻²³.
  for (const auto& [name, values] : whole.channels) {
    CAPTURE(name);
    const auto& other = merged.channels.at(name);
    double worst = 0.0;
    for (size_t i = 0; i < values.size(); ++i)
      if (values[i] != 0.0f) worst = std::max(worst, std::abs(double(other[i]) - values[i]) / std::abs(double(values[i])));
    CHECK(worst <= 0x1p-23);
  }
  // A partial of another light grouping does not merge.
  json regrouped = json::parse(std::ifstream(example_scene()));
  regrouped["lights"][3]["light_group"] = "fill";
  std::ofstream(folder / "regrouped.json") << regrouped.dump();
  render(tiny_job(folder / "regrouped.json", folder / "c.exr", SampleRange{3, 8}));
  test::input_error([&] { merge_partials({folder / "a.exr", folder / "c.exr"}, folder / "bad.exr", MergeOptions{}, log); },
                    {"light groups (rimu:lightGroups)"});
  CHECK_FALSE(fs::exists(folder / "bad.exr"));
}

TEST_CASE("light groups: --group x=0 shows the beauty minus layer x exactly, scales act on their layer") {
  test::ScratchFolder folder("light_groups_display");
  render(tiny_job(example_scene(), folder / "final.exr"));
  render(tiny_job(example_scene(), folder / "partial.exr", SampleRange{0, 8}));
  for (const char* name : {"final.exr", "partial.exr"}) {
    CAPTURE(name);
    const ExrDisplaySource relit = read_exr_for_display(folder / name, test::library());
    const ExrDisplaySource plain = read_exr_for_display(folder / name, test::library());
    rebalance_light_groups(*relit.film, {{"lamps", 0.0}, {"sun", 2.0}}, name);
    // The expected film: beauty − lamps + sun, built from the read film's own sums.
    FilmOptions options{plain.film->width(), plain.film->height(), plain.film->pixel_bounds(), 0};
    Film expected(options, plain.film->response());
    expected.set_output_transform(plain.film->output_transform());
    FilmTile tile = expected.make_tile(expected.pixel_bounds());
    const PixelBounds& b = expected.pixel_bounds();
    const int first_group = FilmTile::kFirstBin;  // no spectral bins
    for (int y = b.y0; y < b.y1; ++y)
      for (int x = b.x0; x < b.x1; ++x) {
        const double* p = plain.film->accumulators(x, y);
        double* q = tile.pixel(x, y);
        for (int c = 0; c < 3; ++c) q[c] = p[c] - p[first_group + 3 * 2 + c] + p[first_group + 3 * 1 + c];
        q[FilmTile::kWeight] = p[FilmTile::kWeight];
      }
    expected.merge_tile(tile);
    for (int y = b.y0; y < b.y1; ++y)
      for (int x = b.x0; x < b.x1; ++x) {
        // Two groups change, so the sums are added in another order than here: equal up to a few double roundings
        // of the terms' magnitudes (4·2⁻⁵³ of beauty + lamps + sun).
        const double* p = plain.film->accumulators(x, y);
        for (int c = 0; c < 3; ++c) {
          const double magnitude = (std::abs(p[c]) + std::abs(p[first_group + 6 + c]) + std::abs(p[first_group + 3 + c])) /
                                   p[FilmTile::kWeight];
          CHECK(std::abs(relit.film->pixel_value(x, y)[size_t(c)] - expected.pixel_value(x, y)[size_t(c)]) <=
                4 * 0x1p-53 * magnitude);
        }
        // The layers still sum to the beauty after rebalancing: the deltas added to both are the same doubles, so
        // the render's own float discrepancy (check_layers_sum_to_beauty's bound) is all that remains.
        std::array<double, 3> sum{}, magnitude{};
        for (int g = 0; g < 4; ++g)
          for (int c = 0; c < 3; ++c) {
            sum[size_t(c)] += relit.film->group_value(x, y, g)[size_t(c)];
            magnitude[size_t(c)] += std::abs(plain.film->group_value(x, y, g)[size_t(c)]);
          }
        for (int c = 0; c < 3; ++c)
          CHECK(std::abs(sum[size_t(c)] - relit.film->pixel_value(x, y)[size_t(c)]) <=
                32 * 0x1p-24 * (magnitude[size_t(c)] + std::abs(plain.film->pixel_value(x, y)[size_t(c)])));
      }
  }
  // Through the display image: --group lamps=0 writes the same PNG as the film of beauty − lamps.
  const ExrDisplaySource plain = read_exr_for_display(folder / "final.exr", test::library());
  FilmOptions options{plain.film->width(), plain.film->height(), plain.film->pixel_bounds(), 0};
  Film minus_lamps(options, plain.film->response());
  FilmTile tile = minus_lamps.make_tile(minus_lamps.pixel_bounds());
  const PixelBounds& b = minus_lamps.pixel_bounds();
  for (int y = b.y0; y < b.y1; ++y)
    for (int x = b.x0; x < b.x1; ++x) {
      const double* p = plain.film->accumulators(x, y);
      for (int c = 0; c < 3; ++c) tile.pixel(x, y)[c] = p[c] - p[FilmTile::kFirstBin + 3 * 2 + c];
      tile.pixel(x, y)[FilmTile::kWeight] = 1.0;
    }
  minus_lamps.merge_tile(tile);
  std::ostringstream log;
  write_exr_display_image(folder / "final.exr", folder / "relit.png", DisplayOptions{}, false, log,
                          ExrRelightOptions{{{"lamps", 0.0}}, std::nullopt});
  write_display_image(folder / "expected.png", minus_lamps, DisplayOptions{});
  auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  CHECK(bytes(folder / "relit.png") == bytes(folder / "expected.png"));
  // And all groups at 1 is the image as rendered.
  write_exr_display_image(folder / "final.exr", folder / "ones.png", DisplayOptions{}, false, log,
                          ExrRelightOptions{{{"lamps", 1.0}, {"sky", 1.0}}, std::nullopt});
  write_exr_display_image(folder / "final.exr", folder / "asis.png", DisplayOptions{}, false, log);
  CHECK(bytes(folder / "ones.png") == bytes(folder / "asis.png"));
}

TEST_CASE("light groups: display errors name the option and list the groups") {
  test::ScratchFolder folder("light_groups_display_errors");
  render(tiny_job(example_scene(), folder / "groups.exr"));
  render(tiny_job(test::library().root() / "scenes" / "cornell_box" / "scene.json", folder / "plain.exr"));
  std::ostringstream log;
  test::input_error([&] {
    write_exr_display_image(folder / "groups.exr", folder / "x.png", DisplayOptions{}, false, log,
                            ExrRelightOptions{{{"lamp", 0.0}}, std::nullopt});
  }, {"--group", "no light group 'lamp'", "sky,sun,lamps,ungrouped"});
  test::input_error([&] {
    write_exr_display_image(folder / "plain.exr", folder / "x.png", DisplayOptions{}, false, log,
                            ExrRelightOptions{{{"sun", 2.0}}, std::nullopt});
  }, {"--group", "has no light groups"});
  CHECK_FALSE(fs::exists(folder / "x.png"));
  test::input_error([] { parse_light_group_scales("sun=2,lamps", "--group"); }, {"--group", "'lamps'"});
  test::input_error([] { parse_light_group_scales("sun=-1", "--group"); }, {"--group", "from 0 to 1e6"});
  test::input_error([] { parse_light_group_scales("sun=1,sun=2", "--group"); }, {"--group", "given twice"});
  test::input_error([] { parse_display_white("0.7,0.4", test::library(), "--white-balance"); },
                    {"--white-balance", "x + y < 1"});
  test::input_error([] { parse_display_white("warm", test::library(), "--white-balance"); }, {"--white-balance"});
}

TEST_CASE("light groups: --white-balance adapts the chosen white to D65") {
  test::ScratchFolder folder("light_groups_white");
  render(tiny_job(example_scene(), folder / "groups.exr"));
  ExrDisplaySource source = read_exr_for_display(folder / "groups.exr", test::library());
  // A 2700 K blackbody white, as the render's --white-balance 2700K would map it, and the same by chromaticity.
  const DisplayWhite kelvin = parse_display_white("2700K", test::library(), "--white-balance");
  const Matrix3 m = display_white_balance_matrix(kelvin, source.film->response(), test::library());
  const std::array<double, 3> w = film_channels(BlackbodySpectrum(2700.0, BlackbodySpectrum::Scale::peak_one),
                                                source.film->response());
  const std::array<double, 3> d65 = film_channels(*test::library().illuminant("D65"), source.film->response());
  const std::array<double, 3> mapped = m.apply(std::array<double, 3>{w[0] / w[1], 1.0, w[2] / w[1]});
  for (int c = 0; c < 3; ++c) CHECK(mapped[size_t(c)] == doctest::Approx(d65[size_t(c)] / d65[1]).epsilon(1e-9));
  const Chromaticity xy = chromaticity_of(Xyz{w[0], w[1], w[2]});
  const DisplayWhite by_xy = parse_display_white(std::to_string(xy.x) + "," + std::to_string(xy.y), test::library(),
                                                 "--white-balance");
  const Matrix3 m_xy = display_white_balance_matrix(by_xy, source.film->response(), test::library());
  // std::to_string keeps 6 decimals: the whites differ by ≤ 5e-7 in x and y, the matrices by about as much.
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) CHECK(m_xy(r, c) == doctest::Approx(m(r, c)).epsilon(1e-5));
  relight_exr_film(*source.film, ExrRelightOptions{{}, kelvin}, false, std::nullopt, "groups.exr", test::library());
  const PixelBounds& b = source.film->pixel_bounds();
  const std::array<double, 3> raw = source.film->pixel_value(b.x0, b.y0);
  const std::array<double, 3> shown = source.film->output_value(b.x0, b.y0);
  const std::array<double, 3> expected = m.apply(raw);
  for (int c = 0; c < 3; ++c) CHECK(shown[size_t(c)] == doctest::Approx(expected[size_t(c)]).epsilon(1e-12));
  // A white-balanced file whose balance is not known cannot be undone (light_groups_relight_test.cpp: one that is).
  test::input_error([&] {
    relight_exr_film(*source.film, ExrRelightOptions{{}, kelvin}, true, std::nullopt, "groups.exr", test::library());
  }, {"--white-balance", "cannot be undone"});
}

TEST_CASE("light groups: bad names and misplaced keys are errors naming the key") {
  auto load = [](const json& document) { return load_scene(document, "scene.json", ".", test::library()); };
  json base = json::parse(std::ifstream(example_scene()));
  for (const char* bad : {"", "two words", "sun.x", "X", "rimu", "S0", "albedo", "depth", "Half_Even", "naïve"}) {
    CAPTURE(bad);
    json scene = base;
    scene["lights"][0]["light_group"] = bad;
    test::input_error([&] { load(scene); }, {"/lights/0/light_group"});
  }
  json not_a_string = base;
  not_a_string["lights"][1]["light_group"] = 3;
  test::input_error([&] { load(not_a_string); }, {"/lights/1/light_group"});
  json dark_shape = base;
  dark_shape["shapes"][1]["light_group"] = "lamps";
  test::input_error([&] { load(dark_shape); }, {"/shapes/1/light_group", "emissive shapes"});
  // Every light kind takes the key: an IES-less kind list is covered by the example (environment, distant, spot,
  // point, emissive quad); the sky and sun of the daylight model too.
  json sky = base;
  sky["lights"][0] = {{"type", "cie_sky"}, {"sky_type", 12}, {"light_group", "daylight"},
                      {"sun_position", {{"elevation_deg", 30}, {"azimuth_deg", 120}}},
                      {"diffuse_horizontal_illuminance_lx", 10000}};
  const auto loaded = load(sky);
  CHECK(loaded->light_groups == std::vector<std::string>{"daylight", "sun", "lamps", "ungrouped"});
  // Group indices follow first use; the unmarked point light and no other joins "ungrouped".
  CHECK(loaded->lights[0]->light_group() == 0);
  CHECK(loaded->lights[3]->light_group() == 3);
  CHECK(loaded->lights[4]->light_group() == 2);  // the emissive quad, after the four lights
  json ungrouped_named = base;
  ungrouped_named["lights"][0]["light_group"] = "ungrouped";
  const auto named = load(ungrouped_named);
  CHECK(named->light_groups == std::vector<std::string>{"ungrouped", "sun", "lamps"});
  CHECK(named->lights[3]->light_group() == 0);
  json plain = base;
  for (auto& l : plain["lights"]) l.erase("light_group");
  plain["shapes"][2].erase("light_group");
  const auto none = load(plain);
  CHECK(none->light_groups.empty());
  for (const auto& l : none->lights) CHECK(l->light_group() == 0);
}
