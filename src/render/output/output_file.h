// The output-file code lives in src/spectral/io/output_file.h, so that rimu_spectral's plots and tables and every
// tool (rimu-colour links only rimu_spectral) write through the same code as the renderer.
#pragma once

#include "spectral/io/output_file.h"
