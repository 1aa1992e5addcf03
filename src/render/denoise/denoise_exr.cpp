#include "render/denoise/denoise_exr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <map>
#include <ostream>

#include "render/denoise/denoise_layers.h"
#include "render/image/exr_input.h"
#include "spectral/error.h"
#include "spectral/io/output_file.h"

namespace rimu {

void denoise_exr_file(const std::filesystem::path& input, const std::filesystem::path& output,
                      const DenoiseSettings& settings, std::ostream& log) {
  if (same_output_file(input, output))
    throw InputError({output.string(), 0, "-o"}, "is the image being denoised: write the result to another file");
  check_output_path(output);
  const std::unique_ptr<Imf::InputFile> file = open_exr_input(input);
  const Imf::Header& header = file->header();
  const Imath::Box2i window = header.dataWindow();
  const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
  const size_t n = size_t(width) * size_t(height);

  std::map<std::string, Imf::PixelType> types;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    if (it.channel().type == Imf::UINT)
      throw InputError({input.string(), 0, it.name()},
                       "is a partial render's exact sum: denoise the finished image (rimu merge --final) instead");
    types[it.name()] = it.channel().type;
  }
  std::array<std::string, 3> beauty;
  if (types.count("X") && types.count("Y") && types.count("Z"))
    beauty = {"X", "Y", "Z"};
  else if (types.count("R") && types.count("G") && types.count("B"))
    beauty = {"R", "G", "B"};
  else
    throw InputError({input.string(), 0, ""}, "has no beauty channels X, Y, Z or R, G, B to denoise");
  for (const std::string& c : beauty)
    if (types.count("noisy." + c))
      throw InputError({input.string(), 0, ""}, "is denoised already (it has the layer 'noisy." + c + "')");

  std::map<std::string, std::vector<float>> values;
  try {
    Imf::FrameBuffer buffer;
    for (const auto& [name, type] : types) {
      std::vector<float>& v = values[name];
      v.assign(n, 0.0f);
      buffer.insert(name, Imf::Slice::Make(Imf::FLOAT, v.data(), window, sizeof(float), sizeof(float) * size_t(width)));
    }
    file->setFrameBuffer(buffer);
    file->readPixels(window.min.y, window.max.y);
  } catch (const std::exception& e) {
    throw InputError({input.string(), 0, ""}, std::string("cannot read its pixels: ") + e.what());
  }
  const DenoiseInput in = denoise_input_from_layers(
      width, height, beauty,
      [&](const std::string& name) -> const std::vector<float>* {
        const auto it = values.find(name);
        return it == values.end() ? nullptr : &it->second;
      },
      input.string());
  const DenoiseResult result = denoise(in, settings);

  Imf::Header out_header = header;
  for (int k = 0; k < 3; ++k) {
    std::vector<float>& b = values[beauty[size_t(k)]];
    std::vector<float>& noisy = values["noisy." + beauty[size_t(k)]];
    noisy = b;
    types["noisy." + beauty[size_t(k)]] = types[beauty[size_t(k)]];
    out_header.channels().insert("noisy." + beauty[size_t(k)], Imf::Channel(types[beauty[size_t(k)]]));
    for (size_t i = 0; i < n; ++i) b[i] = result.image[3 * i + size_t(k)];
  }
  out_header.insert("rimu:denoised",
                    Imf::StringAttribute("weighted first-order regression on albedo, normal and depth (NFOR, "
                                         "simplified); noisy beauty in the noisy layer"));
  write_atomically(output, [&](const std::filesystem::path& temporary) {
    Imf::FrameBuffer buffer;
    for (auto& [name, v] : values)
      buffer.insert(name, Imf::Slice::Make(Imf::FLOAT, v.data(), window, sizeof(float), sizeof(float) * size_t(width)));
    Imf::OutputFile out(temporary.c_str(), out_header);
    out.setFrameBuffer(buffer);
    out.writePixels(height);
  });
  log << "rimu denoise: " << input.string() << " -> " << output.string() << ": " << width << "x" << height << " in "
      << result.seconds << " s (" << result.seconds / (double(n) * 1e-6) << " s per megapixel)\n";
}

}  // namespace rimu
