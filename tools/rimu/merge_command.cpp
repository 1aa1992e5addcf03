// `rimu merge PART.exr... -o OUT.exr`: a thin parser in front of rimu::merge_partials (render/output/merge_partials.h).
#include "merge_command.h"

#include <iostream>

#include "common/tool_main.h"

#include "render/output/merge_partials.h"
#include "spectral/error.h"

int run_merge_command(int argc, char** argv) {
  CLI::App app{
      "rimu merge: sums partial renders (rimu --samples A:B, crop tiles, checkpoints) of one render into the image\n"
      "one process would have written for their union (docs/farm.md). Refuses partials of another scene, seed,\n"
      "resolution or film, samples held twice, and missing samples (unless --allow-gaps). Nothing is written then.\n"
      "Example: rimu merge part0.exr part1.exr -o final.exr"};
  std::vector<std::string> inputs;
  std::string output;
  rimu::MergeOptions options;
  bool final_only = false;
  app.add_option("partials", inputs, "partial renders (.exr written with --samples or --checkpoint)")->required();
  app.add_option("-o,--output", output, "merged OpenEXR image (written atomically)")->required();
  app.add_flag("--allow-gaps", options.allow_gaps,
               "write even if samples are missing (a warning names them; the result records what it holds)");
  app.add_flag("--final", final_only,
               "write only the image channels, as a plain render does (default: keep the exact sums, so the result "
               "can be merged again or resumed)");
  return rimu::run_tool("rimu merge", app, argc, argv, [&] {
    options.keep_sums = !final_only;
    std::vector<std::filesystem::path> paths(inputs.begin(), inputs.end());
    rimu::merge_partials(paths, output, options, std::cerr);
  });
}
