// Input bytes in messages (core/printable.h): one printable line whatever the input holds.
#include "core/printable.h"

#include <gtest/gtest.h>

using namespace kasha;

TEST(Printable, EscapesControlBytesAndInvalidUtf8AndKeepsText) {
  EXPECT_EQ(printable("plain 500 nm"), "plain 500 nm");
  EXPECT_EQ(printable("λ = 500 nm, 10°"), "λ = 500 nm, 10°");  // valid UTF-8 stays
  EXPECT_EQ(printable("a\nb\rc\x1b[31m"), "a\\x0Ab\\x0Dc\\x1B[31m");
  EXPECT_EQ(printable(std::string("nul\0x", 5)), "nul\\x00x");
  EXPECT_EQ(printable("back\\slash"), "back\\\\slash");
  EXPECT_EQ(printable("\xff\xfe"), "\\xFF\\xFE");
  EXPECT_EQ(printable("\xc0\xaf"), "\\xC0\\xAF");           // overlong '/'
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xED\\xA0\\x80");  // a surrogate
  EXPECT_EQ(printable("\xe2\x82"), "\\xE2\\x82");           // cut short
  EXPECT_EQ(printable("del\x7f"), "del\\x7F");
  EXPECT_TRUE(valid_utf8("λ°"));
  EXPECT_FALSE(valid_utf8("\xff"));
  EXPECT_FALSE(valid_utf8("\xf4\x90\x80\x80"));  // above U+10FFFF
}
