// The check results for people (a table) and for programs (JSON).

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "simtree/capture_check/capture_check.h"

namespace simtree::capture_check {

namespace {

std::string Value(const Check& c) {
  if (std::isnan(c.value)) return "-";
  const double a = std::abs(c.value);
  const std::string number = a >= 100 || a == std::round(a) ? fmt::format("{:.0f}", c.value)
                             : a >= 10                      ? fmt::format("{:.1f}", c.value)
                                                            : fmt::format("{:.2f}", c.value);
  return c.unit.empty() ? number : number + " " + c.unit;
}

}  // namespace

std::string FormatTable(const CaptureCheckResult& result) {
  std::string out = fmt::format("capture-check {}\n\n", result.capture.string());
  out += fmt::format("{:<18} {:<14} {:>10}  {:<7}  {}\n", "check", "subject", "value", "status",
                     "limits");
  for (const Check& c : result.checks) {
    out += fmt::format("{:<18} {:<14} {:>10}  {:<7}  {}\n", c.name, c.subject, Value(c),
                       ToString(c.status), c.limits);
  }
  bool header = false;
  for (const Check& c : result.checks) {
    if (c.status != Status::kWarn && c.status != Status::kFail) continue;
    if (!header) out += "\nto fix:\n";
    header = true;
    out += fmt::format("  {} {} ({}): {}\n", ToString(c.status), c.subject, c.name, c.message);
  }
  out += fmt::format("\n{} ok, {} warn, {} fail, {} skipped: {} ({:.1f} s)\n",
                     result.Count(Status::kOk), result.Count(Status::kWarn),
                     result.Count(Status::kFail), result.Count(Status::kSkipped),
                     result.Worst() == Status::kFail   ? "fix the failures before `simtree run`"
                     : result.Worst() == Status::kWarn ? "usable; the warnings cost accuracy"
                                                       : "ready for `simtree run`",
                     result.seconds);
  return out;
}

nlohmann::ordered_json ToJson(const CaptureCheckResult& result) {
  nlohmann::ordered_json j;
  j["format"] = kCaptureCheckFormat;
  j["version"] = kCaptureCheckFormatVersion;
  j["capture"] = result.capture.string();
  j["status"] = ToString(result.Worst());
  j["checks"] = nlohmann::ordered_json::array();
  for (const Check& c : result.checks) {
    nlohmann::ordered_json item;
    item["name"] = c.name;
    item["subject"] = c.subject;
    item["value"] =
        std::isnan(c.value) ? nlohmann::ordered_json() : nlohmann::ordered_json(c.value);
    item["unit"] = c.unit;
    item["limits"] = c.limits;
    item["status"] = ToString(c.status);
    item["message"] = c.message;
    j["checks"].push_back(item);
  }
  j["seconds"] = result.seconds;
  return j;
}

}  // namespace simtree::capture_check
