// Inputs the pbrt-v4 fuzz target (fuzz/fuzz_pbrt.cpp, docs/fuzzing.md) found or was written to find: each must end
// in an InputError with the pbrt file and line, quickly and without large allocations. The raw inputs are in
// fuzz/regressions/pbrt/, replayed by every fuzz run.
#include <doctest/doctest.h>

#include <string>

#include "render/scene/pbrt/pbrt_to_scene.h"
#include "test_support.h"
#include "pbrt_test_support.h"

using namespace rimu;

namespace pbrt_hardening_test {

const std::string kCamera = "LookAt 0 0 -3  0 0 0  0 1 0\nCamera \"perspective\"\n";

// The message of the InputError that importing `text` (as test.pbrt in tests/data/pbrt) raises.
std::string error_of(const std::string& text) { return test::pbrt_import_error(text, "test.pbrt"); }

TEST_CASE("pbrt hardening: a stratified sampler's xsamples × ysamples beyond 2^24 is refused, not overflowed") {
  CHECK(error_of(kCamera + "Sampler \"stratified\" \"integer xsamples\" 2147483647 \"integer ysamples\" 2147483647\n") ==
        "test.pbrt:3: Sampler: the sample count must be 1-16777216, not 4611686014132420609");
  CHECK(error_of(kCamera + "Sampler \"halton\" \"integer pixelsamples\" 16777217\n") ==
        "test.pbrt:3: Sampler: the sample count must be 1-16777216, not 16777217");
  CHECK(error_of(kCamera + "Sampler \"stratified\" \"integer xsamples\" 4096 \"integer ysamples\" 4096\nWorldBegin\n") == "no error");
}

TEST_CASE("pbrt hardening: Include of a device or a folder is refused before reading it") {
  CHECK(error_of(kCamera + "WorldBegin\nInclude \"/dev/zero\"\n") ==
        "test.pbrt:4: Include: '/dev/zero': is a character device; Rimu reads its inputs only from regular files "
        "(whose end is known)");
  CHECK(error_of(kCamera + "WorldBegin\nImport \".\"\n").find("test.pbrt:4: Import: '") == 0);
  CHECK(error_of(kCamera + "WorldBegin\nImport \".\"\n").find("': is a directory; expected a file") != std::string::npos);
}

TEST_CASE("pbrt hardening: a texture graph that unfolds exponentially is refused at the parameter") {
  // Each texture mixes the one before with itself: 40 statements, 2^40 lookups if followed blindly.
  std::string text = kCamera + "WorldBegin\nTexture \"t0\" \"float\" \"imagemap\" \"string filename\" \"normal_map.ppm\"\n";
  for (int i = 1; i < 40; ++i)
    text += "Texture \"t" + std::to_string(i) + "\" \"float\" \"mix\" \"texture tex1\" \"t" + std::to_string(i - 1) +
            "\" \"texture tex2\" \"t" + std::to_string(i - 1) + "\"\n";
  const std::string error = error_of(text + "Material \"diffuse\" \"texture displacement\" \"t39\"\nShape \"sphere\"\n");
  CHECK(error.find("the parameter's textures unfold into more than 4096 texture lookups") != std::string::npos);
  CHECK(error.find("test.pbrt:") == 0);
  // A chain of 8 such mixes (2^8 leaves) is fine.
  std::string small = kCamera + "WorldBegin\nTexture \"t0\" \"float\" \"imagemap\" \"string filename\" \"normal_map.ppm\"\n";
  for (int i = 1; i <= 8; ++i)
    small += "Texture \"t" + std::to_string(i) + "\" \"float\" \"mix\" \"texture tex1\" \"t" + std::to_string(i - 1) +
             "\" \"texture tex2\" \"t" + std::to_string(i - 1) + "\"\n";
  CHECK(error_of(small + "Material \"diffuse\" \"texture displacement\" \"t8\"\nShape \"sphere\"\n") == "no error");
}

TEST_CASE("pbrt hardening: generated triangles (loopsubdiv, sphere, cylinder and disk meshes) are bounded per scene") {
  const std::string tetrahedron =
      "\"point3 P\" [ 1 1 1  -1 -1 1  -1 1 -1  1 -1 -1 ] \"integer indices\" [ 0 1 2  0 3 1  0 2 3  1 3 2 ]\n";
  // 4 · 4^10 triangles: refused before subdividing, whatever the levels' own bound (0-10) allows.
  CHECK(error_of(kCamera + "WorldBegin\nShape \"loopsubdiv\" \"integer levels\" 10 " + tetrahedron) ==
        "test.pbrt:4: Shape \"loopsubdiv\": would generate 4194304 triangles after 0, beyond the importer's limit of "
        "2097152 generated triangles per scene (Loop subdivision, sphere, cylinder and disk meshes; lower \"levels\"?)");
  // The limit is per scene: a sphere mesh (9024 triangles: reversed spheres are tessellated) and a disk (96
  // triangles, 192 with a hole) count too, so the second reversed sphere crosses a limit of 10,000.
  PbrtImportOptions options;
  options.max_generated_triangles = 10000;
  const auto error_with_limit = [&](const std::string& text) {
    try {
      import_pbrt_text(text, "test.pbrt", test::test_data("pbrt"), test::library(), options);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string spheres = kCamera + "WorldBegin\nReverseOrientation\nShape \"sphere\"\nShape \"disk\"\nShape \"sphere\"\n";
  CHECK(error_with_limit(spheres).find("test.pbrt:7: Shape \"sphere\": would generate 9024 triangles after 9120,") == 0);
  CHECK(error_with_limit(kCamera + "WorldBegin\nShape \"loopsubdiv\" \"integer levels\" 5 " + tetrahedron) == "no error");
  CHECK(error_with_limit(kCamera + "WorldBegin\nShape \"loopsubdiv\" \"integer levels\" 6 " + tetrahedron)
            .find("test.pbrt:4: Shape \"loopsubdiv\": would generate 16384 triangles after 0,") == 0);
}

TEST_CASE("pbrt hardening: --strict's unused parameter of a texture is the statement's error, at the parameter's line") {
  // Found by LeakSanitizer: the error used to be thrown from the parameters' destructor while the texture's value
  // was being returned, which leaked the value. It is now thrown once the statement is done, with the same text.
  const std::string text = kCamera + "WorldBegin\n"
                           "Texture \"bumps\" \"float\" \"checkerboard\" \"float uscale\" 4\n"
                           "  \"float te82\" 0.2\n"
                           "Material \"diffuse\" \"texture displacement\" \"bumps\"\n";
  std::string error = "no error";
  try {
    import_pbrt_text(text, "test.pbrt", test::test_data("pbrt"), test::library(), {true, {}});
  } catch (const InputError& e) {
    error = e.what();
  }
  CHECK(error == "test.pbrt:5: not supported (--strict): parameter \"float te82\" of Texture \"bumps\"");
  CHECK(error_of(text).find("no error") == 0);  // without --strict: listed, not an error
}

}  // namespace pbrt_hardening_test
