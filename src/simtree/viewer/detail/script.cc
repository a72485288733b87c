#include "simtree/viewer/detail/script.h"

#include <map>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/viewer/detail/text_lines.h"

namespace simtree::viewer {
namespace {

const std::map<std::string, ScriptVerb>& Verbs() {
  static const std::map<std::string, ScriptVerb> verbs = {
      {"pick", ScriptVerb::kPick},       {"pick-branch", ScriptVerb::kPickBranch},
      {"drag", ScriptVerb::kDrag},       {"drag-by", ScriptVerb::kDragBy},
      {"release", ScriptVerb::kRelease}, {"hover", ScriptVerb::kHover},
      {"wait", ScriptVerb::kWait},       {"screenshot", ScriptVerb::kScreenshot},
      {"key", ScriptVerb::kKey},         {"play", ScriptVerb::kPlay},
      {"pause", ScriptVerb::kPause},     {"step", ScriptVerb::kStep},
      {"reset", ScriptVerb::kReset},     {"wind", ScriptVerb::kWind},
      {"leaves", ScriptVerb::kLeaves},   {"material", ScriptVerb::kMaterial},
      {"orbit", ScriptVerb::kOrbit},     {"zoom", ScriptVerb::kZoom},
      {"quit", ScriptVerb::kQuit}};
  return verbs;
}

class LineParser {
 public:
  LineParser(const TextLine& line, const std::string& source) : line_(line), source_(source) {}

  [[noreturn]] void Fail(const std::string& message) const {
    throw InputError(source_, fmt::format("line {}", line_.number),
                     fmt::format("{}: {}", line_.words[0], message));
  }
  void Arity(size_t min_args, size_t max_args, const char* usage) const {
    const size_t n = line_.words.size() - 1;
    if (n < min_args || n > max_args) Fail(fmt::format("expected \"{}\"", usage));
  }
  double Number(size_t word, const char* what) const {
    return ParseNumberWord(line_.words[word], source_, line_.number, what);
  }
  int Count(size_t word, const char* what, int min_value) const {
    const int n = ParseIntegerWord(line_.words[word], source_, line_.number, what);
    if (n < min_value) Fail(fmt::format("expected {} >= {}, got {}", what, min_value, n));
    return n;
  }
  const std::string& Word(size_t word) const { return line_.words[word]; }
  size_t size() const { return line_.words.size(); }

 private:
  const TextLine& line_;
  const std::string& source_;
};

ScriptAction ParseAction(const TextLine& line, const std::string& source) {
  LineParser p(line, source);
  const auto verb = Verbs().find(line.words[0]);
  if (verb == Verbs().end()) {
    throw InputError(
        source, fmt::format("line {}", line.number),
        fmt::format("unknown action \"{}\" (expected pick, pick-branch, drag, drag-by, "
                    "release, hover, wait, screenshot, key, play, pause, step, reset, "
                    "wind, leaves, material, orbit, zoom or quit)",
                    line.words[0]));
  }
  ScriptAction a;
  a.verb = verb->second;
  a.line = line.number;
  switch (a.verb) {
    case ScriptVerb::kPick:
    case ScriptVerb::kHover:
      p.Arity(2, 2, fmt::format("{} X Y", line.words[0]).c_str());
      a.numbers = {p.Number(1, "X"), p.Number(2, "Y")};
      break;
    case ScriptVerb::kPickBranch: {
      p.Arity(1, 1, "pick-branch BRANCH[@S]");
      const std::string& w = p.Word(1);
      const size_t at = w.find('@');
      if (at == std::string::npos) {
        a.branch = p.Count(1, "the branch", 0);
      } else {
        a.branch = ParseIntegerWord(w.substr(0, at), source, line.number, "the branch");
        a.arc_length = ParseNumberWord(w.substr(at + 1), source, line.number, "S");
        if (a.branch < 0 || a.arc_length < 0) p.Fail("expected BRANCH >= 0 and S >= 0");
      }
      break;
    }
    case ScriptVerb::kDrag:
    case ScriptVerb::kDragBy:
      p.Arity(2, 3, a.verb == ScriptVerb::kDrag ? "drag X Y [FRAMES]" : "drag-by DX DY [FRAMES]");
      a.numbers = {p.Number(1, "X"), p.Number(2, "Y"),
                   p.size() > 3 ? static_cast<double>(p.Count(3, "FRAMES", 1)) : 1.0};
      break;
    case ScriptVerb::kWait:
      p.Arity(1, 1, "wait FRAMES");
      a.numbers = {static_cast<double>(p.Count(1, "FRAMES", 0))};
      break;
    case ScriptVerb::kScreenshot:
      p.Arity(1, 1, "screenshot PATH");
      a.text = p.Word(1);
      break;
    case ScriptVerb::kKey:
      p.Arity(1, 1, "key NAME");
      a.text = p.Word(1);
      break;
    case ScriptVerb::kWind:
      p.Arity(1, 1, "wind on|off|SPEED");
      if (p.Word(1) == "on" || p.Word(1) == "off") {
        a.on = p.Word(1) == "on";
      } else {
        a.numbers = {p.Number(1, "SPEED")};
        if (a.numbers[0] < 0) p.Fail("expected a speed >= 0 m/s");
      }
      break;
    case ScriptVerb::kLeaves:
      p.Arity(1, 1, "leaves on|off");
      if (p.Word(1) != "on" && p.Word(1) != "off") p.Fail("expected on or off");
      a.on = p.Word(1) == "on";
      break;
    case ScriptVerb::kMaterial: {
      p.Arity(4, 4, "material branch|level ID frequency|damping|stiffness VALUE");
      const std::string& target = p.Word(1);
      if (target != "branch" && target != "level") p.Fail("expected branch or level");
      a.scope = target == "level" ? MaterialScope::kLevel : MaterialScope::kBranch;
      a.branch = p.Count(2, "ID", 0);
      if (p.Word(3) != "frequency" && p.Word(3) != "damping" && p.Word(3) != "stiffness") {
        p.Fail("expected frequency, damping or stiffness");
      }
      a.property = ParseMaterialProperty(p.Word(3), "material");
      a.numbers = {p.Number(4, "VALUE")};
      break;
    }
    case ScriptVerb::kOrbit:
      p.Arity(2, 2, "orbit DYAW_DEG DPITCH_DEG");
      a.numbers = {p.Number(1, "DYAW_DEG"), p.Number(2, "DPITCH_DEG")};
      break;
    case ScriptVerb::kZoom:
      p.Arity(1, 1, "zoom FACTOR");
      a.numbers = {p.Number(1, "FACTOR")};
      if (a.numbers[0] <= 0) p.Fail("expected a factor > 0");
      break;
    case ScriptVerb::kRelease:
    case ScriptVerb::kPlay:
    case ScriptVerb::kPause:
    case ScriptVerb::kStep:
    case ScriptVerb::kReset:
    case ScriptVerb::kQuit:
      p.Arity(0, 0, line.words[0].c_str());
      break;
  }
  return a;
}

}  // namespace

std::vector<ScriptAction> ParseScript(const std::string& text, const std::string& source) {
  std::vector<ScriptAction> actions;
  for (const TextLine& line : SplitTextLines(text, true)) {
    actions.push_back(ParseAction(line, source));
  }
  return actions;
}

std::vector<ScriptAction> ReadScript(const std::string& path) {
  return ParseScript(ReadFile(path), path);
}

}  // namespace simtree::viewer
