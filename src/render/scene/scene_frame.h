// Frames of a sequence: the scene file's text with "${frame}" replaced by the frame number (docs/scene-format.md).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace rimu {

/// The text of the scene file at `path` with every "${frame}" replaced by `frame` and every "${frame:N}" by `frame`
/// zero-padded to N digits (N = 1-9). InputError naming the file if it cannot be read, if it uses ${frame} and no
/// frame was given, or if a "${frame" is malformed. Without any "${frame" the text is returned unchanged.
std::string scene_text_for_frame(const std::filesystem::path& path, std::optional<int> frame);

/// The same substitution on a string (e.g. an output path given as "out.${frame:4}.exr").
std::string substitute_frame(const std::string& text, std::optional<int> frame, const std::string& where);

}  // namespace rimu
