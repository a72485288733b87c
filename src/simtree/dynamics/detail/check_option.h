#pragma once
// The one-line check of an options field, shared by the Validate() of simulate's, view's and
// render's options.

#include <string>

#include "simtree/core/error.h"

namespace simtree::dynamics {

// Throws InputError(source, field, message) unless `ok`.
inline void CheckOption(bool ok, const std::string& source, const std::string& field,
                        const std::string& message) {
  if (!ok) throw InputError(source, field, message);
}

}  // namespace simtree::dynamics
