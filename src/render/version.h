// The version string Rimu writes into its outputs (defined with the git commit in spectral/version.h).
#pragma once

#include "spectral/version.h"
