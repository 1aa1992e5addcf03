// rimu-light writes only light definitions it reads back: a property test over random and extreme option values.
// Whatever light_from_options() accepts, light_definition_json() writes and read_light_definition() reads back to the
// same definition (bit-identical numbers: JSON numbers are printed in the shortest form that round-trips), which
// validates again and which a scene includes. What it refuses is refused with an InputError naming the option, never written.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <fstream>
#include <random>
#include <regex>
#include <unistd.h>

#include "render/scene/json_cursor.h"
#include "render/light_options.h"
#include "render/scene/scene.h"
#include "test_support.h"

using namespace rimu;

namespace {

// Values a hostile or careless user types: the range edges, just outside them, overflow, underflow, NaN, infinity.
const double kExtremes[] = {0.0,     -0.0,   1e-300, 1e-30, 1e-29, 0.01,  0.009,   1.0,     40.0,    179.9,
                            179.91,  180.0,  1e29,   1e30,  1.0000001e30, 1e308, -1e308, -50.0, -50.01, 50.0,
                            50.01,   -1.0,   std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN(),
                            std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max()};

double draw(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> pick(0, 2);
  switch (pick(rng)) {
    case 0: return kExtremes[std::uniform_int_distribution<size_t>(0, std::size(kExtremes) - 1)(rng)];
    case 1: return std::uniform_real_distribution<double>(-200.0, 200.0)(rng);
    default: return std::exp2(std::uniform_real_distribution<double>(-1100.0, 1100.0)(rng));  // 0 .. inf
  }
}

bool same_json_numbers(const nlohmann::json& a, const nlohmann::json& b) { return a == b; }

}  // namespace

TEST_CASE("rimu-light definitions: whatever is written is read back unchanged, whatever is refused names an option") {
  SpectralLibrary& library = test::library();
  const std::filesystem::path here = std::filesystem::current_path();
  std::mt19937_64 rng(20261201);
  const char* types[] = {"point", "spot", "distant", "environment"};
  const char* shapes[] = {"", "cct", "daylight", "illuminant"};
  int written = 0, refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const std::string type = types[trial % 4];
    SpotOptions spot;
    spot.cone_deg = draw(rng);
    spot.softness_deg = trial % 3 == 0 ? 0.0 : std::abs(draw(rng));
    spot.power_convention = trial % 5 == 0 ? "point" : "cone";
    LightAmountOptions amounts;
    const double value = draw(rng);
    switch ((trial / 4) % 6) {
      case 0: amounts.lumens = value; break;
      case 1: amounts.candela = value; break;
      case 2: amounts.lux = value; break;
      case 3: amounts.nits = value; break;
      case 4: amounts.watts = value; break;
      default: amounts.ev = value; break;
    }
    LightShapeOptions shape;
    const std::string which = shapes[(trial / 24) % 4];
    if (which == "cct") shape.cct = std::to_string(1000.0 + std::abs(std::fmod(value, 24000.0)));
    if (which == "daylight") shape.daylight = std::to_string(4000.0 + std::abs(std::fmod(value, 21000.0)));
    if (which == "illuminant") shape.illuminant = trial % 2 ? "F11" : "D65";
    CAPTURE(trial);
    CAPTURE(type);
    CAPTURE(value);
    CAPTURE(spot.cone_deg);
    CAPTURE(spot.softness_deg);
    LightDefinition light;
    try {
      light = light_from_options(type, spot, amounts, shape, library, here);
    } catch (const InputError& e) {
      // Refused: the message names the option (or the "amount" of the definition when the unit does not fit the type).
      CHECK(!e.where().key.empty());
      ++refused;
      continue;
    }
    ++written;
    const std::string text = light_definition_json(light).dump(2);
    CAPTURE(text);
    CHECK(text.find("null") == std::string::npos);  // a non-finite number is written as null by nlohmann-json
    LightDefinition back;
    REQUIRE_NOTHROW(back = read_light_definition(parse_json_text(text, "lamp.json"), "lamp.json"));
    CHECK(back.geometry.kind == light.geometry.kind);
    CHECK(back.amount.unit == light.amount.unit);
    CHECK(back.amount.value == light.amount.value);
    CHECK(same_json_numbers(back.spectrum, light.spectrum));
    if (light.geometry.kind == EmitterKind::spot) {
      CHECK(back.geometry.outer_half_angle_deg == light.geometry.outer_half_angle_deg);
      CHECK(back.geometry.inner_half_angle_deg == light.geometry.inner_half_angle_deg);
      CHECK(back.geometry.spot_power == light.geometry.spot_power);
    }
    CHECK_NOTHROW(validate_light_definition(back, library, here, {"lamp.json", 0, ""}));
    // A scene includes what rimu-light writes, too (the first accepted cases: a scene load builds Embree geometry).
    if (written <= 60) {
      const std::filesystem::path folder =
          std::filesystem::temp_directory_path() / ("rimu-light-round-trip-" + std::to_string(::getpid()));
      std::filesystem::create_directories(folder);
      std::ofstream(folder / "lamp.json") << text;
      nlohmann::json placed = {{"include", "lamp.json"}};
      if (light.geometry.kind == EmitterKind::point || light.geometry.kind == EmitterKind::spot)
        placed["position"] = {0, 2, 0};
      if (light.geometry.kind == EmitterKind::spot || light.geometry.kind == EmitterKind::distant)
        placed["direction"] = {0, -1, 0};
      const nlohmann::json scene = {
          {"camera", {{"from", {0, 1, 3}}, {"to", {0, 0, 0}}, {"up", {0, 1, 0}}, {"vertical_fov_deg", 30}}},
          {"materials", {{"grey", {{"type", "diffuse"}, {"reflectance", 0.5}}}}},
          {"lights", {placed}},
          {"shapes", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 0.5}, {"material", "grey"}}}}};
      CHECK_NOTHROW(load_scene(scene, "round trip scene", folder, library));
      std::filesystem::remove_all(folder);
    }
  }
  // Both outcomes happen often, so the property was exercised on both sides.
  CHECK(written > 300);
  CHECK(refused > 300);
}

TEST_CASE("rimu-light definitions: the range edges are written and read back, one step outside is refused") {
  SpectralLibrary& library = test::library();
  const std::filesystem::path here = std::filesystem::current_path();
  const auto author = [&](const std::string& type, double cone_deg, LightAmountOptions amounts) {
    SpotOptions spot;
    spot.cone_deg = cone_deg;
    const LightDefinition light = light_from_options(type, spot, amounts, {}, library, here);
    return read_light_definition(parse_json_text(light_definition_json(light).dump(), "x.json"), "x.json");
  };
  LightAmountOptions lm;
  for (double v : {kMinLightAmount, kMaxLightAmount}) {
    lm.lumens = v;
    CHECK(author("point", 40, lm).amount.value == v);
  }
  lm.lumens = 800;
  for (double cone : {kMinConeAngleDeg, kMaxConeAngleDeg}) CHECK(author("spot", cone, lm).geometry.outer_half_angle_deg == cone / 2);
  LightAmountOptions ev;
  for (double v : {kMinEv100, kMaxEv100}) {
    ev.ev = v;
    CHECK(author("distant", 40, ev).amount.value == v);
  }
  // The cases the hardening found written as unreadable files: now refused at the option.
  const auto refused_at = [&](const std::string& type, double cone_deg, LightAmountOptions amounts) {
    try {
      author(type, cone_deg, amounts);
    } catch (const InputError& e) {
      return e.where().key;
    }
    return std::string("accepted");
  };
  LightAmountOptions bad;
  bad.lumens = std::numeric_limits<double>::infinity();
  CHECK(refused_at("point", 40, bad) == "--lumens");
  bad.lumens = 1e308;
  CHECK(refused_at("point", 40, bad) == "--lumens");
  CHECK(refused_at("spot", 1e-300, lm) == "--cone");
  LightAmountOptions bad_ev;
  bad_ev.ev = -1e308;
  CHECK(refused_at("distant", 40, bad_ev) == "--ev");
}

TEST_CASE("rimu-light options: a colour temperature is taken as 2700, 2700K or 2700 K") {
  CHECK(parse_temperature_k("2700", "--cct") == 2700.0);
  CHECK(parse_temperature_k("2700K", "--cct") == 2700.0);
  CHECK(parse_temperature_k("2700 k", "--cct") == 2700.0);
  CHECK_THROWS_WITH_AS(parse_temperature_k("warm", "--cct"), doctest::Contains("--cct"), InputError);
  CHECK_THROWS_WITH_AS(parse_temperature_k("2700 kelvin", "--cct"), doctest::Contains("2700K"), InputError);
  CHECK_THROWS_AS(parse_temperature_k("inf", "--cct"), InputError);
  LightShapeOptions shape;
  shape.cct = "2700K";
  CHECK(*shape.spectrum() == nlohmann::json{{"blackbody", 2700.0}});
}

TEST_CASE("rimu-light options: an area light converts but has no definition file") {
  CHECK(parse_light_type("area", LightTypeUse::conversion, "--type") == EmitterKind::area);
  CHECK_THROWS_WITH_AS(parse_light_type("area", LightTypeUse::definition, "--type"),
                       doctest::Contains("rimu-light convert --type area"), InputError);
  // The list of expected types is the list the command accepts.
  CHECK_THROWS_WITH_AS(parse_light_type("tube", LightTypeUse::definition, "--type"),
                       "--type: unknown light type 'tube'; expected point, spot, distant, environment", InputError);
}

TEST_CASE("rimu-light convert prints every value it assumed, and only those the result depends on") {
  SpectralLibrary& library = test::library();
  const std::filesystem::path here = std::filesystem::current_path();
  ConvertRequest r;
  r.from = "1600 lm";
  r.to = "cd";
  std::string text = convert_light_text(r, library, here);
  CHECK(text.rfind("1600 lm = 127.324 cd\n", 0) == 0);  // 1600 / 4π
  CHECK(text.find("assuming a point light (--type)") != std::string::npos);
  CHECK(text.find("illuminant E") == std::string::npos);  // lm to cd does not depend on the spectrum
  r.to = "W";
  r.type_given = true;
  text = convert_light_text(r, library, here);
  CHECK(text.find("--type") == std::string::npos);  // lm to W does not depend on the geometry
  CHECK(text.find("assuming the spectrum of illuminant E") != std::string::npos);
  r.to = "lx";
  text = convert_light_text(r, library, here);
  CHECK(text.find("at 1 m (--distance)") != std::string::npos);
  r.type = "spot";
  r.to = "cd";
  text = convert_light_text(r, library, here);
  CHECK(text.find("assuming a 40° cone") != std::string::npos);
  r.type = "area";
  r.to = "nt";
  text = convert_light_text(r, library, here);
  CHECK(text.find("assuming 1 m² emitting from one face (--area, --two-sided)") != std::string::npos);
  r.area_given = true;
  r.shape.cct = "2700K";
  r.to = "W/m2/sr";
  text = convert_light_text(r, library, here);
  CHECK(text.find("assuming") == std::string::npos);
}

TEST_CASE("rimu-light convert refuses what would overflow or is not a number, naming the option") {
  SpectralLibrary& library = test::library();
  const std::filesystem::path here = std::filesystem::current_path();
  const auto key_of = [&](ConvertRequest r) {
    try {
      convert_light_text(r, library, here);
    } catch (const InputError& e) {
      return e.where().key;
    }
    return std::string("accepted");
  };
  ConvertRequest r;
  r.from = "1e30 EV";
  r.to = "nt";
  r.type = "environment";
  CHECK(key_of(r) == "--from");
  r = {};
  r.from = "1000 lm";
  r.to = "nt";
  r.type = "area";
  r.area_m2 = 1e-308;
  CHECK(key_of(r) == "--area");
  r.area_m2 = std::numeric_limits<double>::quiet_NaN();
  CHECK(key_of(r) == "--area");
  r = {};
  r.from = "1000 lm";
  r.to = "lx";
  r.distance_m = 0.0;
  CHECK(key_of(r) == "--distance");
}

TEST_CASE("rimu-light inspect refuses a distance, angle or electrical power that would print NaN or infinity") {
  const auto key_of = [](InspectPoint p) {
    try {
      validate_inspect_point(p);
    } catch (const InputError& e) {
      return e.where().key;
    }
    return std::string("accepted");
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(key_of({}) == "accepted");
  CHECK(key_of({0.0, 0.0, std::nullopt}) == "--distance");
  CHECK(key_of({nan, 0.0, std::nullopt}) == "--distance");
  CHECK(key_of({1.0, nan, std::nullopt}) == "--angle");
  CHECK(key_of({1.0, 181.0, std::nullopt}) == "--angle");
  CHECK(key_of({1.0, 0.0, 0.0}) == "--electrical-watts");
  CHECK(key_of({1.0, 0.0, nan}) == "--electrical-watts");
  CHECK(key_of({1.0, -180.0, 60.0}) == "accepted");
  // And the report itself: a valid light inspected at a valid point prints no nan or inf.
  SpectralLibrary& library = test::library();
  LightDefinition light;
  light.amount = {kMaxLightAmount, LightUnit::lumen};
  const std::string text = inspect_light_text(light, library, ".", {1e-3, 0.0, kMinLightAmount});
  // As printf and iostreams spell them ("luminance" contains "nan", so whole words only).
  CHECK_FALSE(std::regex_search(text, std::regex("\\b(nan|inf|infinity)\\b", std::regex::icase)));
}
