// Messages built from names ("a point light", "an environment light") need the article that fits the name.
#pragma once

#include <cctype>
#include <string>
#include <string_view>

namespace rimu {

/// `noun` after its indefinite article: "an environment", "an AttributeBegin", "a point". The article follows the
/// first letter (a vowel takes "an"), which is right for the words Rimu's messages use (not for "unit" or "hour").
inline std::string with_article(std::string_view noun) {
  const char first = noun.empty() ? ' ' : char(std::tolower(static_cast<unsigned char>(noun.front())));
  return (std::string_view("aeiou").find(first) != std::string_view::npos ? "an " : "a ") + std::string(noun);
}

}  // namespace rimu
