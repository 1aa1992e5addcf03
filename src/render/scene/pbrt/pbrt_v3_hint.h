#pragma once
// pbrt-v3 files: most published pbrt scenes are pbrt-v3, which pbrt-v4 reads only after its own upgrader has
// rewritten them. Rimu reads pbrt-v4; where a file uses a construct that only pbrt-v3 has, the error says so and
// names the command that converts the file, instead of a bare "unknown type".
#include <optional>
#include <string>

namespace rimu {

/// The sentence appended to an error about a pbrt-v3-only construct.
inline std::string pbrt_v3_hint() {
  return "this looks like a pbrt-v3 file, which Rimu does not read: pbrt-v4 converts it with "
         "`pbrt --upgrade old.pbrt > new.pbrt`, which leaves the files it Includes as they are: upgrade each of them "
         "too (docs/pbrt-import.md, \"pbrt-v3 files\")";
}

/// For a material type that only pbrt-v3 has, the pbrt-v4 material its upgrader turns it into; nullopt for every
/// other name. Not "fourier": the upgrader keeps that name (it warns that pbrt-v4 no longer reads it), so an upgraded
/// file still holds it, and the importer lists it with a stand-in as it does pbrt-v4's "measured".
inline std::optional<std::string> pbrt_v4_name_of_v3_material(const std::string& type) {
  if (type == "matte") return "diffuse";
  if (type == "plastic" || type == "uber" || type == "substrate") return "coateddiffuse";
  if (type == "translucent") return "diffusetransmission";
  if (type == "mirror" || type == "metal") return "conductor";
  if (type == "glass") return "dielectric";
  if (type == "kdsubsurface") return "subsurface";
  if (type == "disney") return "diffuse";
  return std::nullopt;
}

}  // namespace rimu
