// Relighting a rendered EXR without rendering: rebalancing its light groups and white-balancing it for display
// (`rimu display --group sun=2,lamps=0.5 --white-balance 4500K`).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "render/camera/camera_exposure.h"
#include "render/film/film.h"
#include "spectral/colorimetry/chromaticity.h"
#include "spectral/library/spectral_library.h"

namespace rimu {

/// One group's new weight: its layer counts `scale` times in the beauty (1 leaves it as rendered, 0 removes it).
struct LightGroupScale {
  std::string group;
  double scale = 1.0;
};

/// The white a display image is balanced from: a temperature or an illuminant (as `rimu --white-balance` takes it),
/// or a chromaticity.
struct DisplayWhite {
  WhiteBalanceSettings settings;        ///< Kind::none when `xy` is given
  std::optional<Chromaticity> xy;       ///< CIE 1931 x, y of the white
  std::string text;                     ///< as given, for messages
};

/// What `rimu display` changes in the image before showing it. Empty: the image as written.
struct ExrRelightOptions {
  std::vector<LightGroupScale> groups;
  std::optional<DisplayWhite> white;
};

/// Parses "sun=2,lamps=0.5": names and finite scales ≥ 0 (at most 1e6), each group once. InputError naming
/// `option` otherwise.
std::vector<LightGroupScale> parse_light_group_scales(const std::string& text, const std::string& option);

/// Parses "4500K", "4500", an illuminant name ("D50", "A") or a chromaticity "x,y" (0 < x, y < 1, x + y < 1).
/// InputError naming `option` otherwise.
DisplayWhite parse_display_white(const std::string& text, SpectralLibrary& library, const std::string& option);

/// Rebalances `film`'s light groups: the beauty's sums (channels and spectral bins) become beauty + Σ_g (s_g − 1)·layer_g
/// and each named layer's sums s_g·layer_g (groups not named keep 1), so the layers still sum to the beauty and `--group x=0` shows the
/// beauty minus layer x exactly (one subtraction in double per channel). InputError naming `file` if the film has
/// no light groups, or a name is not one of them (the message lists them).
void rebalance_light_groups(Film& film, const std::vector<LightGroupScale>& scales, const std::string& file);

/// The 3×3 matrix on the film's channels that adapts `white` to the display's (D65), by the Bradford transform
/// (white_balance_matrix, render/camera/physical_camera.h): for a temperature or illuminant, the film's own response
/// to its spectrum; for a chromaticity (XYZ films only), that chromaticity at Y = 1. InputError for a chromaticity
/// on a camera film (it has no spectrum to see through the camera's curves).
Matrix3 display_white_balance_matrix(const DisplayWhite& white, const SpectralResponse& response,
                                     SpectralLibrary& library);

/// Both: rebalances the groups and puts the white balance in front of the film's output transform. `white_balanced`
/// says whether the file records a white balance already, `render_white_balance` the matrix M_r the render applied
/// to the written channels: the display's matrix is then M_new · M_r⁻¹ (the render's adaptation undone first), so the
/// image shows the white asked for as if the render had none. InputError naming `file` and --white-balance if the
/// file is white-balanced but M_r is unknown.
void relight_exr_film(Film& film, const ExrRelightOptions& options, bool white_balanced,
                      const std::optional<Matrix3>& render_white_balance, const std::string& file,
                      SpectralLibrary& library);

}  // namespace rimu
