#include "render/output/exr_relight.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/camera/physical_camera.h"
#include "render/output/exr_output.h"
#include "spectral/colour_spaces/chromatic_adaptation.h"
#include "spectral/error.h"

namespace rimu {
namespace {

InputError option_error(const std::string& option, const std::string& what) { return InputError({"", 0, option}, what); }

// The largest scale --group takes: beyond it a layer of a bright lamp would overflow half floats and mean nothing.
constexpr double kMaxGroupScale = 1e6;

}  // namespace

std::vector<LightGroupScale> parse_light_group_scales(const std::string& text, const std::string& option) {
  std::vector<LightGroupScale> scales;
  size_t start = 0;
  for (;;) {
    const size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const size_t equals = item.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == item.size())
      throw option_error(option, "expected group=scale[,group=scale...], e.g. sun=2,lamps=0.5; got '" + item + "'");
    LightGroupScale s{item.substr(0, equals), 0.0};
    const std::string number = item.substr(equals + 1);
    char extra = 0;
    if (std::sscanf(number.c_str(), "%lf%c", &s.scale, &extra) != 1 || !(s.scale >= 0.0 && s.scale <= kMaxGroupScale))
      throw option_error(option, "the scale of light group '" + s.group + "' must be a number from 0 to 1e6, got '" +
                                     number + "'");
    for (const LightGroupScale& earlier : scales)
      if (earlier.group == s.group) throw option_error(option, "light group '" + s.group + "' is given twice");
    scales.push_back(std::move(s));
    if (comma == std::string::npos) return scales;
    start = comma + 1;
  }
}

DisplayWhite parse_display_white(const std::string& text, SpectralLibrary& library, const std::string& option) {
  DisplayWhite white;
  white.text = text;
  double x = 0, y = 0;
  char comma = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%lf%c%lf%c", &x, &comma, &y, &extra) == 3 && comma == ',') {
    if (!(x > 0.0 && y > 0.0 && x + y < 1.0))
      throw option_error(option, "a white chromaticity x,y needs 0 < x, 0 < y and x + y < 1; got '" + text + "'");
    white.xy = Chromaticity{x, y};
    return white;
  }
  white.settings = parse_white_balance_option(text, library, option);
  if (white.settings.kind == WhiteBalanceSettings::Kind::none)
    throw option_error(option, "expected a temperature (4500K), an illuminant name (D50) or a chromaticity x,y; "
                               "'none' is the image as written (leave the option out)");
  return white;
}

void rebalance_light_groups(Film& film, const std::vector<LightGroupScale>& scales, const std::string& file) {
  if (scales.empty()) return;
  const std::vector<std::string>& groups = film.light_groups();
  if (groups.empty())
    throw InputError({file, 0, "--group"}, "has no light groups (no light of its scene has a \"light_group\" key), so "
                                           "--group has nothing to rebalance");
  std::vector<double> scale(groups.size(), 1.0);
  for (const LightGroupScale& s : scales) {
    const auto it = std::find(groups.begin(), groups.end(), s.group);
    if (it == groups.end())
      throw InputError({file, 0, "--group"},
                       "has no light group '" + s.group + "'; its groups are: " + light_groups_text(groups));
    scale[size_t(it - groups.begin())] = s.scale;
  }
  // Film::merge_tile adds: the tile holds the change of every sum, (s − 1)·layer, which is exact for s = 0 and 1.
  // A group's sums are its 3 channels, then its spectral bins (render/film/film_tile.h): each changes the beauty's
  // sum of the same channel or bin, so the spectral layers follow the balance too.
  const PixelBounds& b = film.pixel_bounds();
  FilmTile change = film.make_tile(b);
  const int first_group = change.first_group_sum(), stride = change.group_stride();
  auto beauty_index = [](int k) { return k < 3 ? k : FilmTile::kFirstBin + (k - 3); };
  for (int y = b.y0; y < b.y1; ++y)
    for (int x = b.x0; x < b.x1; ++x) {
      const double* from = film.accumulators(x, y);
      double* to = change.pixel(x, y);
      for (size_t g = 0; g < groups.size(); ++g) {
        const double factor = scale[g] - 1.0;
        if (factor == 0.0) continue;
        const int base = first_group + stride * int(g);
        for (int k = 0; k < stride; ++k) {
          const double delta = factor * from[base + k];
          to[beauty_index(k)] += delta;
          to[base + k] = delta;
        }
      }
    }
  film.merge_tile(change);  // adds no sample counts: the tile has none
}

Matrix3 display_white_balance_matrix(const DisplayWhite& white, const SpectralResponse& response,
                                     SpectralLibrary& library) {
  if (white.xy) {
    if (response.kind() != ResponseKind::cie_xyz)
      throw option_error("--white-balance", "a chromaticity white needs an XYZ film; this image's film is " +
                                                response.description() + ": give a temperature or an illuminant");
    const std::array<double, 3> d65 = film_channels(*library.illuminant("D65"), response);
    return chromatic_adaptation_matrix(xyz_from_xyY(*white.xy, 1.0), Xyz{d65[0] / d65[1], 1.0, d65[2] / d65[1]},
                                       CatMethod::bradford);
  }
  // The render's own code path (camera_exposure.h): the same matrix `rimu --white-balance` would have applied.
  CameraExposureSettings camera;
  camera.white_balance = white.settings;
  try {
    return film_output_transform(camera, response, library).channel_matrix;
  } catch (const InputError& e) {
    throw option_error("--white-balance", e.explanation());
  }
}

void relight_exr_film(Film& film, const ExrRelightOptions& options, bool white_balanced,
                      const std::optional<Matrix3>& render_white_balance, const std::string& file,
                      SpectralLibrary& library) {
  rebalance_light_groups(film, options.groups, file);
  if (!options.white) return;
  // The written channels are scale · M_r · film: M_r⁻¹ takes them back to the film's unbalanced channels (M_r is a
  // Bradford adaptation or a positive diagonal, always invertible), and the new white's matrix adapts those.
  Matrix3 undo = Matrix3::identity();
  if (white_balanced) {
    if (!render_white_balance)
      throw InputError({file, 0, "--white-balance"},
                       "was rendered with a white balance (rimu:whiteBalance) that cannot be undone: a camera-xyz "
                       "film holds it in its fitted channels (rimu:whiteBalanceInFilmResponse; render again with "
                       "the new white balance), or the file has no rimu:whiteBalanceMatrix and its rimu:whiteBalance "
                       "is not one Rimu can rebuild");
    undo = render_white_balance->inverse();
  }
  FilmOutputTransform transform = film.output_transform();
  transform.channel_matrix = display_white_balance_matrix(*options.white, film.response(), library) * undo *
                             transform.channel_matrix;
  film.set_output_transform(transform);
}

}  // namespace rimu
