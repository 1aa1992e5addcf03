// libFuzzer target: the PLY mesh reader (ascii, binary little- and big-endian).
#include "fuzz_support.h"
#include "render/scene/ply_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rimu::fuzz::run_reader("fuzz_ply", [&] {
    rimu::TriangleMesh mesh = rimu::parse_ply(rimu::fuzz::as_text(data, size), "fuzz.ply");
    // The loader promises a mesh that validates; the scene then removes degenerate triangles.
    if (const std::string problem = mesh.validate(); !problem.empty()) {
      std::fprintf(stderr, "fuzz_ply: parse_ply returned an invalid mesh: %s\n", problem.c_str());
      std::abort();
    }
    (void)mesh.remove_degenerate_triangles();
  });
}
