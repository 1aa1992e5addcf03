// Writes a rough metal in the measured-BRDF form (an RGL tensor file, pbrt-v4's `measured` material), so that Rimu
// and pbrt-v4 can render the same measured file (bench/pbrt_scenes/measured_gold.pbrt): the RGL database's own files
// are not in a form this project can fetch. The tables are transport/bsdfs/measured_brdf_tabulation.h's.
//
//   build/bin/rimu-make-measured-bsdf OUT.bsdf [--metal gold|silver|copper|aluminium] [--alpha A]
#include <CLI/CLI.hpp>

#include <cstdio>
#include <fstream>

#include "spectral/error.h"
#include "spectral/library/optical_constants.h"
#include "spectral/library/spectral_library.h"
#include "transport/bsdfs/measured_brdf_tabulation.h"

int main(int argc, char** argv) {
  using namespace rimu;
  CLI::App app("Writes a GGX metal as a measured BRDF (RGL tensor file)");
  std::string out, metal = "gold";
  float alpha = 0.2f;
  app.add_option("output", out, "the .bsdf file to write")->required();
  app.add_option("--metal", metal, "gold, silver, copper or aluminium");
  app.add_option("--alpha", alpha, "GGX alpha")->check(CLI::Range(0.01f, 1.0f));
  CLI11_PARSE(app, argc, argv);
  try {
    SpectralLibrary library = SpectralLibrary::at_default_location();
    MicrofacetTabulation t = MicrofacetTabulation::conductor(conductor_ior(library, metal), alpha);
    t.theta_i_count = 16;
    t.vndf_size = 64;
    const std::string bytes = TensorFile::serialise(tabulate_microfacet_brdf(t));
    std::ofstream(out, std::ios::binary) << bytes;
    std::printf("wrote %s: %s, GGX alpha %g, %zu bytes\n", out.c_str(), metal.c_str(), double(alpha), bytes.size());
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
