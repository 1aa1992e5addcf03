// `rimu display IN.exr --png OUT.png`: a thin parser in front of rimu::write_exr_display_image
// (render/output/exr_display_source.h).
#include "display_command.h"

#include <iostream>

#include "common/tool_main.h"

#include "render/output/exr_display_source.h"
#include "spectral/error.h"

int run_display_command(int argc, char** argv) {
  CLI::App app{
      "rimu display: writes the display image of a rendered EXR (a render, a merge or a partial) again, with another\n"
      "exposure or view, without rendering. The image is made as `rimu --png` makes it: a photometric render that\n"
      "was metered is metered again (--exposure is then the compensation), a camera film is shown through its\n"
      "fitted camera-to-XYZ matrix.\n"
      "Example: rimu display room.exr --png room_plus1.png --exposure 1"};
  std::string input, png;
  rimu::DisplayOptions display;
  bool meter = false;
  app.add_option("image", input, "an OpenEXR image written by rimu or rimu merge")->required();
  app.add_option("--png", png, "the display image: 8-bit PNG, or JPEG or TIFF by the extension (written atomically)")
      ->required();
  app.add_option("--exposure,--ev", display.exposure_ev, "exposure of the display image in stops, -60 to 60")
      ->check(CLI::Range(-rimu::kMaxDisplayExposure_ev, rimu::kMaxDisplayExposure_ev));
  app.add_option("--view", display.view, "OpenColorIO view: Standard, \"ACES 1.0 SDR\" or Raw");
  app.add_flag("--meter", meter,
               "meter the image to 18 % grey (plus --exposure) even if the render did not (it does for photometric "
               "scenes without a camera exposure)");
  return rimu::run_tool("rimu display", app, argc, argv, [&] {
    rimu::write_exr_display_image(input, png, display, meter, std::cerr);
    std::cerr << "rimu display: wrote " << png << "\n";
  });
}
