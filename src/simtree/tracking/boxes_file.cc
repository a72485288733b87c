#include "simtree/tracking/boxes_file.h"

#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"

namespace simtree::tracking {
namespace {

std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

double Number(const std::string& text, const std::string& source, const std::string& where,
              const char* field) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value)) {
    throw InputError(source, where,
                     fmt::format("{}: expected a finite number, got '{}'", field, text));
  }
  return value;
}

MarkerBox ParseRow(const std::vector<std::string>& f, const std::string& source,
                   const std::string& where, int* frame) {
  if (f.size() != 10) {
    throw InputError(source, where, fmt::format("expected 10 fields, got {}", f.size()));
  }
  *frame = static_cast<int>(Number(f[0], source, where, "frame"));
  MarkerBox b;
  b.marker = static_cast<int>(Number(f[1], source, where, "marker"));
  for (int k = 0; k < 4; ++k) {
    static const char* kNames[4] = {"x", "y", "w", "h"};
    b.box[k] = Number(f[2 + k], source, where, kNames[k]);
  }
  if (b.box[2] < 0.0 || b.box[3] < 0.0) {
    throw InputError(source, where, "w, h: expected sizes >= 0");
  }
  b.center = {Number(f[6], source, where, "cx"), Number(f[7], source, where, "cy")};
  b.state = ParseMarkerState(f[8], source + ": " + where);
  b.confidence = Number(f[9], source, where, "confidence");
  if (b.confidence < 0.0 || b.confidence > 1.0) {
    throw InputError(source, where, "confidence: expected a value in [0, 1]");
  }
  return b;
}

void CheckSameMarkers(const std::vector<FrameBoxes>& frames, const std::string& source) {
  for (const FrameBoxes& f : frames) {
    bool same = f.markers.size() == frames[0].markers.size();
    for (size_t i = 0; same && i < f.markers.size(); ++i) {
      same = f.markers[i].marker == frames[0].markers[i].marker;
    }
    if (!same) {
      throw InputError(source, fmt::format("frame {}", f.frame),
                       "expected the markers of the first frame, in the same order");
    }
  }
}

}  // namespace

std::string BoxesToCsv(const std::vector<FrameBoxes>& frames) {
  std::string out = std::string(kBoxesFirstLine) + "\n" + kBoxesHeader + "\n";
  for (const FrameBoxes& f : frames) {
    for (const MarkerBox& b : f.markers) {
      out += fmt::format("{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{},{:.3f}\n", f.frame,
                         b.marker, b.box[0], b.box[1], b.box[2], b.box[3], b.center[0], b.center[1],
                         ToString(b.state), b.confidence);
    }
  }
  return out;
}

std::vector<FrameBoxes> ParseBoxesCsv(const std::string& text, const std::string& source) {
  std::vector<FrameBoxes> frames;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  bool have_first = false, have_header = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::string where = fmt::format("line {}", line_number);
    if (!have_first || !have_header) {
      const char* expected = have_first ? kBoxesHeader : kBoxesFirstLine;
      if (line != expected) {
        throw InputError(source, where, fmt::format("expected '{}', got '{}'", expected, line));
      }
      (have_first ? have_header : have_first) = true;
      continue;
    }
    int frame = 0;
    const MarkerBox box = ParseRow(Split(line), source, where, &frame);
    if (frames.empty() || frames.back().frame != frame) {
      if (!frames.empty() && frame < frames.back().frame) {
        throw InputError(source, where,
                         fmt::format("frame {} after frame {}: expected frames "
                                     "in increasing order",
                                     frame, frames.back().frame));
      }
      frames.push_back(FrameBoxes{frame, {}});
    }
    frames.back().markers.push_back(box);
  }
  if (!have_header) throw InputError(source, "", "expected the boxes.csv header, file is empty");
  CheckSameMarkers(frames, source);
  return frames;
}

std::vector<FrameBoxes> ReadBoxesCsv(const std::filesystem::path& path) {
  return ParseBoxesCsv(ReadFile(path), path.string());
}

void WriteBoxesCsv(const std::vector<FrameBoxes>& frames, const std::filesystem::path& path) {
  WriteFileAtomically(path, BoxesToCsv(frames));
}

}  // namespace simtree::tracking
