// pbrt-v3 files are refused at their first pbrt-v3-only construct with a message that says what the file is and
// names the command that upgrades it (docs/pbrt-import.md, "pbrt-v3 files").
#include <doctest/doctest.h>

#include "pbrt_test_support.h"

namespace rimu {
namespace {

const std::string kWorld = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

TEST_CASE("pbrt-v3: a 'color' parameter names the file, line, pbrt-v4's name and the upgrade command") {
  const std::string e = test::pbrt_import_error(kWorld + "Material \"diffuse\" \"color reflectance\" [0.5 0.5 0.5]\n", "old.pbrt");
  CHECK_CONTAINS(e, "old.pbrt:4", "'color'", "pbrt-v3", "'rgb'", "pbrt --upgrade");
}

TEST_CASE("pbrt-v3: materials that only pbrt-v3 has are refused with their pbrt-v4 counterpart") {
  for (const auto& [v3, v4] : std::initializer_list<std::pair<std::string, std::string>>{
           {"matte", "diffuse"}, {"plastic", "coateddiffuse"}, {"uber", "coateddiffuse"},
           {"substrate", "coateddiffuse"}, {"translucent", "diffusetransmission"}, {"mirror", "conductor"},
           {"metal", "conductor"}, {"glass", "dielectric"}, {"kdsubsurface", "subsurface"}, {"disney", "diffuse"}}) {
    CAPTURE(v3);
    CHECK_CONTAINS(test::pbrt_import_error(kWorld + "Material \"" + v3 + "\"\n"), "t.pbrt:4", "\"" + v3 + "\"",
                   "pbrt-v3", "\"" + v4 + "\"", "pbrt --upgrade");
    CHECK_CONTAINS(test::pbrt_import_error(kWorld + "MakeNamedMaterial \"m\" \"string type\" \"" + v3 + "\"\n"),
                   "t.pbrt:4", "pbrt-v3", "pbrt --upgrade");
  }
}

TEST_CASE("pbrt-v3: the message says that pbrt's upgrader leaves included files as they are") {
  CHECK_CONTAINS(test::pbrt_import_error(kWorld + "Material \"matte\"\n"), "leaves the files it Includes",
                 "upgrade each of them");
}

TEST_CASE("pbrt-v3: 'fourier', which pbrt-v4's upgrader keeps, is listed with a stand-in, not refused") {
  // The upgrader warns and writes "fourier" again, so an upgraded file still holds it: refusing it as pbrt-v3
  // would send the user round the same loop. pbrt-v4 itself refuses the name; Rimu lists it as it lists "measured".
  const PbrtImport imported = test::import_pbrt_test_text(
      kWorld + "MakeNamedMaterial \"m\" \"string type\" \"fourier\" \"string bsdffile\" \"x.bsdf\"\n");
  REQUIRE(!imported.ignored.empty());
  CHECK_CONTAINS(imported.ignored.front().what, "Material \"fourier\"", "pbrt-v4 no longer reads", "stands in");
  PbrtImportOptions strict;
  strict.strict = true;
  CHECK(test::pbrt_import_error(kWorld + "Material \"fourier\"\n", "t.pbrt", strict) != "no error");
}

TEST_CASE("pbrt-v3: a 'heterogeneous' medium, which the upgrader leaves, is read as the 'uniformgrid' it means") {
  const auto medium = [](const std::string& type) {
    return kWorld + "MakeNamedMedium \"smoke\" \"string type\" \"" + type +
           "\" \"integer nx\" 2 \"integer ny\" 1 \"integer nz\" 1 \"float density\" [0.5 1]\n"
           "AttributeBegin\nMediumInterface \"smoke\" \"\"\nMaterial \"interface\"\n"
           "Shape \"sphere\" \"float radius\" 1\nAttributeEnd\n";
  };
  const PbrtImport v3 = test::import_pbrt_test_text(medium("heterogeneous"));
  const PbrtImport v4 = test::import_pbrt_test_text(medium("uniformgrid"));
  CHECK(v3.ignored.empty());
  REQUIRE(v3.document.contains("media"));
  CHECK(v3.document["media"] == v4.document["media"]);
  CHECK(v3.document["shapes"] == v4.document["shapes"]);
}

TEST_CASE("pbrt-v3: a 'color' texture is refused with the upgrade command") {
  CHECK_CONTAINS(test::pbrt_import_error(kWorld + "Texture \"c\" \"color\" \"checkerboard\"\n"), "t.pbrt:4",
                 "\"color\"", "pbrt-v3", "\"spectrum\"", "pbrt --upgrade");
}

TEST_CASE("pbrt-v3 detection leaves pbrt-v4's own names alone") {
  CHECK(test::pbrt_import_error(kWorld + "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
                                         "Texture \"c\" \"spectrum\" \"checkerboard\"\n"
                                         "MakeNamedMaterial \"glass\" \"string type\" \"dielectric\"\n") == "no error");
}

}  // namespace
}  // namespace rimu
