// rimu_spectral including rimu_transport: a library may not include the ones to its right.
#pragma once

#include "transport/undeclared_room/guide.h"
