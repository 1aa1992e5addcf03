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
           {"metal", "conductor"}, {"glass", "dielectric"}}) {
    CAPTURE(v3);
    CHECK_CONTAINS(test::pbrt_import_error(kWorld + "Material \"" + v3 + "\"\n"), "t.pbrt:4", "\"" + v3 + "\"",
                   "pbrt-v3", "\"" + v4 + "\"", "pbrt --upgrade");
    CHECK_CONTAINS(test::pbrt_import_error(kWorld + "MakeNamedMaterial \"m\" \"string type\" \"" + v3 + "\"\n"),
                   "t.pbrt:4", "pbrt-v3", "pbrt --upgrade");
  }
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
