// Relighting from the EXR beyond the beauty's channels: on a spectral film each light group carries its own spectral
// bins (they sum to the beauty's bin by bin, and `--group` moves them with the channels), and `rimu display
// --white-balance` on an image white-balanced at render time undoes the recorded adaptation first, so it shows what
// the same render without a white balance would show with that white.
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfStringAttribute.h>
#include <doctest/doctest.h>

#include <cmath>

#include "input_error_check.h"
#include "light_groups_support.h"
#include "render/camera/camera_exposure.h"
#include "render/output/exr_output.h"
#include "render/output/partial_exr.h"

using namespace rimu;
using namespace rimu::test;
namespace fs = std::filesystem;

namespace {

constexpr int kBins = 8;

std::vector<std::string> spectral_channels() {
  std::vector<std::string> names{"X", "Y", "Z"};
  for (int b = 0; b < kBins; ++b) names.push_back(spectral_channel_name(SpectralBinning{kBins}, b));
  return names;
}

// Σ_j |a_ij| |v_j|: how large the terms of a·v are, for rounding bounds.
std::array<double, 3> abs_apply(const Matrix3& a, const std::array<double, 3>& v) {
  std::array<double, 3> out{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[size_t(i)] += std::abs(a(i, j)) * std::abs(v[size_t(j)]);
  return out;
}

}  // namespace

TEST_CASE("light groups on a spectral film: each layer has the film's bins, and they sum to the beauty's") {
  ScratchFolder folder("light_groups_spectral");
  RenderJob job = tiny_job(light_groups_example(), folder / "spectral.exr");
  job.film = "spectral:" + std::to_string(kBins);
  render(job);
  const ExrChannels exr = read_channels(folder / "spectral.exr");
  // 3 + 8 beauty channels and 4 groups of 3 + 8.
  CHECK(exr.channels.size() == size_t(3 + kBins) * (1 + kExampleGroups.size()));
  check_layers_sum_to_beauty(exr, kExampleGroups, spectral_channels());
}

TEST_CASE("light groups on a spectral film: --group moves the bins with the channels, and partials record the layout") {
  ScratchFolder folder("light_groups_spectral_partial");
  RenderJob job = tiny_job(light_groups_example(), folder / "partial.exr", SampleRange{0, 8});
  job.film = "spectral:" + std::to_string(kBins);
  render(job);
  const PartialImage partial = read_partial_exr(folder / "partial.exr");
  CHECK(partial.spectral_bins == kBins);
  CHECK(partial.accumulators_per_pixel == 4 + kBins + 4 * (3 + kBins));

  const ExrDisplaySource plain = read_exr_for_display(folder / "partial.exr", library());
  const ExrDisplaySource relit = read_exr_for_display(folder / "partial.exr", library());
  rebalance_light_groups(*relit.film, {{"lamps", 0.0}, {"sun", 2.0}}, "partial.exr");
  const int sun = 1, lamps = 2;
  const PixelBounds& b = plain.film->pixel_bounds();
  double lamps_light = 0.0;
  for (int y = b.y0; y < b.y1; ++y)
    for (int x = b.x0; x < b.x1; ++x)
      for (int bin = 0; bin < kBins; ++bin) {
        const double beauty = plain.film->spectral_value(x, y, bin);
        const double l = plain.film->group_spectral_value(x, y, lamps, bin);
        const double s = plain.film->group_spectral_value(x, y, sun, bin);
        lamps_light += l;
        // beauty − lamps + sun, added in another order: a few double roundings of the terms (4·2⁻⁵³, as for the
        // channels in light_groups_test.cpp).
        CHECK(std::abs(relit.film->spectral_value(x, y, bin) - (beauty - l + s)) <= 4 * 0x1p-53 * (beauty + l + s));
        CHECK(relit.film->group_spectral_value(x, y, lamps, bin) == 0.0);
        CHECK(relit.film->group_spectral_value(x, y, sun, bin) == 2.0 * s);
        // The bins of the layers still sum to the beauty's: the deltas added to both are the same doubles.
        double sum = 0.0, magnitude = beauty;
        for (int g = 0; g < 4; ++g) {
          sum += relit.film->group_spectral_value(x, y, g, bin);
          magnitude += plain.film->group_spectral_value(x, y, g, bin);
        }
        CHECK(std::abs(sum - relit.film->spectral_value(x, y, bin)) <= kLayerSumBound * (magnitude + s));
      }
  CHECK(lamps_light > 0.0);

  // A partial of this layout without rimu:partial:spectralBins is what a Rimu whose group layers had no bins wrote
  // (4 + N + 3·G sums): its sums cannot be told apart, so it is refused by name.
  copy_exr_with_header(folder / "partial.exr", folder / "older.exr",
                       [](Imf::Header& h) { h.erase("rimu:partial:spectralBins"); });
  input_error([&] { read_partial_exr(folder / "older.exr"); }, {"older.exr", "older Rimu", "spectral bins"});
  // A damaged layout: the bins and groups the header names do not make its accumulator count.
  copy_exr_with_header(folder / "partial.exr", folder / "damaged.exr",
                       [](Imf::Header& h) { h.insert("rimu:partial:spectralBins", Imf::IntAttribute(kBins - 1)); });
  input_error([&] { read_partial_exr(folder / "damaged.exr"); },
              {"damaged.exr", "rimu:partial:accumulators is 56", "7 spectral bins and 4 light groups (rimu:lightGroups) make 51"});
}

TEST_CASE("display --white-balance on a white-balanced render: the render's adaptation is undone first") {
  ScratchFolder folder("light_groups_white_undo");
  for (const bool partial : {false, true}) {
    CAPTURE(partial);
    const std::optional<SampleRange> samples = partial ? std::optional(SampleRange{0, 8}) : std::nullopt;
    RenderJob plain_job = tiny_job(light_groups_example(), folder / "plain.exr", samples);
    RenderJob balanced_job = tiny_job(light_groups_example(), folder / "balanced_a.exr", samples);
    balanced_job.white_balance = "A";
    render(plain_job);
    render(balanced_job);

    // The file says what it was adapted from and to, and by which matrix: the render's own.
    CameraExposureSettings camera;
    camera.white_balance = parse_white_balance_option("A", library(), "--white-balance");
    const Matrix3 m_a = film_output_transform(camera, SpectralResponse::cie_xyz(library()), library()).channel_matrix;
    {
      Imf::InputFile file((folder / "balanced_a.exr").c_str());
      const auto* matrix = file.header().findTypedAttribute<Imf::M33dAttribute>("rimu:whiteBalanceMatrix");
      REQUIRE(matrix);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) CHECK(matrix->value()[r][c] == m_a(r, c));
      CHECK(file.header().findTypedAttribute<Imf::StringAttribute>("rimu:whiteBalance")->value() == "illuminant A");
      CHECK(file.header().findTypedAttribute<Imf::StringAttribute>("rimu:whiteBalanceTarget")->value() == "D65");
      Imf::InputFile plain_file((folder / "plain.exr").c_str());
      CHECK_FALSE(plain_file.header().findTypedAttribute<Imf::M33dAttribute>("rimu:whiteBalanceMatrix"));
    }
    // A file from before rimu:whiteBalanceMatrix: the matrix is rebuilt from rimu:whiteBalance, bit for bit.
    copy_exr_with_header(folder / "balanced_a.exr", folder / "older_a.exr",
                         [](Imf::Header& h) { h.erase("rimu:whiteBalanceMatrix"); });
    const ExrDisplaySource older = read_exr_for_display(folder / "older_a.exr", library());
    REQUIRE(older.white_balance_matrix);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) CHECK((*older.white_balance_matrix)(r, c) == m_a(r, c));

    // For each display white X: display(render balanced to A, --white-balance X) = display(render, --white-balance X).
    for (const std::string white : {"D65", "3200K", "0.3457,0.3585", "F11"}) {
      CAPTURE(white);
      const DisplayWhite x = parse_display_white(white, library(), "--white-balance");
      const Matrix3 m_x = display_white_balance_matrix(x, SpectralResponse::cie_xyz(library()), library());
      for (const std::string name : {"balanced_a.exr", "older_a.exr"}) {
        CAPTURE(name);
        ExrDisplaySource reference = read_exr_for_display(folder / "plain.exr", library());
        ExrDisplaySource balanced = read_exr_for_display(folder / name, library());
        CHECK(balanced.white_balanced);
        relight_exr_film(*reference.film, {{}, x}, reference.white_balanced, reference.white_balance_matrix,
                         "plain.exr", library());
        relight_exr_film(*balanced.film, {{}, x}, balanced.white_balanced, balanced.white_balance_matrix, name,
                         library());
        // Bound. A final image holds the floats w_n = fl(v) and w_a = fl(M_A v) (exposure scale 1 here): the display
        // shows M_X w_n and M_X M_A⁻¹ w_a, which differ by M_X (M_A⁻¹ e_a − e_n) with |e| ≤ 2⁻²⁴ of each written
        // value: ≤ 2⁻²⁴ Σ_k |M_X|_ik (Σ_j |M_A⁻¹|_kj |w_a,j| + |w_n,k|), plus double rounding (≤ 2⁻⁴⁰ of it). A
        // partial holds the same double sums in both files: only the double rounding of M_X M_A⁻¹ M_A against M_X.
        const double unit = partial ? 0x1p-40 : 0x1p-24 + 0x1p-40;
        const PixelBounds& b = reference.film->pixel_bounds();
        double worst = 0.0;
        for (int y = b.y0; y < b.y1; ++y)
          for (int x_px = b.x0; x_px < b.x1; ++x_px) {
            const auto shown_reference = reference.film->output_value(x_px, y);
            const auto shown = balanced.film->output_value(x_px, y);
            // The unbalanced values (a final image's floats; a partial's film values, shown times its exposure
            // scale) and the balanced ones M_A·v.
            const auto written_plain = reference.film->pixel_value(x_px, y);
            const auto written_a = m_a.apply(written_plain);
            const auto through_undo = abs_apply(m_a.inverse(), written_a);
            std::array<double, 3> terms{};
            for (int k = 0; k < 3; ++k)
              terms[size_t(k)] = (through_undo[size_t(k)] + std::abs(written_plain[size_t(k)])) *
                                 reference.film->output_transform().scale;
            const auto magnitude = abs_apply(m_x, terms);
            for (size_t c = 0; c < 3; ++c) {
              CHECK(std::abs(shown[c] - shown_reference[c]) <= unit * magnitude[c]);
              if (magnitude[c] > 0.0) worst = std::max(worst, std::abs(shown[c] - shown_reference[c]) / magnitude[c]);
            }
          }
        MESSAGE(name << " under " << white << ": largest difference " << worst << " of the bound's magnitude");
      }
    }
    // --group alone needs no matrix: a file whose white balance cannot be rebuilt still rebalances, but refuses a
    // second white by name.
    copy_exr_with_header(folder / "balanced_a.exr", folder / "unknown.exr", [](Imf::Header& h) {
      h.erase("rimu:whiteBalanceMatrix");
      h.insert("rimu:whiteBalance", Imf::StringAttribute("sunset"));
    });
    ExrDisplaySource unknown = read_exr_for_display(folder / "unknown.exr", library());
    CHECK_FALSE(unknown.white_balance_matrix);
    relight_exr_film(*unknown.film, {{{"sun", 0.0}}, std::nullopt}, true, std::nullopt, "unknown.exr", library());
    const DisplayWhite d65 = parse_display_white("D65", library(), "--white-balance");
    input_error([&] {
      relight_exr_film(*unknown.film, {{}, d65}, true, unknown.white_balance_matrix, "unknown.exr", library());
    }, {"unknown.exr", "--white-balance", "cannot be undone"});
  }
}

TEST_CASE("display --white-balance undoes a camera film's render-time white balance too") {
  ScratchFolder folder("light_groups_white_camera");
  RenderJob plain_job = tiny_job(light_groups_example(), folder / "plain.exr");
  plain_job.film = "camera:nikon_d850";
  RenderJob balanced_job = plain_job;
  balanced_job.exr_output = folder / "balanced.exr";
  balanced_job.white_balance = "3200K";
  render(plain_job);
  render(balanced_job);
  {
    Imf::InputFile file((folder / "balanced.exr").c_str());
    CHECK(file.header().findTypedAttribute<Imf::StringAttribute>("rimu:whiteBalanceTarget")->value() ==
          "equal R, G, B (G kept)");
  }
  const DisplayWhite x = parse_display_white("A", library(), "--white-balance");
  ExrDisplaySource reference = read_exr_for_display(folder / "plain.exr", library());
  ExrDisplaySource balanced = read_exr_for_display(folder / "balanced.exr", library());
  REQUIRE(balanced.white_balance_matrix);
  relight_exr_film(*reference.film, {{}, x}, false, std::nullopt, "plain.exr", library());
  relight_exr_film(*balanced.film, {{}, x}, true, balanced.white_balance_matrix, "balanced.exr", library());
  // The camera's balances are diagonal: each channel of the balanced file is scaled and rounded to float, and scaled
  // back; the plain file's is rounded once: they agree to 2·2⁻²⁴ of each channel (plus the double rounding, 2⁻⁴⁰),
  // which the diagonal M_X keeps relative.
  const PixelBounds& b = reference.film->pixel_bounds();
  for (int y = b.y0; y < b.y1; ++y)
    for (int px = b.x0; px < b.x1; ++px) {
      const auto shown_reference = reference.film->output_value(px, y);
      const auto shown = balanced.film->output_value(px, y);
      for (size_t c = 0; c < 3; ++c)
        CHECK(std::abs(shown[c] - shown_reference[c]) <= (2 * 0x1p-24 + 0x1p-40) * std::abs(shown_reference[c]));
    }
}

TEST_CASE("display --white-balance refuses a camera-xyz film, whose white balance is part of its fitted channels") {
  ScratchFolder folder("light_groups_white_camera_xyz");
  RenderJob job = tiny_job(light_groups_example(), folder / "fitted.exr");
  job.film = "camera-xyz:nikon_d850";
  job.white_balance = "3200K";
  render(job);
  ExrDisplaySource fitted = read_exr_for_display(folder / "fitted.exr", library());
  CHECK(fitted.white_balanced);
  CHECK_FALSE(fitted.white_balance_matrix);
  CHECK(fitted.film->response().kind() == ResponseKind::cie_xyz);
  // Light groups still rebalance; a new white is an error naming the option and why.
  relight_exr_film(*fitted.film, {{{"sun", 0.0}}, std::nullopt}, true, std::nullopt, "fitted.exr", library());
  const DisplayWhite d65 = parse_display_white("D65", library(), "--white-balance");
  input_error([&] {
    relight_exr_film(*fitted.film, {{}, d65}, true, fitted.white_balance_matrix, "fitted.exr", library());
  }, {"fitted.exr", "--white-balance", "camera-xyz"});
}
