// rimu-pbrt-image-compare: the image half of bench/pbrt_side_by_side.sh. Reads a pbrt-v4 EXR (linear R, G, B in
// its film's colour space) and a Rimu EXR (CIE 1931 X, Y, Z), brings both to the same RGB space with the exact
// matrix of Rimu's colour-space code, and prints key=value lines the script turns into a table:
//
//   rimu-pbrt-image-compare compare A.exr B.exr [--space srgb-linear] [--block 8]
//       channel means of both, their ratio B/A per channel, and per block×block tile and channel the mean
//       paired difference in units of its standard error (sd of the 64 pixel differences / 8)
//   rimu-pbrt-image-compare relmse IMAGE.exr REFERENCE.exr [--space srgb-linear]
//       relMSE = mean over pixels and channels of (x − r)² / (r² + 0.01); also the same without the worst 0.1 %
//       of the pixels, and those pixels' share of the sum (fireflies). --denominator D.exr: r taken from D instead
//       (two renders of one renderer compared with each other, weighted alike for both renderers)
//   rimu-pbrt-image-compare png A.exr B.exr OUT.png [--space srgb-linear]
//       A and B side by side, enlarged 3×, one exposure for both (A's mean luminance shown as 18 % grey),
//       clipped and sRGB-encoded, 8 bits: the pictures next to the numbers in docs/benchmarks.md
//   rimu-pbrt-image-compare info IMAGE.exr
//       render_time_s: pbrt's "renderTimeSeconds" or Rimu's "rimu:renderTimeSeconds" header attribute; pixels: the
//       data window's pixel count
//   rimu-pbrt-image-compare allocation COUNTS.exr RUN.exr RUN.exr ... --run-spp N
//       what an adaptive render's per-pixel sample counts (COUNTS.exr's `spp` channel) are worth, without that
//       render's own noise: from k ≥ 2 independent uniform renders of N spp each (RUN.exr; their mean is r, their
//       spread per pixel times N the variance per sample σ²), each pixel's q = the mean over channels of
//       σ²/(r² + 0.01), so that a render of n_i samples in pixel i has the expected relMSE Σ q_i/n_i / pixels.
//       Prints allocation_gain (a uniform render of the same mean over those counts), oracle_gain (n_i ∝ √q_i, the
//       best any per-pixel allocation of the same samples does) and oracle_3x3_gain (n_i ∝ the root of q's 3×3
//       mean: what estimates as smooth as the sampler's would reach with exact variances). Equal samples, not CPU
//       time: the counts carry no cost. docs/benchmarks.md, "Adaptive sampling"
//   rimu-pbrt-image-compare mean OUT.exr IN.exr IN.exr ... [--space srgb-linear]
//       the per-pixel mean of the inputs (each converted to the RGB space), written as R, G, B floats with that
//       space's chromaticities: a reference averaged from renders of several seeds (docs/benchmarks.md,
//       "Metropolis light transport")
//   --crop X0 Y0 X1 Y1 (compare, relmse, png): only the pixels x0 ≤ x < x1, y0 ≤ y < y1 of both images (e.g. one
//       object's pixels, so that its mean is not diluted by the rest of the frame)
//
// Either file may hold R, G, B or X, Y, Z channels (found by name); anything else is an error (exit 1).
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <OpenImageIO/imageio.h>
#include <ImfDoubleAttribute.h>
#include <ImfFloatAttribute.h>

#include <algorithm>
#include <array>
#include <optional>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "spectral/colour_spaces/rgb_colour_space.h"

namespace {

struct LinearRgbImage {
  int width = 0, height = 0;
  std::vector<double> rgb;  // 3 per pixel, row 0 at the top
  double at(int x, int y, int c) const { return rgb[3 * (size_t(y) * size_t(width) + size_t(x)) + size_t(c)]; }
};

[[noreturn]] void fail(const std::string& message, int status = 1) {
  std::cerr << "rimu-pbrt-image-compare: " << message << "\n";
  std::exit(status);
}

// The named FLOAT channels of an open EXR, one plane each over its data window, row by row.
std::vector<std::vector<float>> read_planes(Imf::InputFile& file, const std::vector<const char*>& names) {
  const Imath::Box2i window = file.header().dataWindow();
  const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
  std::vector<std::vector<float>> planes(names.size(), std::vector<float>(size_t(width) * size_t(height)));
  Imf::FrameBuffer frame;
  for (size_t c = 0; c < names.size(); ++c) {
    char* origin = reinterpret_cast<char*>(planes[c].data() - window.min.x - window.min.y * width);
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, origin, sizeof(float), sizeof(float) * size_t(width)));
  }
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  return planes;
}

// Reads R,G,B (taken as already in `space`) or X,Y,Z (converted with space.xyz_to_rgb()).
LinearRgbImage read_linear_rgb(const std::filesystem::path& path, const rimu::RgbColourSpace& space) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
    const Imf::ChannelList& channels = file.header().channels();
    const bool xyz = channels.findChannel("X") && channels.findChannel("Y") && channels.findChannel("Z");
    const bool rgb = channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
    if (!xyz && !rgb) fail(path.string() + ": has neither R, G, B nor X, Y, Z channels");
    // A pbrt file names its primaries: they must be the space the comparison is made in.
    if (rgb && Imf::hasChromaticities(file.header())) {
      const Imf::Chromaticities& c = Imf::chromaticities(file.header());
      const auto far = [](Imath::V2f p, rimu::Chromaticity q) { return std::abs(p.x - q.x) + std::abs(p.y - q.y) > 2e-3; };
      if (far(c.red, space.red()) || far(c.green, space.green()) || far(c.blue, space.blue()) ||
          far(c.white, space.white()))
        fail(path.string() + ": its chromaticities are not those of " + space.name() + " (use --space)");
    }
    const std::vector<std::vector<float>> planes =
        read_planes(file, xyz ? std::vector<const char*>{"X", "Y", "Z"} : std::vector<const char*>{"R", "G", "B"});
    const size_t n = size_t(width) * size_t(height);
    LinearRgbImage image{width, height, std::vector<double>(3 * n)};
    for (size_t i = 0; i < n; ++i) {
      const double a = planes[0][i], b = planes[1][i], c = planes[2][i];
      if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c))
        fail(path.string() + ": pixel " + std::to_string(i % size_t(width)) + "," + std::to_string(i / size_t(width)) +
             " is not finite");
      rimu::Rgb out{a, b, c};
      if (xyz) out = space.from_xyz(rimu::Xyz{a, b, c});
      image.rgb[3 * i] = out.r, image.rgb[3 * i + 1] = out.g, image.rgb[3 * i + 2] = out.b;
    }
    return image;
  } catch (const std::exception& e) {
    fail(path.string() + ": " + e.what());
  }
}

void require_same_size(const LinearRgbImage& a, const LinearRgbImage& b);

// The per-pixel mean of `inputs`, written to `path` as float R, G, B in `space` (with its chromaticities).
void write_mean(const std::vector<std::string>& inputs, const std::string& path, const rimu::RgbColourSpace& space) {
  LinearRgbImage mean = read_linear_rgb(inputs[0], space);
  for (size_t i = 1; i < inputs.size(); ++i) {
    const LinearRgbImage next = read_linear_rgb(inputs[i], space);
    require_same_size(mean, next);
    for (size_t k = 0; k < mean.rgb.size(); ++k) mean.rgb[k] += next.rgb[k];
  }
  std::vector<float> planes[3];
  for (int c = 0; c < 3; ++c) planes[c].resize(size_t(mean.width) * size_t(mean.height));
  for (size_t i = 0; i < planes[0].size(); ++i)
    for (int c = 0; c < 3; ++c) planes[c][i] = float(mean.rgb[3 * i + size_t(c)] / double(inputs.size()));
  try {
    Imf::Header header(mean.width, mean.height);
    const char* names[3] = {"R", "G", "B"};
    Imf::FrameBuffer frame;
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(planes[c].data()), sizeof(float),
                                        sizeof(float) * size_t(mean.width)));
    }
    Imf::addChromaticities(header, Imf::Chromaticities({float(space.red().x), float(space.red().y)},
                                                       {float(space.green().x), float(space.green().y)},
                                                       {float(space.blue().x), float(space.blue().y)},
                                                       {float(space.white().x), float(space.white().y)}));
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(mean.height);
  } catch (const std::exception& e) {
    fail(path + ": " + e.what());
  }
}

void require_same_size(const LinearRgbImage& a, const LinearRgbImage& b) {
  if (a.width != b.width || a.height != b.height)
    fail("the images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
         std::to_string(b.width) + "x" + std::to_string(b.height));
}

void print_triple(const char* key, const double v[3]) { std::printf("%s=%.6g,%.6g,%.6g\n", key, v[0], v[1], v[2]); }

// Means, their ratio, and the block test. Two unbiased renders of one scene differ per pixel by noise alone, so the
// mean of a block's 64 paired differences divided by its standard error is ~N(0, 1): a block and channel beyond
// ~4.5 (the project's threshold for 48–300 tests) is a difference in the images, not noise.
void compare(const LinearRgbImage& a, const LinearRgbImage& b, int block) {
  require_same_size(a, b);
  double sum_a[3] = {0, 0, 0}, sum_b[3] = {0, 0, 0};
  for (size_t i = 0; i < a.rgb.size(); ++i) sum_a[i % 3] += a.rgb[i], sum_b[i % 3] += b.rgb[i];
  const double n = double(a.width) * double(a.height);
  double mean_a[3], mean_b[3], ratio[3];
  for (int c = 0; c < 3; ++c) {
    mean_a[c] = sum_a[c] / n, mean_b[c] = sum_b[c] / n;
    ratio[c] = mean_a[c] != 0 ? mean_b[c] / mean_a[c] : NAN;
  }
  print_triple("mean_a", mean_a);
  print_triple("mean_b", mean_b);
  print_triple("ratio_b_over_a", ratio);

  int tests = 0, beyond_3 = 0, beyond_4_5 = 0;
  double worst = 0, sum_sq = 0;
  std::string worst_where = "none";
  for (int by = 0; by + block <= a.height; by += block)
    for (int bx = 0; bx + block <= a.width; bx += block)
      for (int c = 0; c < 3; ++c) {
        double s = 0, s2 = 0;
        for (int y = by; y < by + block; ++y)
          for (int x = bx; x < bx + block; ++x) {
            const double d = b.at(x, y, c) - a.at(x, y, c);
            s += d, s2 += d * d;
          }
        const double m = double(block) * double(block);
        const double mean = s / m, variance = std::max(0.0, (s2 - s * s / m) / (m - 1));
        const double se = std::sqrt(variance / m);
        const double z = se > 0 ? mean / se : (mean == 0 ? 0.0 : INFINITY);
        ++tests;
        sum_sq += std::isfinite(z) ? z * z : 0;
        beyond_3 += std::abs(z) > 3.0;
        beyond_4_5 += std::abs(z) > 4.5;
        if (std::abs(z) > std::abs(worst)) {
          worst = z;
          worst_where = "block(" + std::to_string(bx) + "," + std::to_string(by) + ")" + "RGB"[c];
        }
      }
  std::printf("block_tests=%d\nblocks_beyond_3sigma=%d\nblocks_beyond_4.5sigma=%d\n", tests, beyond_3, beyond_4_5);
  std::printf("rms_z=%.4g\nworst_z=%.4g\nworst_at=%s\n", std::sqrt(sum_sq / std::max(tests, 1)), worst,
              worst_where.c_str());
}

void relmse(const LinearRgbImage& image, const LinearRgbImage& reference, const LinearRgbImage& denominator) {
  require_same_size(image, reference);
  require_same_size(image, denominator);
  std::vector<double> per_pixel(image.rgb.size() / 3, 0.0);
  double sum = 0;
  for (size_t i = 0; i < image.rgb.size(); ++i) {
    const double d = image.rgb[i] - reference.rgb[i], r = denominator.rgb[i];
    const double e = d * d / (r * r + 0.01);
    sum += e;
    per_pixel[i / 3] += e;
  }
  std::printf("relmse=%.6g\n", sum / double(image.rgb.size()));
  // How much of it a few pixels carry (fireflies): relMSE without the worst 0.1 % of the pixels (at least one),
  // and their share of the sum. relMSE is unbounded per pixel, so one firefly can decide a comparison.
  const size_t worst = std::max<size_t>(1, per_pixel.size() / 1000);
  std::nth_element(per_pixel.begin(), per_pixel.begin() + std::ptrdiff_t(worst), per_pixel.end(), std::greater<>());
  double top = 0;
  for (size_t i = 0; i < worst; ++i) top += per_pixel[i];
  const size_t rest = std::max<size_t>(1, per_pixel.size() - worst);  // a 1-pixel crop has no rest: 0
  std::printf("relmse_without_worst_0.1pct=%.6g\nworst_0.1pct_share=%.4g\n", std::max(0.0, sum - top) / double(3 * rest),
              sum > 0 ? top / sum : 0.0);
}

// One float channel of an EXR (e.g. an adaptive render's `spp`), row by row.
std::vector<double> read_channel(const std::filesystem::path& path, const char* name, int& width, int& height) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
    if (!file.header().channels().findChannel(name)) fail(path.string() + ": has no channel " + name);
    const std::vector<float> plane = read_planes(file, {name}).front();
    return {plane.begin(), plane.end()};
  } catch (const std::exception& e) {
    fail(path.string() + ": " + e.what());
  }
}

// The `allocation` command (see the header): q per pixel from the runs, then the expected relMSE of three
// allocations of the counts' mean S against S everywhere.
void allocation(const std::vector<double>& counts, const std::vector<LinearRgbImage>& runs, double run_spp) {
  const LinearRgbImage& first = runs.front();
  for (const LinearRgbImage& run : runs) require_same_size(first, run);
  const size_t pixels = size_t(first.width) * size_t(first.height);
  if (counts.size() != pixels) fail("the counts image differs in size from the runs");
  const double k = double(runs.size());
  std::vector<double> q(pixels, 0.0);
  for (size_t i = 0; i < 3 * pixels; ++i) {
    double mean = 0.0, spread = 0.0;
    for (const LinearRgbImage& run : runs) mean += run.rgb[i] / k;
    for (const LinearRgbImage& run : runs) spread += (run.rgb[i] - mean) * (run.rgb[i] - mean) / (k - 1.0);
    q[i / 3] += spread * run_spp / (mean * mean + 0.01) / 3.0;
  }
  double samples = 0.0;
  for (size_t i = 0; i < pixels; ++i) {
    if (!(counts[i] > 0)) fail("pixel " + std::to_string(i) + " of the counts has no samples");
    samples += counts[i];
  }
  const double mean_samples = samples / double(pixels);
  const auto expected_relmse = [&](const std::vector<double>& n) {
    double sum = 0.0;
    for (size_t i = 0; i < pixels; ++i) sum += q[i] / n[i];
    return sum / double(pixels);
  };
  // n_i ∝ weight_i with the same total (a pixel of weight 0 keeps a hundredth of a sample: its q is 0 too); all
  // weights 0 (runs without noise): the counts' mean everywhere.
  const auto proportional = [&](const std::vector<double>& weight) {
    double sum = 0.0;
    for (double w : weight) sum += w;
    std::vector<double> n(pixels, mean_samples);
    if (sum > 0.0)
      for (size_t i = 0; i < pixels; ++i) n[i] = std::max(0.01, samples * weight[i] / sum);
    return n;
  };
  std::vector<double> root(pixels), smooth_root(pixels);
  for (size_t i = 0; i < pixels; ++i) root[i] = std::sqrt(q[i]);
  for (int y = 0; y < first.height; ++y)
    for (int x = 0; x < first.width; ++x) {
      double sum = 0.0;
      int count = 0;
      for (int v = std::max(0, y - 1); v <= std::min(first.height - 1, y + 1); ++v)
        for (int u = std::max(0, x - 1); u <= std::min(first.width - 1, x + 1); ++u, ++count)
          sum += q[size_t(v) * size_t(first.width) + size_t(u)];
      smooth_root[size_t(y) * size_t(first.width) + size_t(x)] = std::sqrt(sum / count);
    }
  const double uniform = expected_relmse(std::vector<double>(pixels, mean_samples));
  if (!(uniform > 0.0)) fail("the runs agree in every pixel: no noise to weigh the counts by (different seeds?)");
  std::printf("mean_spp=%.6g\nuniform_expected_relmse=%.6g\n", mean_samples, uniform);
  std::printf("allocation_gain=%.4f\noracle_gain=%.4f\noracle_3x3_gain=%.4f\n", uniform / expected_relmse(counts),
              uniform / expected_relmse(proportional(root)), uniform / expected_relmse(proportional(smooth_root)));
}

void side_by_side_png(const LinearRgbImage& a, const LinearRgbImage& b, const rimu::RgbColourSpace& space,
                      const std::filesystem::path& out) {
  require_same_size(a, b);
  constexpr int kZoom = 3, kGap = 2;
  const rimu::Matrix3& m = space.rgb_to_xyz();
  double mean_y = 0;
  for (size_t i = 0; i < a.rgb.size(); i += 3)
    mean_y += m(1, 0) * a.rgb[i] + m(1, 1) * a.rgb[i + 1] + m(1, 2) * a.rgb[i + 2];
  mean_y /= double(a.width) * double(a.height);
  const double exposure = mean_y > 0 ? 0.18 / mean_y : 1.0;
  const int width = kZoom * (2 * a.width) + kGap, height = kZoom * a.height;
  std::vector<unsigned char> pixels(size_t(width) * size_t(height) * 3, 255);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int xa = x / kZoom, xb = (x - kZoom * a.width - kGap) / kZoom;
      const bool in_a = xa < a.width, in_b = x >= kZoom * a.width + kGap;
      if (!in_a && !in_b) continue;
      for (int c = 0; c < 3; ++c) {
        const double v = in_a ? a.at(xa, y / kZoom, c) : b.at(xb, y / kZoom, c);
        const double encoded = rimu::srgb_encode(std::clamp(v * exposure, 0.0, 1.0));
        pixels[3 * (size_t(y) * size_t(width) + size_t(x)) + size_t(c)] = (unsigned char)std::lround(255 * encoded);
      }
    }
  auto file = OIIO::ImageOutput::create(out.string());
  if (!file || !file->open(out.string(), OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8)) ||
      !file->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !file->close())
    fail(out.string() + ": cannot write: " + (file ? file->geterror() : OIIO::geterror()), 2);
}

// The render time each renderer records in its EXR header (pbrt-v4: float "renderTimeSeconds", the integrator's
// loop only; Rimu: double "rimu:renderTimeSeconds", the render loop only): wall time minus this is load + output.
void info(const std::filesystem::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    if (const auto* pbrt = file.header().findTypedAttribute<Imf::FloatAttribute>("renderTimeSeconds"))
      std::printf("render_time_s=%.6g\n", double(pbrt->value()));
    else if (const auto* rimu = file.header().findTypedAttribute<Imf::DoubleAttribute>("rimu:renderTimeSeconds"))
      std::printf("render_time_s=%.6g\n", rimu->value());
    else
      fail(path.string() + ": no renderTimeSeconds attribute");
    // The pixel count, for per-sample costs (bench/pbrt_side_by_side.sh's CPU table).
    const Imath::Box2i window = file.header().dataWindow();
    std::printf("pixels=%lld\n", (long long)(window.max.x - window.min.x + 1) * (long long)(window.max.y - window.min.y + 1));
  } catch (const std::exception& e) {
    fail(path.string() + ": " + e.what());
  }
}

/// The pixels x0 ≤ x < x1, y0 ≤ y < y1 of `image` (the crop must lie inside it).
LinearRgbImage crop(const LinearRgbImage& image, const std::array<int, 4>& box) {
  const auto [x0, y0, x1, y1] = box;
  if (!(0 <= x0 && x0 < x1 && x1 <= image.width && 0 <= y0 && y0 < y1 && y1 <= image.height))
    fail("--crop " + std::to_string(x0) + " " + std::to_string(y0) + " " + std::to_string(x1) + " " + std::to_string(y1) +
         " does not lie inside the " + std::to_string(image.width) + "x" + std::to_string(image.height) + " image");
  LinearRgbImage out{x1 - x0, y1 - y0, {}};
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) out.rgb.push_back(image.at(x, y, c));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> positional;
  std::string space_name = "srgb-linear";
  int block = 8;
  std::optional<std::array<int, 4>> crop_box;
  std::string denominator_path;
  double run_spp = 0.0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--space" && i + 1 < argc) space_name = argv[++i];
    else if (arg == "--crop" && i + 4 < argc) {
      crop_box = std::array<int, 4>{};
      for (int& v : *crop_box) v = std::atoi(argv[++i]);
    }
    else if (arg == "--block" && i + 1 < argc) block = std::atoi(argv[++i]);
    else if (arg == "--denominator" && i + 1 < argc) denominator_path = argv[++i];
    else if (arg == "--run-spp" && i + 1 < argc) run_spp = std::atof(argv[++i]);
    else if (arg.rfind("--", 0) == 0) fail("unknown option " + arg);
    else positional.push_back(arg);
  }
  const std::string command = positional.empty() ? "" : positional[0];
  const size_t expected = command == "info" ? 2 : command == "png" ? 4 : 3;
  const bool allocation_usage = command == "allocation" && positional.size() >= 4 && run_spp > 0;
  const bool mean_usage = command == "mean" && positional.size() >= 3;
  if (!allocation_usage && !mean_usage && ((command != "info" && command != "png" && command != "compare" && command != "relmse") ||
                            positional.size() != expected || block < 2))
    fail("usage: rimu-pbrt-image-compare compare|relmse A.exr B.exr | png A.exr B.exr OUT.png | info A.exr | "
         "allocation COUNTS.exr RUN.exr RUN.exr... --run-spp N | mean OUT.exr IN.exr... "
         "[--space NAME] [--block N] [--crop X0 Y0 X1 Y1] [--denominator D.exr]");
  if (command == "info") {
    info(positional[1]);
    return 0;
  }
  const rimu::RgbColourSpace* space = nullptr;
  try {
    space = &rimu::RgbColourSpace::named(space_name);
  } catch (const std::exception& e) {
    fail(std::string("--space: ") + e.what());
  }
  if (command == "mean") {
    write_mean(std::vector<std::string>(positional.begin() + 2, positional.end()), positional[1], *space);
    return 0;
  }
  if (command == "allocation") {
    int width = 0, height = 0;
    const std::vector<double> counts = read_channel(positional[1], "spp", width, height);
    std::vector<LinearRgbImage> runs;
    for (size_t i = 2; i < positional.size(); ++i) runs.push_back(read_linear_rgb(positional[i], *space));
    allocation(counts, runs, run_spp);
    return 0;
  }
  LinearRgbImage a = read_linear_rgb(positional[1], *space);
  LinearRgbImage b = read_linear_rgb(positional[2], *space);
  if (crop_box) {
    a = crop(a, *crop_box);
    b = crop(b, *crop_box);
  }
  if (command == "png") side_by_side_png(a, b, *space, positional[3]);
  else if (command == "compare") compare(a, b, block);
  else {
    LinearRgbImage d = denominator_path.empty() ? b : read_linear_rgb(denominator_path, *space);
    if (crop_box && !denominator_path.empty()) d = crop(d, *crop_box);
    relmse(a, b, d);
  }
  return 0;
}
