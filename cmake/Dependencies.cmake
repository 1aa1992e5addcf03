# Every dependency is a Debian package; scripts/install-deps.sh installs them.
# A missing one stops configuration with the name of the package to install.

function(rimu_require found debian_package what)
  if(NOT ${found})
    message(FATAL_ERROR "Rimu needs ${what}: install the Debian package '${debian_package}' "
                        "(or run scripts/install-deps.sh).")
  endif()
endfunction()

find_package(PkgConfig QUIET)
rimu_require(PKG_CONFIG_FOUND pkg-config "pkg-config")

find_package(Threads REQUIRED)

find_package(embree 3 QUIET CONFIG)
rimu_require(embree_FOUND libembree-dev "Embree 3 (ray tracing kernels)")

find_package(OpenEXR 3 QUIET CONFIG)
rimu_require(OpenEXR_FOUND libopenexr-dev "OpenEXR 3 (EXR output)")

find_package(TBB QUIET CONFIG)
rimu_require(TBB_FOUND libtbb-dev "oneTBB (parallelism)")


find_package(nlohmann_json 3 QUIET CONFIG)
rimu_require(nlohmann_json_FOUND nlohmann-json3-dev "nlohmann-json (scene files, JSON output)")

find_package(CLI11 QUIET CONFIG)
rimu_require(CLI11_FOUND libcli11-dev "CLI11 (command-line parsing)")

find_package(tinyobjloader QUIET CONFIG)
rimu_require(tinyobjloader_FOUND libtinyobjloader-dev "tinyobjloader (OBJ meshes)")

# Debian 12's CMake package files of OpenColorIO and OpenImageIO point at wrong include folders,
# so these two are found through pkg-config.
pkg_check_modules(OCIO QUIET IMPORTED_TARGET OpenColorIO)
rimu_require(OCIO_FOUND libopencolorio-dev "OpenColorIO 2 (display transforms)")
pkg_check_modules(OIIO QUIET IMPORTED_TARGET OpenImageIO)
rimu_require(OIIO_FOUND libopenimageio-dev "OpenImageIO 2 (image IO)")
# stb_image decodes PNG, JPEG, TGA and BMP in-process (render/image/stb_image_decoder.h); Debian ships it as
# a shared libstb with a pkg-config file.
pkg_check_modules(STB QUIET IMPORTED_TARGET stb)
rimu_require(STB_FOUND libstb-dev "stb_image (PNG, JPEG, TGA and BMP textures)")
# NanoVDB (sparse volumes, transport/media/nanovdb_grid.h) is header-only and Debian ships no CMake or pkg-config
# file for it, so its header is found directly. Its reader inflates ZIP (zlib) and BLOSC files only when told to
# (transport/media/nanovdb_io.h defines the switches; the codecs' libraries are linked here).
find_path(NANOVDB_INCLUDE_DIR nanovdb/NanoVDB.h)
rimu_require(NANOVDB_INCLUDE_DIR libnanovdb-dev "NanoVDB (sparse volume files, .nvdb)")
find_package(ZLIB QUIET)
rimu_require(ZLIB_FOUND zlib1g-dev "zlib (ZIP-compressed .nvdb files)")
pkg_check_modules(BLOSC QUIET IMPORTED_TARGET blosc)
rimu_require(BLOSC_FOUND libblosc-dev "Blosc (BLOSC-compressed .nvdb files)")
add_library(rimu_nanovdb INTERFACE)
target_include_directories(rimu_nanovdb SYSTEM INTERFACE ${NANOVDB_INCLUDE_DIR})
target_link_libraries(rimu_nanovdb INTERFACE ZLIB::ZLIB PkgConfig::BLOSC)

if(RIMU_BUILD_TESTS)
  find_package(doctest QUIET CONFIG)
  rimu_require(doctest_FOUND doctest-dev "doctest (unit tests)")
endif()

if(RIMU_BUILD_BENCHMARKS)
  find_package(benchmark QUIET CONFIG)
  rimu_require(benchmark_FOUND libbenchmark-dev "Google Benchmark (benchmarks)")
endif()
