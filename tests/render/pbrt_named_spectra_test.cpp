// pbrt-v4's named spectra (metal-*-eta/-k, glass-*) imported onto Rimu's copies of pbrt's own tables
// (data/spectra/materials/pbrt_*.csv, src/spectral/library/optical_constants.cpp), so that an imported scene reflects and
// refracts as in pbrt; Rimu's own "gold", "bk7", … keep their names and sources.
#include <doctest/doctest.h>

#include <cmath>

#include "integration_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "spectral/library/optical_constants.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_named_spectra_test {
const std::string kCamera = "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

json material_of(const std::string& statement) {
  const PbrtImport imported = import_pbrt_text(kCamera + statement + "\nShape \"sphere\"", "t.pbrt", test::test_data("pbrt"), test::library());
  CHECK_MESSAGE(imported.ignored.empty(), describe_ignored(imported.ignored));
  const json& d = imported.document;
  CHECK_NOTHROW(load_scene(d, "t.pbrt", test::test_data("pbrt"), test::library()));
  return d["materials"][d["shapes"][0]["material"].get<std::string>()];
}

TEST_CASE("pbrt named spectra: every metal-*-eta/-k pair and every glass-* maps onto pbrt's own table") {
  const std::pair<const char*, const char*> metals[] = {{"Au", "pbrt-au"},     {"Ag", "pbrt-ag"},   {"Cu", "pbrt-cu"}, {"Al", "pbrt-al"},
                                                        {"CuZn", "pbrt-cuzn"}, {"MgO", "pbrt-mgo"}, {"TiO2", "pbrt-tio2"}};
  for (const auto& [symbol, name] : metals) {
    CAPTURE(symbol);
    const json m = material_of(std::string("Material \"conductor\" \"spectrum eta\" \"metal-") + symbol + "-eta\" \"spectrum k\" \"metal-" +
                               symbol + "-k\"");
    CHECK(m == json({{"type", "conductor"}, {"metal", name}}));
  }
  const std::pair<const char*, const char*> glasses[] = {{"BK7", "pbrt-bk7"},   {"BAF10", "pbrt-baf10"}, {"FK51A", "pbrt-fk51a"},
                                                         {"LASF9", "pbrt-lasf9"}, {"F5", "pbrt-sf5"},      {"F10", "pbrt-sf10"},
                                                         {"F11", "pbrt-sf11"}};
  for (const auto& [pbrt_name, name] : glasses) {
    CAPTURE(pbrt_name);
    CHECK(material_of(std::string("Material \"dielectric\" \"spectrum eta\" \"glass-") + pbrt_name + "\"") ==
          json({{"type", "dielectric"}, {"glass", name}}));
  }
  // pbrt's default conductor is its copper; eta and k of two different metals are not a pair (listed, copper).
  CHECK(material_of("Material \"conductor\"") == json({{"type", "conductor"}, {"metal", "pbrt-cu"}}));
  const PbrtImport mixed = import_pbrt_text(kCamera + "Material \"conductor\" \"spectrum eta\" \"metal-Au-eta\" \"spectrum k\" \"metal-Ag-k\"\nShape \"sphere\"",
                                            "t.pbrt", test::test_data("pbrt"), test::library());
  CHECK(mixed.ignored.size() == 2);  // both named spectra: a JSON n or k cannot name a library table
}

TEST_CASE("pbrt named spectra: the tables hold pbrt's numbers, and pbrt's BK7 table follows SCHOTT's formula") {
  SpectralLibrary& lib = test::library();
  // Points of pbrt-v4's arrays (src/pbrt/util/spectrum.cpp at 5f7a6068): exact at the table's own wavelengths,
  // linear between them, and the end value beyond the last one (pbrt's FromInterleaved extends the same way).
  const ComplexIorSpectra tio2 = conductor_ior(lib, "pbrt-tio2");
  CHECK(tio2.n->value(600.097046) == doctest::Approx(2.90).epsilon(1e-9));
  CHECK(tio2.k->value(412.031006) == doctest::Approx(0.022).epsilon(1e-9));
  CHECK(tio2.n->value(0.5 * (600.097046 + 619.900024)) == doctest::Approx(0.5 * (2.90 + 2.88)).epsilon(1e-9));
  const ComplexIorSpectra mgo = conductor_ior(lib, "pbrt-mgo");
  CHECK(mgo.n->value(830.0) == doctest::Approx(1.728720).epsilon(1e-9));  // last point 767.68 nm, carried out
  const ComplexIorSpectra au = conductor_ior(lib, "pbrt-au");
  CHECK(au.n->value(298.75705) == doctest::Approx(1.795).epsilon(1e-9));
  CHECK(au.k->value(298.75705) == doctest::Approx(1.920375).epsilon(1e-9));
  // pbrt's glass-BK7 is SCHOTT's N-BK7 Sellmeier formula sampled every ~22 nm (Rimu's "bk7" evaluates the formula
  // itself): linear interpolation of a convex n(λ) departs from it by < 8e-5 over 380-780 nm (docs/pbrt-import.md).
  const SpectrumPtr table = dielectric_ior(lib, "pbrt-bk7"), formula = dielectric_ior(lib, "bk7");
  double worst = 0.0;
  for (int nm = 380; nm <= 780; ++nm) worst = std::max(worst, std::abs(table->value(nm) - formula->value(nm)));
  CHECK(worst < 8e-5);
  CHECK(worst > 0.0);  // two different things were compared
  CHECK(dielectric_ior(lib, "pbrt-sf11")->value(587.6) == doctest::Approx(1.7847).epsilon(2e-4));  // SF11's n_d 1.78472 (SCHOTT)
}

}  // namespace pbrt_named_spectra_test
