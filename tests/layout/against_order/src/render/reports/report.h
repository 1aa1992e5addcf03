// A report (reports/ may include scene/, not the other way round).
#pragma once
