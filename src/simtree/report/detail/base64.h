#pragma once
// Base64 (RFC 4648, with padding) for the data the report inlines: images as data: URIs and the
// animation's binary arrays, which the page decodes with atob().

#include <cstddef>
#include <string>
#include <string_view>

namespace simtree::report {

// The encoded length of `bytes` bytes: 4 characters per 3 bytes, rounded up.
constexpr size_t Base64Size(size_t bytes) { return (bytes + 2) / 3 * 4; }

std::string Base64Encode(std::string_view bytes);
// Throws InputError (source "<base64>") for a length that is not a multiple of 4, a character
// outside the alphabet or misplaced padding.
std::string Base64Decode(std::string_view text);

}  // namespace simtree::report
