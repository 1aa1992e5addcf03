#include "render/output/exr_display_source.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfMatrixAttribute.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>

#include <array>
#include <exception>
#include <string>
#include <vector>

#include "render/output/display_image_policy.h"
#include "render/output/display_output.h"
#include "render/image/exr_input.h"
#include "render/output/exr_output.h"
#include "render/output/partial_exr.h"
#include "spectral/error.h"
#include "spectral/io/output_file.h"

namespace rimu {
namespace {

const std::string* string_attribute(const Imf::Header& header, const char* name) {
  const auto* attribute = header.findTypedAttribute<Imf::StringAttribute>(name);
  return attribute ? &attribute->value() : nullptr;
}

// The film a final image was written from: its response (from the channels and rimu:camera) and its windows, with
// each pixel's written value as a sum of weight 1.
std::unique_ptr<Film> film_from_image(const std::filesystem::path& path, Imf::InputFile& file,
                                      SpectralLibrary& library) {
  const Imf::Header& header = file.header();
  const std::string* camera = string_attribute(header, "rimu:camera");
  const std::array<const char*, 3> channels =
      camera ? std::array<const char*, 3>{"R", "G", "B"} : std::array<const char*, 3>{"X", "Y", "Z"};
  for (const char* channel : channels)
    if (!header.channels().findChannel(channel))
      throw InputError({path.string(), 0, ""}, std::string("has no '") + channel + "' channel, which its " +
                                                   (camera ? "camera film ('rimu:camera' = " + *camera + ")"
                                                           : std::string("XYZ film")) +
                                                   " writes");
  SpectralResponse response =
      camera ? SpectralResponse::camera_rgb(library, *camera) : SpectralResponse::cie_xyz(library);
  // Light-group layers ("sun.X", ...; render/output/exr_output.h) come back as the film's group sums.
  std::vector<std::string> groups;
  if (const std::string* names = string_attribute(header, "rimu:lightGroups")) groups = parse_light_groups_text(*names);
  std::vector<std::string> names(channels.begin(), channels.end());
  for (const std::string& group : groups)
    for (const char* channel : channels) {
      names.push_back(group + "." + channel);
      if (!header.channels().findChannel(names.back()))
        throw InputError({path.string(), 0, ""}, "has no '" + names.back() + "' channel, which its light group '" +
                                                     group + "' (rimu:lightGroups) writes");
    }

  const Imath::Box2i display = header.displayWindow(), data = header.dataWindow();
  FilmOptions options;
  options.width = display.max.x - display.min.x + 1;
  options.height = display.max.y - display.min.y + 1;
  options.crop = PixelBounds{data.min.x, data.min.y, data.max.x + 1, data.max.y + 1};
  auto film = std::make_unique<Film>(options, std::move(response), groups);

  const int width = data.max.x - data.min.x + 1, height = data.max.y - data.min.y + 1;
  const size_t n = names.size();  // 3 beauty channels, then 3 per group
  std::vector<float> values(size_t(width) * size_t(height) * n);
  Imf::FrameBuffer frame;
  const size_t x_stride = n * sizeof(float), y_stride = x_stride * size_t(width);
  // OpenEXR addresses a slice by the data window's origin: base + x·xStride + y·yStride for absolute x, y.
  char* origin = reinterpret_cast<char*>(values.data()) - ptrdiff_t(data.min.x) * ptrdiff_t(x_stride) -
                 ptrdiff_t(data.min.y) * ptrdiff_t(y_stride);
  for (size_t c = 0; c < n; ++c)
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, origin + c * sizeof(float), x_stride, y_stride));
  file.setFrameBuffer(frame);
  file.readPixels(data.min.y, data.max.y);

  FilmTile tile = film->make_tile(film->pixel_bounds());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double* pixel = tile.pixel(data.min.x + x, data.min.y + y);
      const float* value = &values[(size_t(y) * size_t(width) + size_t(x)) * n];
      for (int c = 0; c < 3; ++c) pixel[c] = double(value[c]);
      pixel[FilmTile::kWeight] = 1.0;
      for (size_t c = 3; c < n; ++c) pixel[tile.first_group_sum() + int(c) - 3] = double(value[c]);
    }
  film->merge_tile(tile);
  return film;
}

// A file written before rimu:whiteBalanceMatrix: the matrix its rimu:whiteBalance gave, by the render's own code
// (camera_exposure.h) on the film's response, the same numbers the render computed. Nothing if the text is not one
// Rimu writes (relight_exr_film then refuses --white-balance).
std::optional<Matrix3> rebuilt_white_balance_matrix(const std::string& description, const SpectralResponse& response,
                                                    SpectralLibrary& library) {
  const std::optional<WhiteBalanceSettings> settings = WhiteBalanceSettings::from_description(description);
  if (!settings) return std::nullopt;
  CameraExposureSettings camera;
  camera.white_balance = *settings;
  try {
    return film_output_transform(camera, response, library).channel_matrix;
  } catch (const InputError&) {
    return std::nullopt;  // an illuminant this library does not have
  }
}

}  // namespace

ExrDisplaySource read_exr_for_display(const std::filesystem::path& path, SpectralLibrary& library) {
  ExrDisplaySource source;
  std::optional<double> nits_per_unit_y;
  std::string white_balance_text;
  bool balance_in_channels = false;
  try {
    const std::unique_ptr<Imf::InputFile> file = open_exr_input(path);
    const Imf::Header& header = file->header();
    if (!string_attribute(header, "rimu:filmResponse"))
      throw InputError({path.string(), 0, ""}, "is not an image Rimu wrote (no 'rimu:filmResponse' attribute): "
                                               "display it with any EXR viewer");
    const std::string* white_balance = string_attribute(header, "rimu:whiteBalance");
    const std::string* in_channels = string_attribute(header, "rimu:whiteBalanceInFilmResponse");
    balance_in_channels = in_channels && *in_channels == "yes";
    source.white_balanced = white_balance && *white_balance != "none";
    if (source.white_balanced) white_balance_text = *white_balance;
    if (const auto* m = header.findTypedAttribute<Imf::M33dAttribute>("rimu:whiteBalanceMatrix")) {
      Matrix3 matrix;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) matrix(r, c) = m->value()[r][c];
      source.white_balance_matrix = matrix;
    }
    const std::string* metered = string_attribute(header, "rimu:displayMetered");
    source.metered = metered && *metered == "yes";
    if (const auto* nits = header.findTypedAttribute<Imf::DoubleAttribute>("rimu:luminanceNitsPerUnitY"))
      nits_per_unit_y = nits->value();
    if (header.findTypedAttribute<Imf::StringAttribute>("rimu:partial:sceneHash")) {
      const PartialImage partial = read_partial_exr(path, true);
      source.film = film_from_partial(partial, library);
    } else {
      source.film = film_from_image(path, *file, library);
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError({path.string(), 0, ""}, std::string("cannot be read as an OpenEXR image: ") + e.what());
  }
  const SpectralResponse& response = source.film->response();
  // A camera-xyz film holds its white balance in its channels: there is no matrix to undo, and none is rebuilt
  // (relight_exr_film then refuses --white-balance).
  if (balance_in_channels) source.white_balance_matrix.reset();
  else if (source.white_balanced && !source.white_balance_matrix)
    source.white_balance_matrix = rebuilt_white_balance_matrix(white_balance_text, response, library);
  if (response.kind() == ResponseKind::camera_rgb) source.camera_fit = fit_camera_to_xyz(response, library);
  // Of the displayed Y (the film's output values): an XYZ file records it; a camera film is shown through XYZ.
  source.nits_per_unit_y = nits_per_unit_y ? *nits_per_unit_y
                                           : SpectralResponse::cie_xyz(library).luminance_nits_per_unit_y() /
                                                 source.film->output_transform().scale;
  return source;
}

void write_exr_display_image(const std::filesystem::path& exr, const std::filesystem::path& display_image,
                             const DisplayOptions& options, bool meter, std::ostream& log,
                             const ExrRelightOptions& relight) {
  display_image_format(display_image);
  check_output_not_input(display_image, "--png", {{exr, "the image to display"}});
  const DisplayTransform view_check(ResponseKind::cie_xyz, options);  // the view and the config, before reading
  SpectralLibrary library = SpectralLibrary::at_default_location();
  const ExrDisplaySource source = read_exr_for_display(exr, library);
  relight_exr_film(*source.film, relight, source.white_balanced, source.white_balance_matrix, exr.string(), library);
  DisplayImagePolicy policy;
  policy.camera_fit = source.camera_fit;
  policy.white_balanced = source.white_balanced || relight.white.has_value();
  policy.metered = source.metered || meter;
  policy.nits_per_unit_y = source.nits_per_unit_y;
  write_policy_display_image(display_image, *source.film, options, policy, log);
}

}  // namespace rimu
