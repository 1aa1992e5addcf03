// `rimu denoise IN.exr -o OUT.exr`: a thin parser in front of rimu::denoise_exr_file (render/denoise/denoise_exr.h).
#include "denoise_command.h"

#include <iostream>

#include "common/tool_main.h"

#include "render/denoise/denoise_exr.h"
#include "spectral/error.h"

int run_denoise_command(int argc, char** argv) {
  CLI::App app{
      "rimu denoise: denoises a render written with its feature layers and half buffers (rimu scene.json --aov all)\n"
      "by weighted first-order regression on its albedo, normal and depth (docs/rendering.md, \"Denoising\").\n"
      "The output keeps every layer of the input; the noisy beauty becomes the layer 'noisy'.\n"
      "Example: rimu denoise box.exr -o box_denoised.exr"};
  std::string input, output;
  rimu::DenoiseSettings settings;
  app.add_option("input", input, "a render written with --aov all (.exr)")->required();
  app.add_option("-o,--output", output, "the denoised OpenEXR image (written atomically)")->required();
  app.add_option("--threads", settings.threads, "worker threads (default: every core)")->check(CLI::Range(1, 4096));
  app.add_option("--window", settings.window_radius, "the regression window's radius in pixels (default 5)")
      ->check(CLI::Range(1, 30));
  app.add_option("--clamp-sigmas", settings.clamp_sigmas,
                 "keep each value within the noisy value +- this many standard errors; 0: no clamp, no bias from it "
                 "(default 5)")
      ->check(CLI::Range(0.0, 1e6));
  bool colour_weights_only = false;
  app.add_flag("--colour-weights-only", colour_weights_only,
               "weigh neighbours by colour alone, as NFOR does (default: also by albedo, normal and depth)");
  return rimu::run_tool("rimu denoise", app, argc, argv, [&] {
    settings.feature_weights = !colour_weights_only;
    rimu::denoise_exr_file(input, output, settings, std::cerr);
  });
}
