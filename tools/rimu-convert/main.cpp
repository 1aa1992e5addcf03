// rimu-convert: translates a pbrt-v4 scene into Rimu's JSON scene format, so an imported scene can be edited.
//
// Exit codes (common/tool_main.h): 0 ok, 1 bad input (nothing is written), 2 runtime failure.
#include <iostream>

#include "common/tool_main.h"

#include "render/output/output_file.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/scene.h"
#include "render/output/text_file_output.h"
#include "spectral/error.h"
#include "spectral/io/input_file.h"
#include "spectral/library/spectral_library.h"

int main(int argc, char** argv) {
  CLI::App app{
      "rimu-convert: translates a pbrt-v4 scene (.pbrt, with its Includes) into Rimu's JSON scene format\n"
      "(docs/pbrt-import.md). Mesh and texture paths in the JSON are relative to the output's folder; the JSON is\n"
      "checked by Rimu's scene loader (meshes read) before it is written.\n"
      "What Rimu does not support is listed on stderr (or, with --strict, is an error).\n"
      "Example: rimu-convert scene.pbrt -o scene.json"};
  std::string input, output;
  bool strict = false;
  app.add_option("scene", input, "the pbrt-v4 file")->required();
  app.add_option("-o,--output", output, "the JSON scene to write")->required();
  app.add_flag("--strict", strict, "anything Rimu does not support is an error, not a report");
  std::string rgb_upsampler = "sigmoid";
  app.add_option("--rgb-upsampler", rgb_upsampler,
                 "how constant RGB parameters become spectra: sigmoid (pbrt-v4's sigmoid polynomials, the default) or\n"
                 "rimu (Rimu's smoothest-spectrum upsampler); image textures always use Rimu's")
      ->check(CLI::IsMember({"sigmoid", "rimu"}));
  return rimu::run_tool("rimu-convert", app, argc, argv, [&] {
    rimu::SpectralLibrary library = rimu::SpectralLibrary::at_default_location();
    if (!rimu::is_pbrt_scene_path(input))
      throw rimu::InputError({input, 0, ""}, "expected a pbrt-v4 scene file ending in .pbrt");
    rimu::check_output_path(output);
    rimu::check_output_not_input(output, "-o", {{input, "the pbrt scene"}});
    // Every file the import and the check below read (InputFileLog): none of them may be replaced by the JSON.
    const rimu::InputFileLog files_read;
    const std::filesystem::path output_directory = std::filesystem::absolute(output).parent_path();
    rimu::PbrtImportOptions options{strict, output_directory};
    if (rgb_upsampler == "rimu") options.rgb_upsampler = rimu::PbrtRgbUpsampler::rimu;
    const rimu::PbrtImport imported = rimu::import_pbrt(input, library, options);
    std::cerr << rimu::describe_ignored(imported.ignored);
    // Rimu's own loader checks the document (and reads its meshes) before anything is written: a JSON that
    // rimu-convert writes always loads.
    try {
      rimu::load_scene(imported.document, input, output_directory, library);
    } catch (const rimu::InputError& e) {
      if (std::optional<rimu::InputError> at_pbrt = rimu::at_pbrt_origin(e, imported.origins)) throw *at_pbrt;
      throw;
    }
    std::vector<rimu::InputFile> inputs;
    for (const auto& [path, digest] : files_read.files()) inputs.push_back({path, "read by the pbrt scene"});
    rimu::check_output_not_input(output, "-o", inputs);
    rimu::write_text_file(output, imported.document.dump(2) + "\n");
  });
}
