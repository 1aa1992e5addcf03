// libFuzzer target: the OBJ mesh reader (Rimu's line check, then tinyobjloader, then de-indexing).
#include "fuzz_support.h"
#include "render/scene/obj_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rimu::fuzz::run_reader("fuzz_obj", [&] {
    rimu::TriangleMesh mesh = rimu::parse_obj(rimu::fuzz::as_text(data, size), "fuzz.obj");
    // The loader promises a mesh that validates; the scene then removes degenerate triangles.
    if (const std::string problem = mesh.validate(); !problem.empty()) {
      std::fprintf(stderr, "fuzz_obj: parse_obj returned an invalid mesh: %s\n", problem.c_str());
      std::abort();
    }
    (void)mesh.remove_degenerate_triangles();
    // Selecting one object by name goes through a different path.
    try {
      (void)rimu::parse_obj(rimu::fuzz::as_text(data, size), "fuzz.obj", "box");
    } catch (const rimu::InputError&) {
    }
  });
}
