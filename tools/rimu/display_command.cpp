// `rimu display IN.exr --png OUT.png`: a thin parser in front of rimu::write_exr_display_image
// (render/output/exr_display_source.h).
#include "display_command.h"

#include <iostream>
#include <optional>

#include "common/tool_main.h"

#include "render/output/exr_display_source.h"
#include "render/output/exr_relight.h"
#include "render/output/false_colour_image.h"
#include "spectral/error.h"

namespace {

// Relighting (render/output/exr_relight.h): the light-group and white-balance options, parsed into `relight` once
// the command line is read (relight_options_from).
struct RelightText {
  std::string groups, white;
};

void add_relight_options(CLI::App& app, RelightText& text) {
  app.add_option("--group", text.groups,
                 "rebalance light groups: name=scale[,name=scale...], e.g. sun=2,lamps=0.5 (groups not named keep 1; "
                 "0 removes a group's light)");
  app.add_option("--white-balance", text.white,
                 "white-balance the display image from this white to D65: a temperature (4500K), an illuminant "
                 "(D50) or a chromaticity x,y (0.3457,0.3585); an image white-balanced when rendered has that "
                 "balance undone first");
}

rimu::ExrRelightOptions relight_options_from(const RelightText& text) {
  rimu::ExrRelightOptions options;
  if (!text.groups.empty()) options.groups = rimu::parse_light_group_scales(text.groups, "--group");
  if (!text.white.empty()) {
    rimu::SpectralLibrary library = rimu::SpectralLibrary::at_default_location();
    options.white = rimu::parse_display_white(text.white, library, "--white-balance");
  }
  return options;
}

}  // namespace

int run_display_command(int argc, char** argv) {
  CLI::App app{
      "rimu display: writes the display image of a rendered EXR (a render, a merge or a partial) again, with another\n"
      "exposure or view, without rendering. The image is made as `rimu --png` makes it: a photometric render that\n"
      "was metered is metered again (--exposure is then the compensation), a camera film is shown through its\n"
      "fitted camera-to-XYZ matrix.\n"
      "Example: rimu display room.exr --png room_plus1.png --exposure 1\n"
      "False colour: rimu display room.exr --png room_nt.png --false-colour luminance --range 1:10000"};
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
  // False colour: a lighting designer's view of the same EXR, instead of the display image.
  std::string false_colour, range;
  CLI::Option* false_colour_option =
      app.add_option("--false-colour", false_colour,
                     "write a false-colour PNG instead: luminance (nt = cd/m²) or illuminance (lx, π × luminance: "
                     "exact for a white Lambertian surface), on a log scale with its legend");
  app.add_option("--range", range, "false colour: the legend's range LOW:HIGH in nt or lx (default: the 1st-99th "
                                   "percentile of the image)")
      ->needs(false_colour_option);
  RelightText relight;
  add_relight_options(app, relight);
  // The false-colour picture shows the file's own light: rebalanced groups and a display white belong to the
  // display image.
  for (const char* name : {"--exposure", "--view", "--meter", "--group", "--white-balance"})
    false_colour_option->excludes(app.get_option(name));
  return rimu::run_tool("rimu display", app, argc, argv, [&] {
    if (!false_colour.empty()) {
      const auto quantity = rimu::parse_false_colour_quantity(false_colour, "--false-colour");
      std::optional<rimu::FalseColourRange> legend;
      if (!range.empty()) legend = rimu::parse_false_colour_range(range, "--range");
      rimu::write_exr_false_colour(input, png, quantity, legend, std::cerr);
      std::cerr << "rimu display: wrote " << png << "\n";
      return;
    }
    rimu::write_exr_display_image(input, png, display, meter, std::cerr, relight_options_from(relight));
    std::cerr << "rimu display: wrote " << png << "\n";
  });
}
