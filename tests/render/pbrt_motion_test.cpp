// pbrt-v4's motion blur on import: ActiveTransform chooses which of the two CTMs (at TransformTimes' start and
// end) statements change; a shape, an ObjectInstance or the camera whose two differ moves, and Rimu gets where it is
// at shutteropen and shutterclose ("transform"/"transform_end", "from_end"/"to_end"/"up_end").
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "integration_support.h"
#include "pbrt_test_support.h"
#include "transport/geometry/motion_transform.h"

using namespace rimu;
using namespace rimu::test::pbrt_t;
using nlohmann::json;

namespace {

constexpr double kPiPbrtMotion = 3.14159265358979323846;

const std::string kTriangle = "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0] \"integer indices\" [0 1 2]\n";

// A shape's placement key ("transform" or "transform_end", one matrix step) as a Transform.
Transform placement(const json& shape, const char* key) {
  REQUIRE(shape.contains(key));
  const json& rows = shape[key].at(0).at("matrix");
  std::array<float, 12> m{};
  for (size_t k = 0; k < 12; ++k) m[k] = rows.at(k).get<float>();
  bool invertible = false;
  return Transform::from_rows(m, invertible);
}

Vec3 vec3_of(const json& v) { return {v.at(0).get<float>(), v.at(1).get<float>(), v.at(2).get<float>()}; }

bool listed(const PbrtImport& imported, const std::string& fragment) {
  for (const PbrtIgnored& i : imported.ignored)
    if (i.what.find(fragment) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("pbrt motion: ActiveTransform EndTime moves a shape, statements under All move both ends") {
  const PbrtImport imported = import_text(kCamera + "WorldBegin\nAttributeBegin\n  Translate 0 0 -1\n"
                                                    "  ActiveTransform EndTime\n  Translate 2 0 0\n  ActiveTransform All\n"
                                                    "  Scale 0.5 0.5 0.5\n" + kTriangle +
                                          "AttributeEnd\n" + kTriangle);
  CHECK(imported.ignored.empty());
  const json& shapes = imported.document["shapes"];
  const Transform start = placement(shapes[0], "transform"), end = placement(shapes[0], "transform_end");
  // The corner (1, 0, 0) of the half-size triangle: 2 apart at the two ends (the scale applies to both).
  CHECK(length(end.point({1, 0, 0}) - start.point({1, 0, 0})) == doctest::Approx(2.0));
  CHECK(length(end.vector({1, 0, 0})) == doctest::Approx(0.5));
  // AttributeEnd restores both CTMs: the next shape stays put.
  CHECK_FALSE(shapes[1].contains("transform_end"));
  // The document loads as a scene that moves.
  CHECK(test::scene_from_json(imported.document)->transport_view().has_motion);
}

TEST_CASE("pbrt motion: a shutter open for part of the TransformTimes takes the placements at its ends") {
  // TransformTimes 0 1 with a quarter turn; the shutter open from 0.5 to 1: the shape turns from 45° to 90°.
  const PbrtImport imported = import_text(
      "TransformTimes 0 1\n" + kCamera.substr(0, kCamera.size() - 1) + " \"float shutteropen\" 0.5 \"float shutterclose\" 1\n" +
      "WorldBegin\nActiveTransform EndTime\nRotate 90 0 0 1\nActiveTransform All\n" + kTriangle);
  CHECK(imported.ignored.empty());
  const json& shape = imported.document["shapes"][0];
  const Transform start = placement(shape, "transform"), end = placement(shape, "transform_end");
  // The world may be mirrored (docs/pbrt-import.md); angles between directions are not.
  const Vec3 x_open = start.vector({1, 0, 0}), x_close = end.vector({1, 0, 0});
  CHECK(std::acos(dot(x_open, x_close)) == doctest::Approx(kPiPbrtMotion / 4).epsilon(1e-5));
  CHECK(length(x_open) == doctest::Approx(1.0));
  // Without the motion the start would be the unrotated x axis: the open placement is the half-way one.
  const Transform still = placement(import_text(kCamera + "WorldBegin\nRotate 0.0001 0 0 1\n" + kTriangle).document["shapes"][0],
                                    "transform");
  CHECK(std::acos(std::fmin(1.0f, dot(x_open, still.vector({1, 0, 0})))) == doctest::Approx(kPiPbrtMotion / 4).epsilon(1e-4));
  // A shutter reaching beyond the TransformTimes is listed (pbrt holds the object still there).
  const PbrtImport beyond = import_text("TransformTimes 0 1\n" + kCamera.substr(0, kCamera.size() - 1) +
                                        " \"float shutterclose\" 2\nWorldBegin\nActiveTransform EndTime\nTranslate 1 0 0\n"
                                        "ActiveTransform All\n" + kTriangle);
  CHECK(listed(beyond, "beyond TransformTimes"));
}

TEST_CASE("pbrt motion: a moving camera, instance and sphere, lights and area lights stay at their start") {
  const PbrtImport imported = import_text(
      "LookAt 0 0 5  0 0 0  0 1 0\nActiveTransform EndTime\nTranslate 1 0 0\nActiveTransform All\nCamera \"perspective\"\n"
      "WorldBegin\n"
      "ObjectBegin \"tri\"\n" + kTriangle + "ObjectEnd\n"
      "AttributeBegin\n  ActiveTransform EndTime\n  Translate 0 3 0\n  ActiveTransform All\n  ObjectInstance \"tri\"\n"
      "  Shape \"sphere\" \"float radius\" 0.5\n"
      "  AreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n" + kTriangle +
      "AttributeEnd\n"
      "AttributeBegin\n  ActiveTransform StartTime\n  Translate 0 1 0\n  LightSource \"point\" \"rgb I\" [1 1 1]\nAttributeEnd\n");
  const json& camera = imported.document["camera"];
  // The camera moves 1 sideways in the camera's own frame (pbrt's CTM is camera-from-world).
  CHECK(length(vec3_of(camera["from_end"]) - vec3_of(camera["from"])) == doctest::Approx(1.0));
  CHECK(length(vec3_of(camera["to_end"]) - vec3_of(camera["from_end"])) == doctest::Approx(1.0));
  const json& shapes = imported.document["shapes"];
  REQUIRE(shapes.size() == 3);
  CHECK(shapes[0]["type"] == "instance");
  CHECK(length(placement(shapes[0], "transform_end").point({0, 0, 0}) - placement(shapes[0], "transform").point({0, 0, 0})) ==
        doctest::Approx(3.0));
  // A moving sphere is a mesh (Rimu's analytic spheres do not move).
  CHECK(shapes[1]["type"] == "triangles");
  CHECK(shapes[1].contains("transform_end"));
  // The area light stays, listed; so does the point light.
  CHECK(shapes[2].contains("emission"));
  CHECK_FALSE(shapes[2].contains("transform_end"));
  CHECK(listed(imported, "moving area light"));
  CHECK(listed(imported, "LightSource \"point\" that moves"));
  const auto scene = test::scene_from_json(imported.document);
  CHECK(scene->transport_view().has_motion);
}

TEST_CASE("pbrt motion: a turning ObjectInstance turns as pbrt-v4 turns it, in its camera-world rendering space") {
  // pbrt-v4 interpolates an instance's placements C⁻¹·M·C, C the translation to the camera (0, 0, 5): a quarter turn
  // about x placed at (2, 0, 0) carries the object's origin half-way to (2, 0, 0) + (0, 2.5, −2.5) − R45·(0, 0, 5) =
  // (2, 1.036, −1.036), where a turn about its own origin would leave it at (2, 0, 0). The world is mirrored in x
  // here (pbrt's image-right is −x for this camera; docs/pbrt-import.md).
  const PbrtImport imported = import_text(kCamera + "WorldBegin\nObjectBegin \"tri\"\n" + kTriangle + "ObjectEnd\n"
                                          "Translate 2 0 0\nActiveTransform EndTime\nRotate 90 1 0 0\nActiveTransform All\n"
                                          "ObjectInstance \"tri\"\n");
  const json& instance = imported.document["shapes"][0];
  const json& prototype = imported.document["prototypes"][instance["prototype"].get<std::string>()];
  // The prototype's copy is shifted by C⁻¹ = (0, 0, −5) after its own placement.
  const json& shift = prototype[0]["transform"].back()["translate"];
  CHECK(vec3_of(shift) == Vec3{0, 0, -5});
  bool valid = false;
  const MotionTransform motion(placement(instance, "transform"), placement(instance, "transform_end"), valid);
  REQUIRE(valid);
  const float y = float(5.0 * std::sqrt(0.5) - 2.5);
  CHECK(length(motion.at(0.5f).point(vec3_of(shift)) - Vec3{-2, y, -y}) < 1e-5f);
  // At the ends the placements are pbrt's CTMs (the origin at (±2, 0, 0)).
  CHECK(length(motion.at(0.0f).point(vec3_of(shift)) - Vec3{-2, 0, 0}) < 1e-5f);
  CHECK(length(motion.at(1.0f).point(vec3_of(shift)) - Vec3{-2, 0, 0}) < 1e-5f);
  CHECK(test::scene_from_json(imported.document)->transport_view().has_motion);
}

TEST_CASE("pbrt motion: bad ActiveTransform and TransformTimes are errors with their line") {
  CHECK_CONTAINS(import_error(kCamera + "WorldBegin\nActiveTransform Sometimes\n"), "t.pbrt:4", "StartTime, EndTime or All");
  CHECK_CONTAINS(import_error("TransformTimes 1 0\n" + kCamera + "WorldBegin\n"), "t.pbrt:1", "TransformTimes");
  CHECK_CONTAINS(import_error(kCamera + "WorldBegin\nTransformTimes 0 1\n"), "t.pbrt:4", "before WorldBegin");
}
