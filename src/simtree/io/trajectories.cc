#include "simtree/io/trajectories.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/units.h"

namespace simtree {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ' || s.back() == '\t'))
    s.remove_suffix(1);
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  return s;
}

std::vector<std::string_view> SplitCommas(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    fields.push_back(
        Trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

bool ParseInt(std::string_view s, int* out) {
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && ptr == s.data() + s.size() && !s.empty();
}

bool ParseDouble(std::string_view s, double* out) {
  if (s.empty()) return false;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && ptr == s.data() + s.size();
}

bool IsNaNWord(std::string_view s) {
  std::string lower(s);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return lower == "nan" || lower == "-nan";
}

std::string Quote(std::string_view s) {
  // fmt rather than operator+: GCC 12 warns (-Wrestrict) on the inlined concatenation.
  return fmt::format("\"{}\"", s.substr(0, std::min<size_t>(s.size(), 60)));
}

// The checks a writer makes before writing (a reader checks the same while parsing).
void CheckTrajectories(const Trajectories& t, const std::string& source) {
  if (t.frames.size() != t.times_s.size()) {
    throw InputError(
        source, "",
        fmt::format("{} frame numbers but {} times", t.frames.size(), t.times_s.size()));
  }
  if (t.frames.empty()) throw InputError(source, "", "expected at least one frame, got none");
  if (t.tracks.empty()) throw InputError(source, "", "expected at least one marker, got none");
  for (size_t i = 0; i < t.frames.size(); ++i) {
    if (!std::isfinite(t.times_s[i])) {
      throw InputError(source, fmt::format("frame {}", t.frames[i]), "time is not finite");
    }
    if (i > 0 && (t.frames[i] <= t.frames[i - 1] || t.times_s[i] <= t.times_s[i - 1])) {
      throw InputError(source, fmt::format("frame {}", t.frames[i]),
                       "expected frame numbers and times to increase");
    }
  }
  std::vector<int> ids;
  for (const MarkerTrack& track : t.tracks) {
    ids.push_back(track.marker);
    if (track.positions.size() != t.frames.size() || track.valid.size() != t.frames.size()) {
      throw InputError(source, fmt::format("marker {}", track.marker),
                       fmt::format("expected {} frames, got {} positions and {} flags",
                                   t.frames.size(), track.positions.size(), track.valid.size()));
    }
    for (size_t i = 0; i < t.frames.size(); ++i) {
      if (track.valid[i] && !track.positions[i].allFinite()) {
        throw InputError(source, fmt::format("frame {}, marker {}", t.frames[i], track.marker),
                         "valid position is not finite");
      }
    }
  }
  std::sort(ids.begin(), ids.end());
  if (std::adjacent_find(ids.begin(), ids.end()) != ids.end()) {
    throw InputError(source, "", "marker ids repeat");
  }
}

// Throws InputError naming the file and the line being read.
struct LineError {
  const std::string& source;
  int line = 0;
  [[noreturn]] void operator()(const std::string& message) const {
    throw InputError(source, fmt::format("line {}", line), message);
  }
};

// One data row: "frame,time_s,marker,x,y,z,valid".
struct TrajectoryRow {
  int frame = 0, marker = 0, valid = 0;
  double time = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Constant(kNaN);
};

TrajectoryRow ParseRow(std::string_view line, const LineError& fail) {
  const std::vector<std::string_view> f = SplitCommas(line);
  if (f.size() != 7) {
    fail(fmt::format("expected 7 fields \"frame,time_s,marker,x,y,z,valid\", got {}", f.size()));
  }
  TrajectoryRow r;
  if (!ParseInt(f[0], &r.frame))
    fail(fmt::format("frame: expected an integer, got {}", Quote(f[0])));
  if (!ParseDouble(f[1], &r.time) || !std::isfinite(r.time)) {
    fail(fmt::format("time_s: expected a finite number, got {}", Quote(f[1])));
  }
  if (!ParseInt(f[2], &r.marker)) {
    fail(fmt::format("marker: expected an integer id, got {}", Quote(f[2])));
  }
  if (!ParseInt(f[6], &r.valid) || (r.valid != 0 && r.valid != 1)) {
    fail(fmt::format("valid: expected 0 or 1, got {}", Quote(f[6])));
  }
  for (int k = 0; k < 3; ++k) {
    const std::string_view v = f[3 + k];
    double x = kNaN;
    if (v.empty() || IsNaNWord(v)) {
      if (r.valid) fail(fmt::format("{}: a valid row needs a finite coordinate", "xyz"[k]));
    } else if (!ParseDouble(v, &x) || (r.valid && !std::isfinite(x))) {
      fail(fmt::format("{}: expected a number in metres, got {}", "xyz"[k], Quote(v)));
    }
    r.position[k] = x;
  }
  return r;
}

// Gathers rows into frames and tracks, checking that frames increase, each frame's rows come
// together, and every marker appears once in every frame.
class TrajectoryBuilder {
 public:
  explicit TrajectoryBuilder(const std::string& source) : source_(source) {}

  bool empty() const { return out_.frames.empty(); }

  void Add(const TrajectoryRow& row, const LineError& fail) {
    const bool new_frame = out_.frames.empty() || row.frame != out_.frames.back();
    if (new_frame) {
      StartFrame(row, fail);
    } else if (row.time != out_.times_s.back()) {
      fail(fmt::format("time_s {} differs from {} on the same frame {}", row.time,
                       out_.times_s.back(), row.frame));
    }
    auto it = track_of_.find(row.marker);
    if (it == track_of_.end()) {
      if (out_.frames.size() > 1) {
        fail(
            fmt::format("marker {} first appears in frame {} (every marker must appear in every "
                        "frame)",
                        row.marker, row.frame));
      }
      it = track_of_.emplace(row.marker, out_.marker_count()).first;
      out_.tracks.push_back(MarkerTrack{row.marker, {}, {}});
      seen_in_frame_.push_back(false);
    }
    const int m = it->second;
    if (seen_in_frame_[m]) {
      fail(fmt::format("marker {} appears twice in frame {}", row.marker, row.frame));
    }
    seen_in_frame_[m] = true;
    ++seen_count_;
    out_.tracks[m].positions.push_back(row.valid ? row.position : Eigen::Vector3d::Constant(kNaN));
    out_.tracks[m].valid.push_back(row.valid == 1);
  }

  Trajectories Finish() {
    CloseFrame();
    return std::move(out_);
  }

 private:
  void StartFrame(const TrajectoryRow& row, const LineError& fail) {
    CloseFrame();
    if (!out_.frames.empty()) {
      if (row.frame < out_.frames.back()) {
        fail(
            fmt::format("frame {} after frame {}: expected frames in increasing order, each "
                        "frame's rows together",
                        row.frame, out_.frames.back()));
      }
      if (row.time <= out_.times_s.back()) {
        fail(fmt::format("time_s {} is not after the previous frame's {}", row.time,
                         out_.times_s.back()));
      }
    }
    out_.frames.push_back(row.frame);
    out_.times_s.push_back(row.time);
    std::fill(seen_in_frame_.begin(), seen_in_frame_.end(), false);
    seen_count_ = 0;
  }

  // Every marker must have appeared in the frame just read.
  void CloseFrame() const {
    if (out_.frames.empty() || seen_count_ == out_.marker_count()) return;
    for (const MarkerTrack& track : out_.tracks) {
      if (!seen_in_frame_[track_of_.at(track.marker)]) {
        throw InputError(source_, fmt::format("frame {}", out_.frames.back()),
                         fmt::format("marker {} is missing (every marker must appear in every "
                                     "frame, with valid 0 when lost)",
                                     track.marker));
      }
    }
  }

  const std::string& source_;
  Trajectories out_;
  std::unordered_map<int, int> track_of_;  // marker id -> index into out_.tracks
  std::vector<bool> seen_in_frame_;
  int seen_count_ = 0;
};

}  // namespace

int MarkerTrack::valid_count() const {
  return static_cast<int>(std::count(valid.begin(), valid.end(), true));
}

int Trajectories::IndexOf(int marker) const {
  for (size_t i = 0; i < tracks.size(); ++i) {
    if (tracks[i].marker == marker) return static_cast<int>(i);
  }
  return -1;
}

const MarkerTrack* Trajectories::Find(int marker) const {
  const int i = IndexOf(marker);
  return i < 0 ? nullptr : &tracks[i];
}

void Trajectories::AddFrame(int frame, double time_s, const std::vector<Eigen::Vector3d>& positions,
                            const std::vector<bool>& valid) {
  if (positions.size() != tracks.size() || valid.size() != tracks.size()) {
    throw InputError("<memory>", fmt::format("frame {}", frame),
                     fmt::format("expected {} markers, got {} positions and {} flags",
                                 tracks.size(), positions.size(), valid.size()));
  }
  frames.push_back(frame);
  times_s.push_back(time_s);
  for (size_t m = 0; m < tracks.size(); ++m) {
    tracks[m].valid.push_back(valid[m]);
    tracks[m].positions.push_back(valid[m] ? positions[m] : Eigen::Vector3d::Constant(kNaN));
  }
}

Trajectories ParseTrajectoriesCsv(const std::string& text, const std::string& source) {
  TrajectoryBuilder builder(source);
  LineError fail{source};
  size_t pos = 0;
  bool have_first_line = false, have_header = false;
  while (pos < text.size()) {
    const size_t eol = std::min(text.find('\n', pos), text.size());
    const std::string_view line = Trim(std::string_view(text).substr(pos, eol - pos));
    pos = eol + 1;
    ++fail.line;
    if (!have_first_line) {
      if (line != kTrajectoriesFirstLine) {
        fail(fmt::format("expected the first line \"{}\", got {}", kTrajectoriesFirstLine,
                         Quote(line)));
      }
      have_first_line = true;
      continue;
    }
    if (line.empty()) continue;
    if (!have_header) {
      if (line != kTrajectoriesHeader) {
        fail(fmt::format("expected the header \"{}\", got {}", kTrajectoriesHeader, Quote(line)));
      }
      have_header = true;
      continue;
    }
    builder.Add(ParseRow(line, fail), fail);
  }
  if (!have_first_line) {
    throw InputError(source, "", "expected a simtree.trajectories file, the file is empty");
  }
  if (!have_header) throw InputError(source, "", "expected the header line, got end of file");
  if (builder.empty()) throw InputError(source, "", "expected at least one frame, got none");
  return builder.Finish();
}

Trajectories ReadTrajectoriesCsv(const std::filesystem::path& path) {
  return ParseTrajectoriesCsv(ReadFile(path), path.string());
}

std::string TrajectoriesToCsv(const Trajectories& t) {
  CheckTrajectories(t, "<trajectories>");
  std::string out;
  out.reserve(64 + t.frames.size() * t.tracks.size() * 48);
  out += kTrajectoriesFirstLine;
  out += '\n';
  out += kTrajectoriesHeader;
  out += '\n';
  for (size_t i = 0; i < t.frames.size(); ++i) {
    for (const MarkerTrack& track : t.tracks) {
      if (track.valid[i]) {
        const Eigen::Vector3d& p = track.positions[i];
        fmt::format_to(std::back_inserter(out), "{},{:.6f},{},{:.6f},{:.6f},{:.6f},1\n",
                       t.frames[i], t.times_s[i], track.marker, p.x(), p.y(), p.z());
      } else {
        fmt::format_to(std::back_inserter(out), "{},{:.6f},{},,,,0\n", t.frames[i], t.times_s[i],
                       track.marker);
      }
    }
  }
  return out;
}

void WriteTrajectoriesCsv(const Trajectories& trajectories, const std::filesystem::path& path) {
  WriteFileAtomically(path, TrajectoriesToCsv(trajectories));
}

}  // namespace simtree
