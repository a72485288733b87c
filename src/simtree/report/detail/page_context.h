#pragma once
// What the sections of the page share while it is built: the result folder, the options, the
// image budget and the data block the page's scripts read (charts, the animation).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/io/image_io.h"
#include "simtree/report/detail/image_embed.h"
#include "simtree/report/detail/result_folder.h"
#include "simtree/report/report.h"

namespace simtree::report {

// One section of the page: its HTML and what it says is missing.
struct Section {
  std::string id;
  std::string title;
  std::string html;
  bool present = false;            // something of it was in the result
  std::vector<std::string> notes;  // what is missing or left out, as said on the page

  // A part that is not in the result (shown, and listed in the notes).
  void Missing(const std::string& text);
  // A part that is there but left out or cut (shown, and listed in the notes).
  void LeftOut(const std::string& text);
  // A remark on the page only.
  void Remark(const std::string& text);
};

class PageContext {
 public:
  PageContext(const ResultFolder& folder, const ReportOptions& options, bool scripts);

  const ResultFolder& folder() const { return folder_; }
  const ReportOptions& options() const { return options_; }
  // Whether the page has its JavaScript libraries (charts and the 3D view work).
  bool scripts() const { return scripts_; }

  // A <figure> with the image inlined and a caption, or, when the file does not read or the image
  // budget is spent, a note in `section` and "". `max_width` 0: the options' width.
  std::string Figure(const std::filesystem::path& path, const std::string& caption,
                     Section& section, int max_width = 0);
  // The same for a picture drawn by the report (`name` in notes).
  std::string FigureOf(const RgbImage& image, const std::string& name, const std::string& caption,
                       Section& section, int max_width = 0);
  int64_t image_bytes() const { return image_bytes_; }

  // The JSON object the page's scripts read (one member per section that needs one).
  void SetData(const std::string& key, nlohmann::json value);
  const nlohmann::json& data() const { return data_; }

 private:
  const ResultFolder& folder_;
  const ReportOptions& options_;
  bool scripts_;
  // The figure's HTML when the image fits the budget (counted), else a note and "".
  std::string Place(const EmbeddedImage& image, const std::string& name, const std::string& caption,
                    Section& section);
  int64_t image_bytes_ = 0;
  nlohmann::json data_ = nlohmann::json::object();
};

// Path of `path` relative to the result folder, for captions and notes.
std::string RelativeName(const ResultFolder& folder, const std::filesystem::path& path);

}  // namespace simtree::report
