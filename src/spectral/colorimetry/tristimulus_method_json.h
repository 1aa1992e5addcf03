// How a report's JSON says which tristimulus method it used: shared by the spectrum and reflectance reports.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "spectral/colorimetry/astm_e308.h"

namespace rimu {

/// Adds "tristimulus_method": `method` to `j`, then "e308_table" (the table's number) and "e308_weights" (what it
/// is) if an ASTM E308 table was used.
inline void add_tristimulus_method_json(nlohmann::ordered_json& j, const std::string& method,
                                        const std::optional<E308Table>& e308_table) {
  j["tristimulus_method"] = method;
  if (e308_table) {
    j["e308_table"] = e308_table_number(*e308_table);
    j["e308_weights"] = e308_table_description(*e308_table);
  }
}

}  // namespace rimu
