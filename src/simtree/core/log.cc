#include "simtree/core/log.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"

namespace simtree {

void ConfigureLogging(const std::string& level) {
  const spdlog::level::level_enum parsed = spdlog::level::from_str(level);
  if (parsed == spdlog::level::off && level != "off") {
    throw InputError("--log-level", "",
                     "expected one of trace, debug, info, warn, error, off; got \"" + level + "\"");
  }
  static const bool once = [] {
    auto logger = spdlog::stderr_color_mt("simtree");
    logger->set_pattern("[%^%l%$] %v");
    spdlog::set_default_logger(logger);
    return true;
  }();
  (void)once;
  spdlog::set_level(parsed);
}

}  // namespace simtree
