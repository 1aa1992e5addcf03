// OpenImageIO, loaded on first use: image textures and environment maps are read, and display images (PNG, JPEG,
// TIFF) written, through a module (librimu_oiio.so) that only those paths load, so a render without them starts
// without OpenImageIO's ~250 libraries (image_module/image_module_api.h says why that matters).
#pragma once

#include "render/image/image_module/image_module_api.h"

namespace rimu {

/// The OpenImageIO module's functions; loads it on the first call (thread-safe; later calls cost an atomic load).
/// The module is found at, in order: the RIMU_IMAGE_MODULE environment variable (a wrong one is an error);
/// `<exe>/../lib/rimu/librimu_oiio.so` (the build tree and an installed tree); the install prefix's and then the
/// build tree's path recorded at compile time (for the Python module, whose executable is python3). Throws RenderError (exit 2: the
/// installation, not the user's input) naming the places tried and dlopen's message if none loads.
const ImageModuleApi& image_library();

/// True once image_library() has loaded the module in this process (tests check that reading a PNG does not).
bool image_library_loaded();

}  // namespace rimu
