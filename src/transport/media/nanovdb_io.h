// NanoVDB's file reader and writer with its ZIP and BLOSC codecs switched on. IO.h's inline functions differ with
// and without NANOVDB_USE_ZIP / NANOVDB_USE_BLOSC, so every Rimu file (and test) that includes IO.h does so here:
// all then agree (one definition), and no compile flag reaches the files that never read a volume.
#pragma once

#define NANOVDB_USE_ZIP 1
#define NANOVDB_USE_BLOSC 1
#include <nanovdb/util/IO.h>
