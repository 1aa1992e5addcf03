// The pbrt importer's Include graph and its bounds (issue 24): an include bomb and an instance bomb stop at a stated
// limit with the file and line that crossed it; the top-level file is read like every other input (regular files
// only); strings that are not UTF-8 and an ObjectBegin left open are errors at their line; and the files the
// import reads are the ones an InputFileLog records (the scene hash's source).
#include <doctest/doctest.h>

#include <sys/stat.h>

#include <chrono>
#include <string>

#include "pbrt_test_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/scene.h"
#include "spectral/io/input_file.h"
#include "test_support.h"

using namespace rimu;

namespace {

const std::string kScene = "LookAt 0 0 -3  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

// The message of the InputError importing `file` raises, or "no error".
std::string import_error(const std::filesystem::path& file, const PbrtImportOptions& options = {}) {
  try {
    import_pbrt(file, test::library(), options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST_CASE("pbrt include graph: 41 files each including the next twice (2^40 reads) stop at the included-file limit") {
  test::ScratchFolder folder("pbrt_include_bomb");
  folder.write("main.pbrt", kScene + "Include \"f1.pbrt\"\nInclude \"f1.pbrt\"\n");
  for (int i = 1; i <= 40; ++i) {
    const std::string next = "f" + std::to_string(i + 1) + ".pbrt";
    folder.write("f" + std::to_string(i) + ".pbrt",
                 i < 40 ? "# level " + std::to_string(i) + "\nInclude \"" + next + "\"\nInclude \"" + next + "\"\n"
                        : "Shape \"sphere\"\n");
  }
  const auto start = std::chrono::steady_clock::now();
  const std::string error = import_error(folder / "main.pbrt");
  CHECK(seconds_since(start) < 30.0);  // about 0.2 s in a release build: 65,536 small files
  CHECK(error.rfind(folder.path.string() + "/f", 0) == 0);  // the file and line of the Include that crossed it
  CHECK_CONTAINS(error, ".pbrt:", ": Include: the scene reads more than 65,536 included files", "docs/pbrt-import.md");
}

TEST_CASE("pbrt include graph: statements are counted over the Include graph, instances over the scene") {
  test::ScratchFolder folder("pbrt_statement_limit");
  // 10 Includes of a file of 10 lines: 100 statements read, beyond a limit of 50.
  std::string ten;
  for (int i = 0; i < 10; ++i) ten += "Translate 0 0 0\n";
  folder.write("ten.pbrt", ten);
  std::string main = kScene;
  for (int i = 0; i < 10; ++i) main += "Include \"ten.pbrt\"\n";
  folder.write("main.pbrt", main);
  PbrtImportOptions options;
  options.parse_limits.max_statements = 50;
  CHECK_CONTAINS(import_error(folder / "main.pbrt", options), "ten.pbrt:", ": Translate: the scene expands to more than 50 statements");
  options.parse_limits.max_statements = 200;
  CHECK(import_error(folder / "main.pbrt", options) == "no error");

  // Eight tiny files would expand to 10^6 ObjectInstances; the instance bound stops them at the line that crosses it.
  test::ScratchFolder bomb("pbrt_instance_bomb");
  bomb.write("main.pbrt", kScene + "ObjectBegin \"o\"\nShape \"sphere\"\nObjectEnd\n" +
                              [] { std::string s; for (int i = 0; i < 10; ++i) s += "Include \"i1.pbrt\"\n"; return s; }());
  for (int level = 1; level <= 5; ++level) {
    std::string text;
    for (int i = 0; i < 10; ++i)
      text += level < 5 ? "Include \"i" + std::to_string(level + 1) + ".pbrt\"\n" : "ObjectInstance \"o\"\n";
    bomb.write("i" + std::to_string(level) + ".pbrt", text);
  }
  PbrtImportOptions instances;
  instances.max_instances = 1000;
  CHECK(import_error(bomb / "main.pbrt", instances) ==
        (bomb / "i5.pbrt").string() + ":1: ObjectInstance: the scene places more than 1000 instances, beyond the "
        "importer's limit (PbrtImportOptions::max_instances; docs/pbrt-import.md, \"Limits\")");
  // (The default bound, 2^20, lets these 10^6 through: a forest of a million trees is a real scene.)

  // A file of shapes included over and over: its Shape statements are counted at every read.
  test::ScratchFolder shapes("pbrt_shape_limit");
  shapes.write("main.pbrt", kScene + "Include \"s.pbrt\"\nInclude \"s.pbrt\"\nInclude \"s.pbrt\"\n");
  shapes.write("s.pbrt", "Shape \"sphere\"\nShape \"sphere\"\n");
  PbrtImportOptions few_shapes;
  few_shapes.max_shapes = 5;
  CHECK(import_error(shapes / "main.pbrt", few_shapes) ==
        (shapes / "s.pbrt").string() + ":2: Shape: the scene has more than 5 Shape statements (counting each read of "
        "an included file), beyond the importer's limit (PbrtImportOptions::max_shapes; docs/pbrt-import.md, \"Limits\")");
  few_shapes.max_shapes = 6;
  CHECK(import_error(shapes / "main.pbrt", few_shapes) == "no error");
}

TEST_CASE("pbrt include graph: instances are placements of their prototype, a matrix each, never copies") {
  test::ScratchFolder folder("pbrt_instance_reference");
  std::string text = kScene + "ObjectBegin \"ball\"\nShape \"sphere\"\nObjectEnd\n";  // lines 4-6
  for (int i = 0; i < 100; ++i) text += "AttributeBegin\nTranslate " + std::to_string(i) + " 0 0\nObjectInstance \"ball\"\nAttributeEnd\n";
  folder.write("main.pbrt", text);
  const PbrtImport imported = import_pbrt(folder / "main.pbrt", test::library());
  REQUIRE(imported.document["prototypes"]["ball"].size() == 1);  // the sphere's mesh, once
  // Consecutive instances of one object are one shape with one origin: a line per instance, not 200 bytes.
  REQUIRE(imported.document["shapes"].size() == 1);
  const auto& batch = imported.document["shapes"][0];
  CHECK(batch["type"] == "instances");
  CHECK(batch["prototype"] == "ball");
  REQUIRE(batch["matrices"].size() == 100);
  CHECK(batch.dump().size() < 100 * 120);  // twelve numbers an instance: bytes, not the 9,024-triangle sphere
  for (int i = 0; i < 100; ++i) {
    // The camera looks along +z with up +y, where pbrt's image-right is Rimu's left: the importer mirrors x.
    const auto& m = batch["matrices"][size_t(i)];
    REQUIRE(m.size() == 12);
    CHECK(m[3].get<double>() == doctest::Approx(-i));
    CHECK(m[0].get<double>() == -1.0);
  }
  REQUIRE(imported.origins.size() == 2);  // the object's sphere, and the instances
  const PbrtOrigin& batch_origin = imported.origins[1];
  CHECK(batch_origin.pointer == "/shapes/0");
  CHECK(batch_origin.statement == "ObjectInstance \"ball\"");
  REQUIRE(batch_origin.element_lines.size() == 100);
  CHECK(batch_origin.element_lines[0] == 9);
  CHECK(batch_origin.element_lines[99] == 9 + 99 * 4);
  // Another object, another file or a shape in between starts a new batch; the JSON loads.
  folder.write("more.pbrt", "ObjectInstance \"ball\"\n");
  folder.write("mixed.pbrt", kScene + "ObjectBegin \"ball\"\nShape \"sphere\"\nObjectEnd\nObjectBegin \"box\"\n"
                             "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\nObjectEnd\n"
                             "ObjectInstance \"ball\"\nObjectInstance \"box\"\nObjectInstance \"box\"\nInclude \"more.pbrt\"\n"
                             "ObjectInstance \"ball\"\nShape \"sphere\"\nObjectInstance \"ball\"\n");
  const PbrtImport mixed = import_pbrt(folder / "mixed.pbrt", test::library());
  const auto& shapes = mixed.document["shapes"];
  REQUIRE(shapes.size() == 6);
  const std::vector<std::pair<std::string, size_t>> expected = {{"ball", 1}, {"box", 2}, {"ball", 1}, {"ball", 1}, {"", 0}, {"ball", 1}};
  for (size_t k = 0; k < shapes.size(); ++k) {
    if (expected[k].second == 0) continue;  // the sphere
    CHECK(shapes[k]["prototype"] == expected[k].first);
    CHECK(shapes[k]["matrices"].size() == expected[k].second);
  }
  CHECK_NOTHROW(load_scene(mixed.document, (folder / "mixed.pbrt").string(), folder.path, test::library()));
}

TEST_CASE("pbrt include graph: an instance the loader refuses is reported at its own ObjectInstance line") {
  // The second of three instances in one batch places the ball beyond Embree's coordinate range.
  const std::string text = kScene + "ObjectBegin \"ball\"\nShape \"sphere\"\nObjectEnd\n"
                           "ObjectInstance \"ball\"\nTranslate 1e19 0 0\nObjectInstance \"ball\"\nIdentity\nObjectInstance \"ball\"\n";
  const PbrtImport imported = import_pbrt_text(text, "far.pbrt", test::test_data("pbrt"), test::library());
  REQUIRE(imported.document["shapes"].size() == 1);
  std::string moved = "no error";
  try {
    load_scene(imported.document, "far.pbrt", test::test_data("pbrt"), test::library());
  } catch (const InputError& e) {
    const std::optional<InputError> at_pbrt = at_pbrt_origin(e, imported.origins);
    REQUIRE(at_pbrt);
    moved = at_pbrt->what();
  }
  CHECK_CONTAINS(moved, "far.pbrt:9: ObjectInstance \"ball\": ", "coordinates must lie within",
                 "(the converted scene's /shapes/0/matrices/1)");
}

TEST_CASE("pbrt include graph: an ObjectBegin without ObjectEnd is an error at the ObjectBegin") {
  test::ScratchFolder folder("pbrt_unclosed_object");
  folder.write("main.pbrt", kScene + "Include \"objects.pbrt\"\nShape \"sphere\"\n");
  folder.write("objects.pbrt", "# objects\nObjectBegin \"tree\"\nShape \"sphere\"\n");
  CHECK(import_error(folder / "main.pbrt") ==
        (folder / "objects.pbrt").string() + ":2: ObjectBegin \"tree\" has no ObjectEnd: the scene's files end inside "
        "the object's definition");
}

TEST_CASE("pbrt include graph: a quoted string that is not UTF-8 is an error at its line") {
  CHECK(test::pbrt_import_error(kScene + "MakeNamedMaterial \"caf\xe9\" \"string type\" \"diffuse\"\n", "latin1.pbrt") ==
        "latin1.pbrt:4: the quoted string \"caf\\xE9\" is not UTF-8 (bytes above 127 shown as \\xHH; a Latin-1 file?); "
        "pbrt strings are UTF-8: convert the file, e.g. iconv -f latin1 -t utf-8");
  // UTF-8 names, and Latin-1 in comments, are fine.
  CHECK(test::pbrt_import_error(kScene + "# caf\xe9\nMakeNamedMaterial \"caf\xc3\xa9\" \"string type\" \"diffuse\"\n") ==
        "no error");
}

TEST_CASE("pbrt include graph: the top-level file is read like any input: a folder, a FIFO, a device are refused") {
  test::ScratchFolder folder("pbrt_top_level");
  std::filesystem::create_directory(folder / "folder.pbrt");
  CHECK(import_error(folder / "folder.pbrt") == (folder / "folder.pbrt").string() + ": is a directory; expected a file");
  REQUIRE(::mkfifo((folder / "fifo.pbrt").c_str(), 0600) == 0);
  CHECK_CONTAINS(import_error(folder / "fifo.pbrt"), "fifo.pbrt: is a FIFO (named pipe); Rimu reads its inputs only from regular files");
  std::filesystem::create_symlink("/dev/zero", folder / "zero.pbrt");
  CHECK_CONTAINS(import_error(folder / "zero.pbrt"), "zero.pbrt: is a character device");
}

TEST_CASE("pbrt include graph: the files an import reads are what an InputFileLog records, resolved as read") {
  test::ScratchFolder folder("pbrt_read_log");
  std::filesystem::create_directories(folder / "sub" / "meshes");
  folder.write("main.pbrt", kScene + "Include \"sub/part.pbrt\"\nInclude 'sub/more.inc'\n");
  folder.write("sub/part.pbrt", "Shape \"plymesh\" \"string filename\" \"meshes/tri.ply\"\n");
  folder.write("sub/more.inc", "Shape 'sphere'\n");
  folder.write("sub/meshes/tri.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                     "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const InputFileLog log;
  const PbrtImport imported = import_pbrt(folder / "main.pbrt", test::library());
  (void)load_scene(imported.document, (folder / "main.pbrt").string(), folder.path, test::library());
  const auto& files = log.files();
  for (const char* name : {"main.pbrt", "sub/part.pbrt", "sub/more.inc", "sub/meshes/tri.ply"}) {
    const auto found = files.find((folder / name).lexically_normal());
    REQUIRE_MESSAGE(found != files.end(), name);
    CHECK(found->second.has_value());  // read by read_input_file: the digest of the bytes read
  }
}
