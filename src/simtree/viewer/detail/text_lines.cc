#include "simtree/viewer/detail/text_lines.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::viewer {

std::vector<TextLine> SplitTextLines(const std::string& text, bool skip_comments) {
  std::vector<TextLine> lines;
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (skip_comments) line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    TextLine out{number, {}};
    for (std::string w; words >> w;) out.words.push_back(w);
    if (!out.words.empty()) lines.push_back(std::move(out));
  }
  return lines;
}

double ParseNumberWord(const std::string& word, const std::string& source, int line,
                       const std::string& what) {
  double x = 0.0;
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, x);
  if (ec != std::errc() || ptr != end || !std::isfinite(x)) {
    throw InputError(source, fmt::format("line {}", line),
                     fmt::format("expected a finite number for {}, got \"{}\"", what, word));
  }
  return x;
}

int ParseIntegerWord(const std::string& word, const std::string& source, int line,
                     const std::string& what) {
  int x = 0;
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, x);
  if (ec != std::errc() || ptr != end) {
    throw InputError(source, fmt::format("line {}", line),
                     fmt::format("expected an integer for {}, got \"{}\"", what, word));
  }
  return x;
}

}  // namespace simtree::viewer
