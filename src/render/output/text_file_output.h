// Text outputs of the tools (a light definition, a converted scene): write_text_file() lives in
// src/spectral/io/output_file.h with the rest of the output-file code, so rimu_spectral's tools share it.
#pragma once

#include "spectral/io/output_file.h"
