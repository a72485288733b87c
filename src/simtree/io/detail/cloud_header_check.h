#pragma once
// Checks of a PLY or PCD header before Open3D reads the file. Open3D's readers allocate what the
// header claims before reading any data (a header claiming a billion points is 24 GB), and its
// PCD reader trusts the header's field layout (a COUNT of -1 indexes before its buffers). These
// refuse, with an InputError naming the file and the header line, a header that cannot describe
// the file it heads. A PLY header is read line by line as Open3D's rply reads it, and a line it
// would skip or read differently (a property of an unknown type, a control character) is refused
// too; a PCD header they do not understand is left to Open3D to refuse.

#include <cstdint>
#include <filesystem>
#include <string>

namespace simtree::cloud_detail {

// The most points a cloud file may hold. Open3D holds 72 bytes a point (positions, normals and
// colours as doubles): 20 million is about 1.4 GB before any work, more is how a reader gets a
// machine killed for memory. A larger file is refused with a message saying to thin it.
inline constexpr int64_t kMaxCloudPoints = 20'000'000;

// Throws InputError naming `source` and `where` when `points` is above `max_points`.
void CheckPointCount(const std::string& source, const std::string& where, int64_t points,
                     int64_t max_points = kMaxCloudPoints);

// The magic line, then only format, comment, obj_info, element and property lines of the PLY
// grammar up to end_header; every element's count times its smallest size on disk (its
// properties' sizes when binary, two characters a value when ASCII) must fit in the bytes after
// the header. The vertex element's count must not be above `max_points`.
void CheckPlyHeader(const std::filesystem::path& path, int64_t max_points = kMaxCloudPoints);

// SIZE values of 1, 2, 4 or 8 and COUNT values of at least 1, one per field; the points (POINTS,
// or WIDTH x HEIGHT, whichever Open3D takes) must fit in the bytes after the header; compressed
// data must hold exactly the points and be no larger than the file holds; at most `max_points`.
void CheckPcdHeader(const std::filesystem::path& path, int64_t max_points = kMaxCloudPoints);

}  // namespace simtree::cloud_detail
