// Where Rimu's data tables (data/cmf, data/spectra, ...) live at run time.
#pragma once

#include <filesystem>

namespace rimu {

/// The root of the data folder. Found, in order: the RIMU_DATA environment variable; `<exe>/../share/rimu/data`
/// (the install layout, which the build tree mirrors with a symbolic link); `<exe>/data`.
/// Throws InputError listing every place it looked if none holds `cmf/`.
std::filesystem::path find_data_directory();

/// Path of a data file relative to the data root, e.g. "cmf/cie1931_2deg_xyz_1nm.csv".
std::filesystem::path data_file(const std::filesystem::path& relative);

}  // namespace rimu
