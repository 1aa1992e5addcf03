// Partial renders and their merge (render/output/merge_partials.h, render/output/partial_exr.h): N sample ranges or crop tiles of
// a render, merged, give the single process's image (crop tiles bit for bit; sample ranges within the stated bound
// of one float32 ULP); mismatched, overlapping and missing partials are errors that write nothing.
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <doctest/doctest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "test_support.h"
#include "render/output/exr_compare.h"
#include "render/output/merge_partials.h"
#include "render/output/partial_exr.h"
#include "render/render_job.h"
#include "spectral/error.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace {

struct Folder : test::ScratchFolder {
  explicit Folder(const std::string& name) : ScratchFolder("merge_" + name) {}
};

// The embedded Cornell box, small, float32 channels, 24 spp in all; `film` e.g. "spectral:47" or "camera:...".
RenderJob tiny_job(const fs::path& out, std::optional<SampleRange> samples, const std::string& film = "xyz") {
  RenderJob job;
  job.width = 24;
  job.height = 16;
  job.samples_per_pixel = 24;
  job.seed = 7;
  job.threads = 2;
  job.half_exr = false;  // 32-bit floats (the default)
  job.quiet = true;
  job.film = film;
  job.samples = samples;
  job.exr_output = out;
  return job;
}

void render_partial(const RenderJob& job) {
  std::ostringstream log;
  run_render_job(job, log);
}

MergeResult merge(const std::vector<fs::path>& parts, const fs::path& out, MergeOptions options = {}) {
  std::ostringstream log;
  return merge_partials(parts, out, options, log);
}

}  // namespace

TEST_CASE("partial renders: sample ranges merge to the single process's image within one float32 ULP") {
  for (const std::string film : {"xyz", "spectral:47"}) {
    CAPTURE(film);
    Folder dir("ranges");
    render_partial(tiny_job(dir / "single.exr", SampleRange{0, 24}, film));
    // Ranges that cut passes (the pass boundaries are 1, 3, 7, 15, 31) and one that is a whole pass.
    render_partial(tiny_job(dir / "a.exr", SampleRange{0, 5}, film));
    render_partial(tiny_job(dir / "b.exr", SampleRange{5, 15}, film));
    render_partial(tiny_job(dir / "c.exr", SampleRange{15, 24}, film));
    const MergeResult result = merge({dir / "c.exr", dir / "a.exr", dir / "b.exr"}, dir / "merged.exr");
    CHECK(result.complete);
    CHECK(result.samples_per_pixel == 24);
    const ExrDifference d = compare_exr(dir / "single.exr", dir / "merged.exr", true);
    CAPTURE(d.worst);
    CHECK(d.values == 24 * 16 * (film == "xyz" ? 3 : 50));
    // The bound (merge_partials.h): two more double additions per pixel cannot move a float32 by more than 1 ULP.
    CHECK(d.max_ulps <= 1);
    MESSAGE(film << ": " << d.different << " of " << d.values << " values differ (by 1 ULP)");

    // The merged sums agree with the single process's to double rounding. Both are sums of the same m non-negative
    // terms in different association (ranges that cut a pass split its tile sums), and a recursive sum of m
    // non-negative terms is within (m - 1) u of the exact one (u = 2^-53), so the two differ by at most
    // 2 (m - 1) u relative. m: 24 samples from each pixel within the Gaussian's 1.5-pixel radius (at most 5 x 5).
    const PartialImage single = read_partial_exr(dir / "single.exr");
    const PartialImage merged = read_partial_exr(dir / "merged.exr");
    REQUIRE(single.sums.size() == merged.sums.size());
    const double terms = 24.0 * 25.0;
    for (size_t i = 0; i < single.sums.size(); ++i)
      REQUIRE(std::abs(single.sums[i] - merged.sums[i]) <= 2.0 * (terms - 1.0) * 0x1p-53 * std::abs(single.sums[i]));
    CHECK(merged.record.samples == std::vector<SampleRange>{{0, 24}});

    // A plain render (no --samples) writes the same image as the partial covering everything: bit for bit.
    RenderJob plain = tiny_job(dir / "plain.exr", std::nullopt, film);
    render_partial(plain);
    CHECK(compare_exr(dir / "single.exr", dir / "plain.exr", true).different == 0);
  }
}

TEST_CASE("partial renders: crop tiles merge bit for bit, and a merged file merges again (tree of merges)") {
  Folder dir("tiles");
  render_partial(tiny_job(dir / "single.exr", SampleRange{0, 24}));
  RenderJob left = tiny_job(dir / "left.exr", SampleRange{0, 24});
  left.crop = PixelBounds{0, 0, 10, 16};
  RenderJob right = tiny_job(dir / "right.exr", SampleRange{0, 24});
  right.crop = PixelBounds{10, 0, 24, 16};
  render_partial(left);
  render_partial(right);
  merge({dir / "right.exr", dir / "left.exr"}, dir / "merged.exr");
  CHECK(compare_exr(dir / "single.exr", dir / "merged.exr", false).different == 0);  // sums too

  // Tree: (a + b) + c equals a + b + c up to the same bound.
  render_partial(tiny_job(dir / "a.exr", SampleRange{0, 8}));
  render_partial(tiny_job(dir / "b.exr", SampleRange{8, 16}));
  render_partial(tiny_job(dir / "c.exr", SampleRange{16, 24}));
  MergeOptions gaps;
  gaps.allow_gaps = true;
  const MergeResult ab = merge({dir / "a.exr", dir / "b.exr"}, dir / "ab.exr", gaps);
  CHECK_FALSE(ab.complete);
  CHECK(ab.samples == std::vector<SampleRange>{{0, 16}});
  CHECK(merge({dir / "ab.exr", dir / "c.exr"}, dir / "abc.exr").complete);
  CHECK(compare_exr(dir / "single.exr", dir / "abc.exr", true).max_ulps <= 1);
}

TEST_CASE("partial renders: camera films keep their colour matrix and the photometric metadata through a merge") {
  Folder dir("camera");
  const std::string film = "camera:nikon_d850";
  RenderJob a = tiny_job(dir / "a.exr", SampleRange{0, 12}, film);
  a.iso = 400;
  RenderJob b = tiny_job(dir / "b.exr", SampleRange{12, 24}, film);
  b.iso = 400;
  RenderJob single = tiny_job(dir / "single.exr", SampleRange{0, 24}, film);
  single.iso = 400;
  render_partial(a);
  render_partial(b);
  render_partial(single);
  merge({dir / "a.exr", dir / "b.exr"}, dir / "merged.exr");
  CHECK(compare_exr(dir / "single.exr", dir / "merged.exr", true).max_ulps <= 1);
  const PartialImage s = read_partial_exr(dir / "single.exr");
  const PartialImage m = read_partial_exr(dir / "merged.exr");
  REQUIRE(m.metadata.camera_to_xyz);
  REQUIRE(m.metadata.camera);
  CHECK(m.metadata.camera->iso == doctest::Approx(400));
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) CHECK((*m.metadata.camera_to_xyz)(r, c) == (*s.metadata.camera_to_xyz)(r, c));
  CHECK(m.record.output_transform.scale == s.record.output_transform.scale);
  CHECK(m.metadata.extra == [&] {
    auto e = s.metadata.extra;
    e["mergedFrom"] = "2 partial renders";
    return e;
  }());
}

TEST_CASE("partial renders: mismatched, overlapping and missing partials are errors and nothing is written") {
  Folder dir("errors");
  render_partial(tiny_job(dir / "a.exr", SampleRange{0, 12}));
  render_partial(tiny_job(dir / "b.exr", SampleRange{12, 24}));
  const fs::path out = dir / "out.exr";
  auto refused = [&](const std::vector<fs::path>& parts, const std::string& message) {
    CAPTURE(message);
    try {
      merge(parts, out);
      FAIL("merged");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find(message) != std::string::npos);
      MESSAGE(std::string(e.what()));
    }
    CHECK_FALSE(fs::exists(out));
  };

  RenderJob other_seed = tiny_job(dir / "seed.exr", SampleRange{12, 24});
  other_seed.seed = 8;
  render_partial(other_seed);
  refused({dir / "a.exr", dir / "seed.exr"}, "seed 8 here, 7 there");

  RenderJob other_size = tiny_job(dir / "size.exr", SampleRange{12, 24});
  other_size.width = 20;
  render_partial(other_size);
  refused({dir / "a.exr", dir / "size.exr"}, "resolution 20x16 here, 24x16 there");

  RenderJob other_scene = tiny_job(dir / "scene.exr", SampleRange{12, 24});
  other_scene.film = "xyz10";
  render_partial(other_scene);
  refused({dir / "a.exr", dir / "scene.exr"}, "film xyz10 here, xyz there");
  RenderJob other_iso = tiny_job(dir / "iso.exr", SampleRange{12, 24});
  other_iso.iso = 200;
  render_partial(other_iso);
  refused({dir / "a.exr", dir / "iso.exr"}, "exposure or white balance");
  RenderJob other_mode = tiny_job(dir / "mode.exr", SampleRange{12, 24});
  other_mode.wavelengths = WavelengthMode::single;  // an image option with no check of its own: the scene hash tells
  render_partial(other_mode);
  refused({dir / "a.exr", dir / "mode.exr"}, "the scene (its file, the files it names, or image options) differs: scene hash");
  RenderJob half = tiny_job(dir / "half.exr", SampleRange{12, 24});
  half.half_exr = true;  // --half: not an image option (the scene hash is the same), the merge checks it itself
  render_partial(half);
  refused({dir / "a.exr", dir / "half.exr"}, "pixel type half here, float there");

  render_partial(tiny_job(dir / "overlap.exr", SampleRange{10, 24}));
  refused({dir / "a.exr", dir / "overlap.exr"}, "both hold samples 10:12");
  refused({dir / "a.exr", dir / "a.exr"}, "both hold samples 0:12");
  refused({dir / "a.exr"}, "no partial holds samples 12:24 of 24");

  RenderJob plain = tiny_job(dir / "plain.exr", std::nullopt);
  render_partial(plain);
  refused({dir / "a.exr", dir / "plain.exr"}, "not a partial render");
}

TEST_CASE("partial renders: --half partials merge to half, record --half for --resume, and old records still read") {
  Folder dir("half");
  RenderJob a = tiny_job(dir / "a.exr", SampleRange{0, 12}), b = tiny_job(dir / "b.exr", SampleRange{12, 24});
  a.half_exr = b.half_exr = true;
  render_partial(a);
  render_partial(b);
  merge({dir / "a.exr", dir / "b.exr"}, dir / "ab.exr");
  const PartialImage merged = read_partial_exr(dir / "ab.exr");
  CHECK(merged.pixel_type == ExrPixelType::half);  // the partials' type, as one process with --half would write
  CHECK(render_job_from_json(merged.record.job, "ab.exr").half_exr);  // --resume continues as half
  CHECK(read_partial_exr(dir / "a.exr").pixel_type == ExrPixelType::half);
  render_partial(tiny_job(dir / "f.exr", SampleRange{0, 12}));
  CHECK(read_partial_exr(dir / "f.exr").pixel_type == ExrPixelType::float32);  // the default
  CHECK_FALSE(render_job_from_json(read_partial_exr(dir / "f.exr").record.job, "f.exr").half_exr);
  // Records written while half was the default say "float": false for half and true for --float.
  CHECK(render_job_from_json(R"({"float": false})", "old.exr").half_exr);
  CHECK_FALSE(render_job_from_json(R"({"float": true})", "old.exr").half_exr);
}

TEST_CASE("the recorded job keeps the sensors' options, so --resume measures them as the first run would") {
  RenderJob job;
  job.sensors_output = "/tmp/room.sensors";
  job.sensor_samples = 2048;
  const RenderJob back = render_job_from_json(render_job_json(job), "record");
  REQUIRE(back.sensors_output);
  CHECK(*back.sensors_output == std::filesystem::path("/tmp/room.sensors"));
  CHECK(back.sensor_samples == std::optional<int>(2048));
  // Without them the record has neither (the scene's "sensors" defaults then apply, as on the first run).
  const RenderJob plain = render_job_from_json(render_job_json(RenderJob{}), "record");
  CHECK_FALSE(plain.sensors_output);
  CHECK_FALSE(plain.sensor_samples);
}

TEST_CASE("partial renders: --samples beyond the render's spp and malformed ranges are input errors") {
  CHECK_THROWS_AS(parse_sample_range("5:5", "--samples"), InputError);
  CHECK_THROWS_AS(parse_sample_range("0-64", "--samples"), InputError);
  CHECK(parse_sample_range("64:128", "--samples") == SampleRange{64, 128});
  CHECK(parse_sample_ranges("0:8,16:24", "x") == std::vector<SampleRange>{{0, 8}, {16, 24}});
  CHECK(parse_sample_ranges("", "x").empty());  // a checkpoint written before its first pass ended
  CHECK(sample_ranges_text({{0, 8}, {16, 24}}) == "0:8,16:24");
  CHECK(parse_duration_s("10m", "--checkpoint") == 600);
  CHECK(parse_duration_s("30s", "--checkpoint") == 30);
  CHECK_THROWS_AS(parse_duration_s("0s", "--checkpoint"), InputError);
  Folder dir("beyond");
  CHECK_THROWS_AS(render_partial(tiny_job(dir / "x.exr", SampleRange{0, 48})), InputError);
  CHECK_FALSE(fs::exists(dir / "x.exr"));
}

TEST_CASE("passes follow the sample index, so a range starting inside the schedule cuts at the same boundaries") {
  CHECK(sample_pass_end(0) == 1);
  CHECK(sample_pass_end(1) == 3);
  CHECK(sample_pass_end(2) == 3);
  CHECK(sample_pass_end(3) == 7);
  CHECK(sample_pass_end(14) == 15);
  CHECK(sample_pass_end(15) == 31);
  CHECK(sample_pass_end(30) == 31);
  CHECK(sample_pass_end(31) == 47);
}

TEST_CASE("partial renders: a header whose windows the file cannot hold is refused before the merge allocates") {
  // A real partial's header with its windows enlarged, and no pixels: before, the merge allocated a film for the
  // claimed window (30000 x 30000 pixels of 7 accumulators: 50 GB) and failed with std::bad_alloc (exit 2).
  Folder dir("hostile_header");
  render_partial(tiny_job(dir / "a.exr", SampleRange{0, 24}));
  const auto rewrite = [&](const std::string& name, int display_side, int data_side) {
    Imf::Header header = Imf::InputFile((dir / "a.exr").c_str()).header();
    header.displayWindow() = Imath::Box2i({0, 0}, {display_side - 1, display_side - 1});
    header.dataWindow() = Imath::Box2i({0, 0}, {data_side - 1, data_side - 1});
    { Imf::OutputFile out((dir / name).c_str(), header); }  // the header and an empty offset table only
    return dir / name;
  };
  const auto refused = [&](const fs::path& part, const std::string& message) {
    CAPTURE(message);
    try {
      merge({part}, dir / "out.exr", MergeOptions{true, true});
      FAIL("merged");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find(part.string()) != std::string::npos);
      CHECK(std::string(e.what()).find(message) != std::string::npos);
    }
    CHECK_FALSE(fs::exists(dir / "out.exr"));
  };
  refused(rewrite("huge.exr", 30000, 30000), "more than a file of");
  refused(rewrite("wide.exr", 40000, 16), "1 to 32768 pixels a side");
  refused(rewrite("outside.exr", 16, 24), "does not lie inside its display window");
}

TEST_CASE("partial renders: OpenEXR does not allocate for a data window of 2^29 rows that a damaged header claims") {
  // The fuzzer's input (fuzz/regressions/merge/): a 2 KB partial whose header made Imf::InputFile allocate its
  // line-offset table, 1.3-1.9 GB, before Rimu's checks saw the header. Here a real partial's data window is patched
  // in place to 2^29 rows (the file stays a few KB): OpenEXR must refuse it by the limits Rimu sets, naming the height.
  Folder dir("tall_header");
  render_partial(tiny_job(dir / "a.exr", SampleRange{0, 24}));
  std::ifstream in(dir / "a.exr", std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), {}};
  const std::string key = std::string("dataWindow") + '\0' + "box2i" + '\0';
  const std::size_t at = bytes.find(key);
  REQUIRE(at != std::string::npos);
  const std::size_t y_max = at + key.size() + 4 + 12;  // the size (4 bytes), then xMin, yMin, xMax, yMax
  const std::int32_t rows = std::int32_t(1) << 29;  // OpenEXR calls 2^30 itself invalid
  std::memcpy(bytes.data() + y_max, &rows, 4);  // little-endian, as OpenEXR stores it (and this machine)
  std::ofstream(dir / "tall.exr", std::ios::binary) << bytes;
  try {
    merge({dir / "tall.exr"}, dir / "out.exr", MergeOptions{true, true});
    FAIL("merged");
  } catch (const InputError& e) {
    const std::string message = e.what();
    CAPTURE(message);
    CHECK(std::string(e.what()).find("cannot read as OpenEXR") != std::string::npos);
    CHECK(std::string(e.what()).find("height") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(dir / "out.exr"));
}

TEST_CASE("partial renders: a header attribute claiming more bytes than the file holds is refused before OpenEXR reads it") {
  // fuzz_merge: a 2.7 KB partial whose rimu:partial:requested string claimed 1.86 GB, which OpenEXR allocated.
  Folder dir("attribute_size");
  render_partial(tiny_job(dir / "a.exr", SampleRange{0, 24}));
  std::ifstream in(dir / "a.exr", std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), {}};
  const std::string key = std::string("rimu:partial:requested") + '\0' + "string" + '\0';
  const std::size_t at = bytes.find(key);
  REQUIRE(at != std::string::npos);
  const std::int32_t claimed = 1862270979;
  std::memcpy(bytes.data() + at + key.size(), &claimed, 4);
  std::ofstream(dir / "claims.exr", std::ios::binary) << bytes;
  try {
    merge({dir / "claims.exr"}, dir / "out.exr", MergeOptions{true, true});
    FAIL("merged");
  } catch (const InputError& e) {
    const std::string message = e.what();
    CAPTURE(message);
    CHECK(message.find("'rimu:partial:requested'") != std::string::npos);
    CHECK(message.find("claims 1862270979 bytes") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(dir / "out.exr"));
}

TEST_CASE("partial renders: guided partials merge, a mix of guided and unguided partials is refused") {
  Folder dir("guiding");
  RenderJob a = tiny_job(dir / "a.exr", SampleRange{0, 12});
  a.guiding = "on";
  render_partial(a);
  RenderJob b = tiny_job(dir / "b.exr", SampleRange{12, 24});
  b.guiding = "on";
  render_partial(b);
  CHECK(read_partial_exr(dir / "a.exr", false).metadata.extra.at("guiding") == "on");
  // Each partial trained its own field: the merge is an unbiased image of 24 spp (not bit-identical to one process).
  CHECK(merge({dir / "a.exr", dir / "b.exr"}, dir / "merged.exr").samples_per_pixel == 24);

  render_partial(tiny_job(dir / "plain.exr", SampleRange{12, 24}));
  CHECK(read_partial_exr(dir / "plain.exr", false).metadata.extra.at("guiding") == "off");
  try {
    merge({dir / "a.exr", dir / "plain.exr"}, dir / "out.exr");
    FAIL("merged");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("path guiding (rimu:guiding) off here, on there") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(dir / "out.exr"));
}
