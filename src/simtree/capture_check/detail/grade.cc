#include "simtree/capture_check/detail/grade.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace simtree::capture_check::detail {

namespace {

bool Worse(const Limits& l, double value, double limit) {
  return l.better == Better::kHigher ? value < limit : value > limit;
}

std::string Describe(const Limits& l, double scale) {
  const char* op = l.better == Better::kHigher ? "<" : ">";
  if (l.fail == l.warn) return fmt::format("warn {} {:g}", op, l.warn * scale);
  return fmt::format("warn {0} {1:g}, fail {0} {2:g}", op, l.warn * scale, l.fail * scale);
}

}  // namespace

Check Grade(const std::string& name, const std::string& subject, double value,
            const std::string& unit, const Limits& limits, const std::string& found,
            const std::string& fix, double scale) {
  Check c;
  c.name = name;
  c.subject = subject;
  c.value = value * scale;
  c.unit = unit;
  c.limits = Describe(limits, scale);
  c.status = Status::kOk;
  if (limits.fail != limits.warn && Worse(limits, value, limits.fail)) {
    c.status = Status::kFail;
  } else if (Worse(limits, value, limits.warn)) {
    c.status = Status::kWarn;
  }
  c.message = c.status == Status::kOk ? found : found + ": " + fix;
  return c;
}

Check Failed(const std::string& name, const std::string& subject, const std::string& message) {
  Check c;
  c.name = name;
  c.subject = subject;
  c.value = std::numeric_limits<double>::quiet_NaN();
  c.status = Status::kFail;
  c.message = message;
  return c;
}

Check Skipped(const std::string& name, const std::string& subject, const std::string& why) {
  Check c = Failed(name, subject, why);
  c.status = Status::kSkipped;
  return c;
}

}  // namespace simtree::capture_check::detail
