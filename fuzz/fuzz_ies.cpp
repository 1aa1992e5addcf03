// libFuzzer target: the IES LM-63 reader and the candela table built from what it accepts.
#include "fuzz_support.h"
#include "render/scene/ies_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rimu::fuzz::run_reader("fuzz_ies", [&] {
    const rimu::IesPhotometry ies = rimu::parse_ies(std::string(rimu::fuzz::as_text(data, size)), "fuzz.ies");
    // What a scene's IES light and `rimu-light inspect` do next with an accepted file.
    const auto table = rimu::candela_distribution(ies);
    (void)rimu::ies_spread_angle_deg(*table, 0.5);
    (void)ies.rated_lamp_lumens();
  });
}
