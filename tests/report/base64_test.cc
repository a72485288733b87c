#include "simtree/report/detail/base64.h"

#include <random>

#include <gtest/gtest.h>

#include "simtree/core/error.h"

namespace simtree::report {
namespace {

TEST(Base64, MatchesTheRfcVectors) {
  // RFC 4648, section 10.
  EXPECT_EQ(Base64Encode(""), "");
  EXPECT_EQ(Base64Encode("f"), "Zg==");
  EXPECT_EQ(Base64Encode("fo"), "Zm8=");
  EXPECT_EQ(Base64Encode("foo"), "Zm9v");
  EXPECT_EQ(Base64Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64Encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64Encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(Base64Decode("Zm9vYmE="), "fooba");
}

TEST(Base64, RoundTripsEveryByteAndLength) {
  std::mt19937 rng(3);
  for (size_t n = 0; n < 70; ++n) {
    std::string bytes(n, '\0');
    for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
    const std::string text = Base64Encode(bytes);
    EXPECT_EQ(text.size(), Base64Size(n));
    EXPECT_EQ(Base64Decode(text), bytes) << n;
  }
  std::string all;
  for (int c = 0; c < 256; ++c) all += static_cast<char>(c);
  EXPECT_EQ(Base64Decode(Base64Encode(all)), all);
}

TEST(Base64, RefusesWhatIsNotBase64) {
  EXPECT_THROW(Base64Decode("Zm9"), InputError);       // length
  EXPECT_THROW(Base64Decode("Zm9v!A=="), InputError);  // alphabet
  EXPECT_THROW(Base64Decode("Z=9v"), InputError);      // padding inside
  EXPECT_THROW(Base64Decode("Zg==Zm9v"), InputError);  // padding before the end
}

}  // namespace
}  // namespace simtree::report
