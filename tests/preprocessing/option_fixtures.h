#pragma once
// What an options struct's Validate() says about it, for the tests of every stage's options.

#include <string>

#include "simtree/core/error.h"

namespace simtree::test {

// The field Validate() names for `options` (InputError::where), "" when it accepts them.
template <class Options>
std::string RefusedField(const Options& options) {
  try {
    options.Validate();
  } catch (const InputError& e) {
    return e.where();
  }
  return "";
}

// RefusedField of default Options after `change(options)`.
template <class Options, class Change>
std::string RefusedFieldAfter(Change change) {
  Options options;
  change(options);
  return RefusedField(options);
}

}  // namespace simtree::test
