// libFuzzer target: `rimu merge`'s reader of partial renders (OpenEXR files with exact sums and a rimu:partial:*
// record), through merge_partials itself: the headers' checks, the sums read band by band, the film they are added
// to and the merged EXR written (into the target's private folder).
#include <sstream>

#include "fuzz_support.h"
#include "render/output/merge_partials.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rimu::fuzz::run_reader("fuzz_merge", [&] {
    const std::filesystem::path input = rimu::fuzz::write_private_file(data, size, ".exr");
    rimu::MergeOptions options;
    options.allow_gaps = true;  // a lone partial is a gap; the merge goes on to read and write it
    std::ostringstream log;
    rimu::merge_partials({input}, rimu::fuzz::private_folder() / "merged.exr", options, log);
  });
}
