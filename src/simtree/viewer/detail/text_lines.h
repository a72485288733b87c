#pragma once
// Line-oriented text files of the viewer (the authors' leaf.txt, scripted input): lines split into
// words, with 1-based line numbers so every error names the line it is about.

#include <string>
#include <vector>

namespace simtree::viewer {

struct TextLine {
  int number = 0;  // 1-based
  std::vector<std::string> words;
};

// The lines of `text` split on blanks (LF or CRLF). With `skip_comments`, text from '#' to the end
// of a line is dropped; blank lines are dropped either way.
std::vector<TextLine> SplitTextLines(const std::string& text, bool skip_comments);

// Word parsers that throw InputError(source, "line N", ...) naming `what` was expected.
double ParseNumberWord(const std::string& word, const std::string& source, int line,
                       const std::string& what);
int ParseIntegerWord(const std::string& word, const std::string& source, int line,
                     const std::string& what);

}  // namespace simtree::viewer
