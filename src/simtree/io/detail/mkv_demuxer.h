#pragma once
// A Matroska file opened with libavformat: its video tracks by name, its attachments, its tags,
// and its packets one at a time with timestamps in microseconds. libav types stay in the .cc.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "simtree/io/azure_kinect.h"

struct AVCodecParameters;

namespace simtree::azure_detail {

struct MkvStream {
  int index = 0;  // libav stream index
  AzureTrack track;
  const AVCodecParameters* parameters = nullptr;  // owned by the demuxer
};

// One packet's bytes, valid until the next call to MkvDemuxer::Next.
struct MkvPacket {
  int stream = 0;
  int64_t timestamp_us = 0;
  const uint8_t* data = nullptr;
  int size = 0;
};

class MkvDemuxer {
 public:
  // Reads the headers; throws InputError naming the file when it is not a readable Matroska file.
  explicit MkvDemuxer(const std::filesystem::path& path);
  ~MkvDemuxer();
  MkvDemuxer(const MkvDemuxer&) = delete;
  MkvDemuxer& operator=(const MkvDemuxer&) = delete;

  const std::vector<MkvStream>& streams() const { return streams_; }
  // The attachment of that file name, nothing when absent.
  std::optional<std::string> Attachment(const std::string& filename) const;
  // A tag of the file (segment), "" when absent.
  std::string Tag(const std::string& key) const;
  // Only these streams' packets are read (the others are skipped by the demuxer).
  void Select(const std::vector<int>& stream_indices);
  // The next packet of a selected stream, false at the end. Throws InputError on a read error.
  bool Next(MkvPacket& packet);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<MkvStream> streams_;
};

}  // namespace simtree::azure_detail
