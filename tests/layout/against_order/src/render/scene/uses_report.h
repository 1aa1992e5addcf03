// A scene file including a report: reports/ is above scene/ in the room order, so the check must refuse this.
#pragma once

#include "render/reports/report.h"
