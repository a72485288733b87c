#include "simtree/report/detail/page_context.h"

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/report/detail/html.h"

namespace simtree::report {

void Section::Missing(const std::string& text) {
  html += MissingHtml(text);
  notes.push_back(text);
}

void Section::LeftOut(const std::string& text) {
  html += NoteHtml(text);
  notes.push_back(text);
}

void Section::Remark(const std::string& text) { html += NoteHtml(text); }

PageContext::PageContext(const ResultFolder& folder, const ReportOptions& options, bool scripts)
    : folder_(folder), options_(options), scripts_(scripts) {}

std::string PageContext::Figure(const std::filesystem::path& path, const std::string& caption,
                                Section& section, int max_width) {
  const std::string name = RelativeName(folder_, path);
  ImageEmbedOptions embed;
  embed.max_width = max_width > 0 ? max_width : options_.max_image_width;
  try {
    return Place(EmbedImageFile(path, embed), name, caption, section);
  } catch (const Error& e) {
    section.LeftOut(fmt::format("{} could not be read: {}", name, e.what()));
    return "";
  }
}

std::string PageContext::FigureOf(const RgbImage& image, const std::string& name,
                                  const std::string& caption, Section& section, int max_width) {
  ImageEmbedOptions embed;
  embed.max_width = max_width > 0 ? max_width : options_.max_image_width;
  return Place(EmbedRgbImage(image, embed), name, caption, section);
}

std::string PageContext::Place(const EmbeddedImage& image, const std::string& name,
                               const std::string& caption, Section& section) {
  if (image_bytes_ + image.bytes() > options_.image_max_bytes) {
    section.LeftOut(fmt::format("{} left out: the page's images reached their budget of {}", name,
                                FormatBytes(options_.image_max_bytes)));
    return "";
  }
  image_bytes_ += image.bytes();
  return fmt::format(
      "<figure><img src=\"{}\" width=\"{}\" height=\"{}\" alt=\"{}\">"
      "<figcaption>{}</figcaption></figure>\n",
      image.data_uri, image.width, image.height, EscapeHtml(name), EscapeHtml(caption));
}

void PageContext::SetData(const std::string& key, nlohmann::json value) {
  data_[key] = std::move(value);
}

std::string RelativeName(const ResultFolder& folder, const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::path rel = std::filesystem::relative(path, folder.root, ec);
  if (ec || rel.empty() || rel.string().rfind("..", 0) == 0) return path.string();
  return rel.generic_string();
}

}  // namespace simtree::report
