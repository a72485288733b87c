#include "simtree/viewer/detail/pick_script.h"

#include <cmath>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"

namespace simtree::viewer::detail {
namespace {

struct VerbShape {
  PickVerb verb;
  size_t min_numbers, max_numbers;
};

const std::map<std::string, VerbShape>& Verbs() {
  static const std::map<std::string, VerbShape> verbs = {
      {"click", {PickVerb::kClick, 2, 2}}, {"click-image", {PickVerb::kClickImage, 2, 2}},
      {"zoom", {PickVerb::kZoom, 1, 3}},   {"pan", {PickVerb::kPan, 2, 2}},
      {"key", {PickVerb::kKey, 0, 0}},     {"wait", {PickVerb::kWait, 1, 1}}};
  return verbs;
}

}  // namespace

std::vector<PickAction> ParsePickScript(const std::string& text, const std::string& source) {
  std::vector<PickAction> actions;
  std::istringstream lines(text);
  std::string raw;
  for (int line = 1; std::getline(lines, raw); ++line) {
    const std::string content = raw.substr(0, raw.find('#'));
    std::istringstream words(content);
    std::string verb;
    if (!(words >> verb)) continue;
    const std::string where = fmt::format("line {}", line);
    const auto it = Verbs().find(verb);
    if (it == Verbs().end()) {
      throw InputError(source, where,
                       fmt::format("unknown action \"{}\" (expected click, click-image, zoom, "
                                   "pan, key or wait)",
                                   verb));
    }
    PickAction action{.verb = it->second.verb, .line = line, .numbers = {}, .key = {}};
    if (action.verb == PickVerb::kKey) {
      words >> action.key;
      if (action.key != "backspace" && action.key != "s" && action.key != "enter" &&
          action.key != "escape") {
        throw InputError(
            source, where,
            fmt::format("expected a key backspace, s, enter or escape, got \"{}\"", action.key));
      }
    }
    std::string word;
    while (words >> word) {
      double value = 0.0;
      try {
        size_t used = 0;
        value = std::stod(word, &used);
        if (used != word.size() || !std::isfinite(value)) throw std::invalid_argument(word);
      } catch (const std::exception&) {
        throw InputError(source, where, fmt::format("expected a number, got \"{}\"", word));
      }
      action.numbers.push_back(value);
    }
    const VerbShape& shape = it->second;
    const size_t n = action.numbers.size();
    if (n < shape.min_numbers || n > shape.max_numbers || (verb == "zoom" && n == 2)) {
      throw InputError(
          source, where,
          fmt::format("{} takes {} numbers, got {}", verb,
                      verb == "zoom" ? std::string("1 or 3") : std::to_string(shape.min_numbers),
                      n));
    }
    actions.push_back(std::move(action));
  }
  return actions;
}

std::vector<PickAction> ReadPickScript(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path)) {
    throw InputError(path.string(), "", "missing (the picking script, --pick-script)");
  }
  return ParsePickScript(ReadFile(path), path.string());
}

}  // namespace simtree::viewer::detail
