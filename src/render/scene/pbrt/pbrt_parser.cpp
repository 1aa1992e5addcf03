#include "render/scene/pbrt/pbrt_parser.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>

#include "render/scene/pbrt/pbrt_tokenizer.h"
#include "render/scene/pbrt/pbrt_v3_hint.h"
#include "spectral/io/input_file.h"

namespace rimu {

namespace {

// What follows each keyword before its parameter list.
enum class Arguments { none, numbers, strings, bare_word, option };

struct Signature {
  Arguments arguments = Arguments::none;
  int count = 0;        ///< numbers or strings expected (for strings: the minimum)
  int max_count = 0;    ///< strings: the maximum
  bool has_params = false;
};

const std::map<std::string, Signature>& signatures() {
  static const std::map<std::string, Signature> table = {
      {"AttributeBegin", {}}, {"AttributeEnd", {}}, {"TransformBegin", {}}, {"TransformEnd", {}},
      {"ReverseOrientation", {}}, {"WorldBegin", {}}, {"WorldEnd", {}}, {"ObjectEnd", {}}, {"Identity", {}},
      {"Translate", {Arguments::numbers, 3}}, {"Scale", {Arguments::numbers, 3}}, {"Rotate", {Arguments::numbers, 4}},
      {"LookAt", {Arguments::numbers, 9}}, {"Transform", {Arguments::numbers, 16}},
      {"ConcatTransform", {Arguments::numbers, 16}}, {"TransformTimes", {Arguments::numbers, 2}},
      {"CoordinateSystem", {Arguments::strings, 1, 1}}, {"CoordSysTransform", {Arguments::strings, 1, 1}},
      {"NamedMaterial", {Arguments::strings, 1, 1}}, {"ObjectBegin", {Arguments::strings, 1, 1}},
      {"ObjectInstance", {Arguments::strings, 1, 1}}, {"ColorSpace", {Arguments::strings, 1, 1}},
      {"Include", {Arguments::strings, 1, 1}}, {"Import", {Arguments::strings, 1, 1}},
      {"MediumInterface", {Arguments::strings, 1, 2}}, {"ActiveTransform", {Arguments::bare_word, 1}},
      {"Camera", {Arguments::strings, 1, 1, true}}, {"Sampler", {Arguments::strings, 1, 1, true}},
      {"Film", {Arguments::strings, 1, 1, true}}, {"PixelFilter", {Arguments::strings, 1, 1, true}},
      {"Integrator", {Arguments::strings, 1, 1, true}}, {"Accelerator", {Arguments::strings, 1, 1, true}},
      {"Shape", {Arguments::strings, 1, 1, true}}, {"Material", {Arguments::strings, 1, 1, true}},
      {"LightSource", {Arguments::strings, 1, 1, true}}, {"AreaLightSource", {Arguments::strings, 1, 1, true}},
      {"MakeNamedMaterial", {Arguments::strings, 1, 1, true}}, {"MakeNamedMedium", {Arguments::strings, 1, 1, true}},
      {"Attribute", {Arguments::strings, 1, 1, true}}, {"Texture", {Arguments::strings, 3, 3, true}},
      {"Option", {Arguments::option, 0, 0, true}},
  };
  return table;
}

const std::map<std::string, PbrtParamType>& param_types() {
  static const std::map<std::string, PbrtParamType> table = {
      {"integer", PbrtParamType::integer}, {"float", PbrtParamType::real},
      {"point2", PbrtParamType::point2},   {"vector2", PbrtParamType::vector2},
      {"point3", PbrtParamType::point3},   {"point", PbrtParamType::point3},
      {"vector3", PbrtParamType::vector3}, {"vector", PbrtParamType::vector3},
      {"normal", PbrtParamType::normal},   {"normal3", PbrtParamType::normal},
      {"bool", PbrtParamType::boolean},    {"string", PbrtParamType::string},
      {"rgb", PbrtParamType::rgb},         {"spectrum", PbrtParamType::spectrum},
      {"blackbody", PbrtParamType::blackbody}, {"texture", PbrtParamType::texture},
  };
  return table;
}

std::string known_keywords() {
  std::string list;
  for (const auto& [name, signature] : signatures()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

// A finite number, or an InputError naming what was found.
double parse_number(const PbrtToken& token, const std::string& file, const std::string& what) {
  if (!token.quoted && !token.text.empty()) {
    const char* begin = token.text.c_str();
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(begin, &end);
    if (end == begin + token.text.size() && errno != ERANGE) {
      if (!std::isfinite(value))
        throw InputError({file, token.line, ""}, what + ": expected a finite number, found '" + token.text + "'");
      return value;
    }
  }
  throw InputError({file, token.line, ""},
                   what + ": expected a number, found " + (token.quoted ? "\"" + token.text + "\"" : "'" + token.text + "'"));
}

// What the whole Include graph has used of PbrtParseLimits so far.
struct ParseBudget {
  PbrtParseLimits limits;
  std::size_t statements = 0;
  std::size_t included_files = 0;
};

// "16,777,216"
std::string with_commas(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

class Parser {
 public:
  Parser(const std::function<void(const PbrtStatement&)>& handle, int depth, ParseBudget& budget)
      : handle_(handle), depth_(depth), budget_(budget) {}

  void parse(const std::string& text, const std::string& file, const std::filesystem::path& directory) {
    file_ = file;
    directory_ = directory;
    PbrtTokenizer tokenizer(text, file_);
    tokenizer_ = &tokenizer;
    next_ = tokenizer.next();
    while (next_) statement();
    tokenizer_ = nullptr;
  }

 private:
  const PbrtToken* peek() const { return next_ ? &*next_ : nullptr; }
  /// The line of the token taken last: at the end of the file, the file's last token.
  int last_line() const { return last_line_; }

  PbrtToken take(const std::string& what) {
    if (!next_) throw InputError({file_, last_line(), ""}, "the file ends where " + what + " was expected");
    PbrtToken token = std::move(*next_);
    last_line_ = token.line;
    next_ = tokenizer_->next();
    return token;
  }

  void statement() {
    const PbrtToken& keyword = take("a statement");
    const auto found = signatures().find(keyword.text);
    if (keyword.quoted || found == signatures().end())
      throw InputError({file_, keyword.line, ""},
                       "unknown statement " + (keyword.quoted ? "\"" + keyword.text + "\"" : "'" + keyword.text + "'") +
                           "; expected one of: " + known_keywords());
    const Signature& signature = found->second;
    PbrtStatement s;
    s.keyword = keyword.text;
    s.where = {file_, keyword.line, ""};
    s.directory = directory_;
    switch (signature.arguments) {
      case Arguments::none:
      case Arguments::option: break;
      case Arguments::numbers: numbers(s, signature.count); break;
      case Arguments::bare_word: {
        const PbrtToken& word = take("a word after " + s.keyword);
        if (word.quoted || (word.text != "StartTime" && word.text != "EndTime" && word.text != "All"))
          throw InputError({file_, word.line, ""}, s.keyword + ": expected StartTime, EndTime or All, found '" + word.text + "'");
        s.strings.push_back(word.text);
        break;
      }
      case Arguments::strings:
        for (int i = 0; i < signature.max_count; ++i) {
          const PbrtToken* t = peek();
          if (i >= signature.count && (!t || !t->quoted)) break;
          if (!t || !t->quoted)
            throw InputError({file_, t ? t->line : last_line(), ""},
                             s.keyword + ": expected a quoted string" + (t ? ", found '" + t->text + "'" : ""));
          s.strings.push_back(take("a quoted string").text);
        }
        break;
    }
    if (signature.has_params) {
      while (peek() && peek()->quoted) s.params.push_back(param(s.keyword));
      if (signature.arguments == Arguments::option && s.params.size() != 1)
        throw InputError(s.where, "Option: expected exactly one \"type name\" value");
    }
    if (s.keyword == "Include" || s.keyword == "Import") {
      include(s);
      return;
    }
    if (++budget_.statements > budget_.limits.max_statements)
      throw InputError(s.where, s.keyword + ": the scene expands to more than " +
                                    with_commas(budget_.limits.max_statements) +
                                    " statements (counting each time an included file is read; "
                                    "docs/pbrt-import.md, \"Limits\")");
    handle_(s);
  }

  // Transform and ConcatTransform may bracket their numbers; the others list them bare.
  void numbers(PbrtStatement& s, int count) {
    const bool bracketed = peek() && !peek()->quoted && peek()->text == "[";
    if (bracketed) take("'['");
    for (int i = 0; i < count; ++i) {
      const PbrtToken& t = take(std::to_string(count) + " numbers after " + s.keyword);
      if (bracketed && !t.quoted && t.text == "]")
        throw InputError({file_, t.line, ""}, s.keyword + ": expected " + std::to_string(count) + " numbers, found " +
                                                  std::to_string(i));
      s.numbers.push_back(parse_number(t, file_, s.keyword));
    }
    if (bracketed) {
      const PbrtToken& close = take("']'");
      if (close.quoted || close.text != "]")
        throw InputError({file_, close.line, ""}, s.keyword + ": expected ']' after " + std::to_string(count) + " numbers");
    }
  }

  PbrtParam param(const std::string& keyword) {
    const PbrtToken& declaration = take("a parameter");
    PbrtParam p;
    p.where = {file_, declaration.line, ""};
    std::istringstream words(declaration.text);
    std::string extra;
    if (!(words >> p.type_name >> p.name) || (words >> extra))
      throw InputError(p.where, keyword + ": expected a parameter declaration \"type name\", found \"" + declaration.text + "\"");
    const auto type = param_types().find(p.type_name);
    if (type == param_types().end() && p.type_name == "color")
      throw InputError(p.where, keyword + ": parameter type 'color' of \"" + declaration.text +
                                    "\" is pbrt-v3's (pbrt-v4 says 'rgb'); " + pbrt_v3_hint());
    if (type == param_types().end())
      throw InputError(p.where, keyword + ": unknown parameter type '" + p.type_name + "' of \"" + declaration.text +
                                    "\"; expected integer, float, point2, vector2, point3, vector3, normal, bool, "
                                    "string, rgb, spectrum, blackbody or texture");
    p.type = type->second;
    const std::string what = keyword + " \"" + declaration.text + "\"";

    std::vector<PbrtToken> values;
    const PbrtToken& first = take("a value for " + what);
    if (!first.quoted && first.text == "[") {
      while (true) {
        const PbrtToken& t = take("']' closing the values of " + what);
        if (!t.quoted && t.text == "]") break;
        if (!t.quoted && t.text == "[") throw InputError({file_, t.line, ""}, what + ": '[' inside a value list");
        values.push_back(t);
      }
    } else {
      if (!first.quoted && first.text == "]") throw InputError({file_, first.line, ""}, what + ": unexpected ']'");
      values.push_back(first);
    }
    if (values.empty()) throw InputError(p.where, what + ": no values");
    check_values(p, values, what);
    return p;
  }

  void check_values(PbrtParam& p, const std::vector<PbrtToken>& values, const std::string& what) {
    const auto all_strings = [&] {
      for (const PbrtToken& t : values) {
        if (!t.quoted) throw InputError({file_, t.line, ""}, what + ": expected a quoted string, found '" + t.text + "'");
        p.strings.push_back(t.text);
      }
    };
    const auto all_numbers = [&] {
      for (const PbrtToken& t : values) p.numbers.push_back(parse_number(t, file_, what));
    };
    const auto multiple_of = [&](size_t k, const char* unit) {
      if (p.numbers.size() % k != 0)
        throw InputError(p.where, what + ": expected a multiple of " + std::to_string(k) + " numbers (" + unit +
                                      "), found " + std::to_string(p.numbers.size()));
    };
    switch (p.type) {
      case PbrtParamType::integer:
        all_numbers();
        for (size_t i = 0; i < p.numbers.size(); ++i)
          if (p.numbers[i] != std::floor(p.numbers[i]) || std::abs(p.numbers[i]) > 2147483647.0)
            throw InputError({file_, values[i].line, ""}, what + ": expected an integer, found '" + values[i].text + "'");
        break;
      case PbrtParamType::real: all_numbers(); break;
      case PbrtParamType::point2:
      case PbrtParamType::vector2: all_numbers(); multiple_of(2, "x y pairs"); break;
      case PbrtParamType::point3:
      case PbrtParamType::vector3:
      case PbrtParamType::normal: all_numbers(); multiple_of(3, "x y z triples"); break;
      case PbrtParamType::rgb:
        all_numbers();
        if (p.numbers.size() != 3) throw InputError(p.where, what + ": expected 3 numbers (r g b), found " + std::to_string(p.numbers.size()));
        for (double v : p.numbers)
          if (v < 0) throw InputError(p.where, what + ": RGB values must be >= 0");
        break;
      case PbrtParamType::blackbody:
        all_numbers();
        if (p.numbers.size() != 1 || p.numbers[0] <= 0)
          throw InputError(p.where, what + ": expected one positive temperature in kelvin");
        break;
      case PbrtParamType::boolean:
        for (const PbrtToken& t : values) {
          if (t.text != "true" && t.text != "false")
            throw InputError({file_, t.line, ""}, what + ": expected true or false, found '" + t.text + "'");
          p.bools.push_back(t.text == "true");
        }
        break;
      case PbrtParamType::string:
      case PbrtParamType::texture: all_strings(); break;
      case PbrtParamType::spectrum:
        if (values.front().quoted) {
          all_strings();
          if (p.strings.size() != 1) throw InputError(p.where, what + ": expected one spectrum name or file");
        } else {
          all_numbers();
          if (p.numbers.size() < 2 || p.numbers.size() % 2 != 0)
            throw InputError(p.where, what + ": expected wavelength-value pairs (an even count), found " +
                                          std::to_string(p.numbers.size()) + " numbers");
          for (size_t i = 2; i < p.numbers.size(); i += 2)
            if (p.numbers[i] <= p.numbers[i - 2])
              throw InputError(p.where, what + ": wavelengths must increase (" + std::to_string(p.numbers[i]) +
                                            " nm follows " + std::to_string(p.numbers[i - 2]) + " nm)");
        }
        break;
    }
  }

  void include(const PbrtStatement& s) {
    if (depth_ >= 64) throw InputError(s.where, s.keyword + ": more than 64 nested includes (does a file include itself?)");
    if (++budget_.included_files > budget_.limits.max_included_files)
      throw InputError(s.where, s.keyword + ": the scene reads more than " +
                                    with_commas(budget_.limits.max_included_files) +
                                    " included files (counting repeats: do files include each other more than "
                                    "once?; docs/pbrt-import.md, \"Limits\")");
    const std::filesystem::path path = directory_ / s.strings[0];
    // The reader every input goes through: only regular files (a folder, a FIFO or /dev/zero are refused), a size
    // limit, and the scene hash's record of what was read.
    std::string text;
    try {
      text = read_input_file(path, kMaxPbrtFileBytes);
    } catch (const InputError& e) {
      throw InputError(s.where, s.keyword + ": '" + path.string() + "': " + e.explanation());
    }
    Parser nested(handle_, depth_ + 1, budget_);
    nested.parse(text, path.string(), path.parent_path());
  }

  const std::function<void(const PbrtStatement&)>& handle_;
  int depth_;
  ParseBudget& budget_;
  PbrtTokenizer* tokenizer_ = nullptr;  ///< of the file being parsed
  std::optional<PbrtToken> next_;       ///< the token after the ones taken: one token of lookahead is all pbrt needs
  int last_line_ = 1;
  std::string file_;
  std::filesystem::path directory_;
};

}  // namespace

const PbrtParam* PbrtStatement::find(const std::string& name) const {
  for (const PbrtParam& p : params)
    if (p.name == name) return &p;
  return nullptr;
}

void parse_pbrt_text(const std::string& text, const std::string& file, const std::filesystem::path& directory,
                     const std::function<void(const PbrtStatement&)>& handle, const PbrtParseLimits& limits) {
  ParseBudget budget{limits};
  Parser parser(handle, 0, budget);
  parser.parse(text, file, directory);
}

void parse_pbrt_file(const std::filesystem::path& file, const std::function<void(const PbrtStatement&)>& handle,
                     const PbrtParseLimits& limits) {
  parse_pbrt_text(read_input_file(file, kMaxPbrtFileBytes), file.string(), file.parent_path(), handle, limits);
}

}  // namespace rimu
