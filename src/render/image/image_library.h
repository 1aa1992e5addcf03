// OpenImageIO, loaded on first use: image textures and environment maps are read, and JPEG and TIFF display images
// written (PNGs are written in-process: render/output/png_file.h), through a module (librimu_oiio.so) that only
// those paths load, so a render without them starts without OpenImageIO's ~250 libraries
// (image_module/image_module_api.h says why that matters). PFM files, the usual format of pbrt scenes' environment
// maps, and Radiance HDR files go to a second module (librimu_freeimage.so, FreeImage: ~4 MiB loaded instead of
// ~120), found the same way.
#pragma once

#include <filesystem>

#include "render/image/image_module/image_module_api.h"

namespace rimu {

/// The OpenImageIO module's functions; loads it on the first call (thread-safe; later calls cost an atomic load).
/// The module (librimu_oiio.so) is found as loadable_module.h says, RIMU_IMAGE_MODULE naming it. Throws RenderError
/// (exit 2: the installation, not the user's input) naming the places tried and dlopen's message if none loads.
const ImageModuleApi& image_library();

/// True once image_library() has loaded the module in this process (tests check that reading a PNG does not).
bool image_library_loaded();

/// The module that reads `path`: the FreeImage module for a PFM (the file starts with "PF" or "Pf" and a white
/// space) or a Radiance HDR in the standard orientation (image_module/radiance_header.h), found as image_library()
/// finds its own (RIMU_FREEIMAGE_MODULE instead of RIMU_IMAGE_MODULE), else image_library(). Throws as
/// image_library() does.
const ImageModuleApi& image_reader_for(const std::filesystem::path& path);

/// The FreeImage module's functions (PFM and HDR only); loads it on the first call, as image_library() does its own.
const ImageModuleApi& freeimage_library();

/// True once freeimage_library() has loaded the FreeImage module in this process.
bool freeimage_library_loaded();

}  // namespace rimu
