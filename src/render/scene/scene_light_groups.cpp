#include "render/scene/scene_light_groups.h"

#include <algorithm>
#include <array>
#include <cctype>

namespace rimu::scene_loading {
namespace {

// Set on a light without the key until finish_light_groups() knows whether the scene has groups at all.
constexpr int kUnmarked = -1;
constexpr size_t kMaxNameLength = 64;

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

std::string light_group_name_problem(const std::string& name) {
  if (name.empty()) return "a light group's name cannot be empty";
  if (name.size() > kMaxNameLength) return "a light group's name has at most 64 characters";
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
      return "a light group's name may hold only letters, digits, '_' and '-' (it names EXR layers '" + name +
             ".X' etc.); '" + name + "' does not";
  // Rimu's own channel names and layer prefixes (render/output/exr_output.h), and the feature buffers' names.
  static constexpr std::array kReserved{"x",      "y", "z",     "r",        "g",     "b",      "a",
                                        "s0",     "rimu", "spp", "relativeerror", "albedo", "n", "depth",
                                        "variance", "half_even", "half_odd", "noisy", "beauty"};
  const std::string l = lower(name);
  for (const char* r : kReserved)
    if (l == r)
      return "'" + name + "' is a name Rimu uses for its own EXR channels or layers; choose another light group name";
  return {};
}

namespace {

// The group index of `object`'s "light_group" (added to the scene's groups if new), or kUnmarked without the key.
int group_of(const JsonCursor& object, Scene& scene) {
  const auto key = object.find("light_group");
  if (!key) return kUnmarked;
  const std::string name = key->string();
  if (const std::string problem = light_group_name_problem(name); !problem.empty()) key->fail(problem);
  auto& groups = scene.light_groups;
  const auto it = std::find(groups.begin(), groups.end(), name);
  // No cap on the number of groups: each costs memory and time in proportion (docs/rendering.md, "Cost").
  if (it == groups.end()) groups.push_back(name);
  return int(std::find(groups.begin(), groups.end(), name) - groups.begin());
}

}  // namespace

void read_light_group(const JsonCursor& light, Scene& scene) { scene.lights.back()->set_light_group(group_of(light, scene)); }

int read_medium_light_group(const JsonCursor& medium, Scene& scene) { return group_of(medium, scene); }

void finish_light_groups(Scene& scene) {
  auto& groups = scene.light_groups;
  if (groups.empty()) {
    for (auto& light : scene.lights) light->set_light_group(0);
    for (Medium& medium : scene.media)
      if (medium.emission()) medium.set_emission_light_group(0);
    return;
  }
  int fallback = -1;
  const auto fallback_group = [&] {
    if (fallback < 0) {
      auto it = std::find(groups.begin(), groups.end(), std::string(kDefaultLightGroup));
      if (it == groups.end()) {
        groups.push_back(kDefaultLightGroup);
        it = groups.end() - 1;
      }
      fallback = int(it - groups.begin());
    }
    return fallback;
  };
  for (auto& light : scene.lights)
    if (light->light_group() == kUnmarked) light->set_light_group(fallback_group());
  for (Medium& medium : scene.media)
    if (medium.emission() && medium.emission_light_group() == kUnmarked) medium.set_emission_light_group(fallback_group());
}

}  // namespace rimu::scene_loading
