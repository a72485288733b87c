#include "simtree/io/detail/cloud_header_check.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace fs = std::filesystem;

namespace simtree::cloud_detail {
namespace {

std::vector<std::string> Words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// A whole number in [0, 2^63); nothing for anything else (a sign, a fraction, too many digits).
std::optional<int64_t> Count(const std::string& word) {
  int64_t value = 0;
  const char* end = word.data() + word.size();
  auto [ptr, ec] = std::from_chars(word.data(), end, value);
  if (ec != std::errc() || ptr != end || value < 0) return std::nullopt;
  return value;
}

// Bytes of each PLY scalar type (both the PLY 1.0 names and the sized ones rply takes).
std::optional<int> PlyTypeBytes(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
      type == "float32") {
    return 4;
  }
  if (type == "double" || type == "float64") return 8;
  return std::nullopt;
}

// A PLY header line's words, split as rply splits them (spaces, tabs and carriage returns only);
// nothing when the line holds another control character, which rply and this check would read
// differently.
std::optional<std::vector<std::string>> PlyWords(const std::string& line) {
  std::vector<std::string> out;
  std::string word;
  for (const char c : line) {
    if (c == ' ' || c == '\t' || c == '\r') {
      if (!word.empty()) out.push_back(std::move(word));
      word.clear();
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      return std::nullopt;
    } else {
      word.push_back(c);
    }
  }
  if (!word.empty()) out.push_back(std::move(word));
  return out;
}

// `count` items of at least `bytes` each must fit in `available` bytes (no overflow: both are
// below 2^63 and the product is compared by division).
bool Fits(int64_t count, int64_t bytes, int64_t available) {
  return bytes == 0 || count <= available / bytes;
}

}  // namespace

void CheckPointCount(const std::string& source, const std::string& where, int64_t points,
                     int64_t max_points) {
  if (points <= max_points) return;
  throw InputError(source, where,
                   fmt::format("{} points or more; simtree reads at most {} (memory: "
                               "about 72 bytes a point): thin the cloud first, e.g. voxel "
                               "down-sampling to 5 mm keeps a tree's shape",
                               points, max_points));
}

void CheckPlyHeader(const fs::path& path, int64_t max_points) {
  std::ifstream in(path, std::ios::binary);
  const std::string source = path.string();
  std::string line;
  if (!std::getline(in, line) || PlyWords(line) != std::vector<std::string>{"ply"}) {
    throw InputError(source, "header line 1", "expected \"ply\", the PLY magic line");
  }
  const int64_t file_bytes = static_cast<int64_t>(fs::file_size(path));
  bool ascii = false;
  struct Element {
    std::string name;
    int64_t count = 0;
    int64_t min_bytes = 0;  // per instance
    int line = 0;
  };
  std::vector<Element> elements;
  for (int number = 2; std::getline(in, line); ++number) {
    const std::string where = fmt::format("header line {}", number);
    const std::optional<std::vector<std::string>> words = PlyWords(line);
    if (!words) throw InputError(source, where, "expected printable text in the PLY header");
    const std::vector<std::string>& w = *words;
    if (w.empty()) continue;
    const std::string& keyword = w[0];
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      // rply reads the data from after the newline; without one it reads before its buffer.
      if (in.eof()) throw InputError(source, where, "expected a newline after \"end_header\"");
      const int64_t header_end = static_cast<int64_t>(in.tellg());
      // + 1: the file's last value needs no separator after it.
      int64_t available = file_bytes - header_end + (ascii ? 1 : 0);
      for (const Element& e : elements) {
        if (!Fits(e.count, e.min_bytes, available)) {
          throw InputError(source, fmt::format("header line {}", e.line),
                           fmt::format("element \"{}\" claims {} items of at least {} bytes, but "
                                       "the file has {} bytes after its header",
                                       e.name, e.count, e.min_bytes, file_bytes - header_end));
        }
        available -= e.count * e.min_bytes;
      }
      return;
    }
    if (keyword == "format" && w.size() == 3) {
      ascii = w[1] == "ascii";
    } else if (keyword == "element" && w.size() == 3) {
      const std::optional<int64_t> count = Count(w[2]);
      if (!count) {
        throw InputError(
            source, where,
            fmt::format("expected a whole number of \"{}\" items, got \"{}\"", w[1], w[2]));
      }
      if (w[1] == "vertex") CheckPointCount(source, where, *count, max_points);
      elements.push_back({w[1], *count, 0, number});
    } else if (keyword == "property" && !elements.empty() &&
               ((w.size() == 3 && PlyTypeBytes(w[1])) ||
                (w.size() == 5 && w[1] == "list" && PlyTypeBytes(w[2]) && PlyTypeBytes(w[3])))) {
      // A list holds at least its length (an empty list); ASCII values take at least a digit and
      // a separator.
      elements.back().min_bytes += ascii ? 2 : *PlyTypeBytes(w.size() == 5 ? w[2] : w[1]);
    } else {
      // Open3D's reader (rply) skips some malformed lines and reads the rest differently.
      throw InputError(source, where,
                       fmt::format("expected \"format\", \"element NAME COUNT\", \"property TYPE "
                                   "NAME\", \"property list TYPE TYPE NAME\" (after an element), "
                                   "\"comment\" or \"end_header\", got \"{}\"",
                                   line.substr(0, 80)));
    }
  }
  throw InputError(source, "", "expected \"end_header\" to close the PLY header");
}

void CheckPcdHeader(const fs::path& path, int64_t max_points) {
  std::ifstream in(path, std::ios::binary);
  const int64_t file_bytes = static_cast<int64_t>(fs::file_size(path));
  const std::string source = path.string();
  size_t fields = 0;
  std::vector<int64_t> sizes, counts;
  int64_t width = 0, points = -1;
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    const std::vector<std::string> w = Words(line);
    if (w.empty() || w[0].starts_with("#")) continue;
    const std::string where = fmt::format("header line {}", line_number);
    // Open3D reads a header line in pieces of 1,023 bytes: a longer one it would misread.
    if (line.size() >= 1023) {
      throw InputError(source, where, "expected a header line under 1,023 characters");
    }
    auto number = [&] {
      const std::optional<int64_t> v = w.size() == 2 ? Count(w[1]) : std::nullopt;
      if (!v)
        throw InputError(source, where, fmt::format("expected one whole number after {}", w[0]));
      return *v;
    };
    auto numbers = [&](const char* what) {
      std::vector<int64_t> out;
      for (size_t i = 1; i < w.size(); ++i) {
        const std::optional<int64_t> v = Count(w[i]);
        if (!v) {
          throw InputError(source, where,
                           fmt::format("expected whole numbers for {}, got \"{}\"", what, w[i]));
        }
        out.push_back(*v);
      }
      if (out.size() != fields) {
        throw InputError(
            source, where,
            fmt::format("expected {} {} values, one per field, got {}", fields, what, out.size()));
      }
      return out;
    };
    // Open3D matches the keywords by prefix; so does this.
    if (w[0].starts_with("FIELDS") || w[0].starts_with("COLUMNS")) {
      fields = w.size() - 1;
      sizes.assign(fields, 4);
      counts.assign(fields, 1);
      // Open3D keeps normals only when all three are there, but writes any one it reads.
      const auto has = [&](const char* name) {
        return std::find(w.begin() + 1, w.end(), name) != w.end();
      };
      const int normals = has("normal_x") + has("normal_y") + has("normal_z");
      if (normals != 0 && normals != 3) {
        throw InputError(source, where,
                         "expected all three of normal_x, normal_y and normal_z, or none");
      }
    } else if (w[0].starts_with("SIZE")) {
      sizes = numbers("SIZE");
      for (int64_t s : sizes) {
        if (s != 1 && s != 2 && s != 4 && s != 8) {
          throw InputError(source, where, fmt::format("expected SIZE 1, 2, 4 or 8, got {}", s));
        }
      }
    } else if (w[0].starts_with("COUNT")) {
      counts = numbers("COUNT");
      for (int64_t c : counts) {
        if (c < 1 || c > (1 << 20)) {
          throw InputError(source, where, fmt::format("expected COUNT 1 to 2^20, got {}", c));
        }
      }
    } else if (w[0].starts_with("WIDTH")) {
      width = number();
    } else if (w[0].starts_with("HEIGHT")) {
      const int64_t height = number();
      points = Fits(width, height, int64_t{1} << 62) ? width * height : INT64_MAX;
    } else if (w[0].starts_with("POINTS")) {
      points = number();
    } else if (w[0].starts_with("DATA")) {
      if (points < 0) return;  // Open3D refuses it
      CheckPointCount(source, where, points, max_points);
      const std::string data = w.size() >= 2 ? w[1] : "ascii";
      int64_t point_bytes = 0, values = 0;
      for (size_t i = 0; i < fields; ++i) {
        point_bytes += sizes[i] * counts[i];
        values += counts[i];
      }
      int64_t available = file_bytes - static_cast<int64_t>(in.tellg());
      if (data.starts_with("binary_compressed")) {
        uint32_t compressed = 0, uncompressed = 0;
        in.read(reinterpret_cast<char*>(&compressed), 4);
        in.read(reinterpret_cast<char*>(&uncompressed), 4);
        if (!in) return;  // Open3D refuses it
        available -= 8;
        // LZF turns 3 bytes into at most 264: a larger claim cannot be the data.
        if (compressed > available || int64_t{uncompressed} > 88 * int64_t{compressed} + 88 ||
            !Fits(points, point_bytes, uncompressed) ||
            (point_bytes > 0 && points * point_bytes != uncompressed)) {
          throw InputError(source, where,
                           fmt::format("the compressed data claims {} bytes ({} uncompressed) for "
                                       "{} points of {} bytes, but the file has {} bytes after "
                                       "its header",
                                       compressed, uncompressed, points, point_bytes, available));
        }
        return;
      }
      const bool binary = data.starts_with("binary");
      const int64_t min_point_bytes = binary ? point_bytes : 2 * values;
      // + 1 when ASCII: the file's last value needs no separator after it.
      if (!Fits(points, min_point_bytes, available + (binary ? 0 : 1))) {
        throw InputError(source, where,
                         fmt::format("the header claims {} points of at least {} bytes, but the "
                                     "file has {} bytes after its header",
                                     points, min_point_bytes, available));
      }
      return;
    }
  }
}

}  // namespace simtree::cloud_detail
