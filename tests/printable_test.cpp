// Input bytes in messages (core/printable.h): one printable line whatever the input holds.
#include "core/printable.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

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

TEST(Printable, JsonTextIsUtf8AndTellsEveryInputApart) {
  EXPECT_EQ(json_text("plain/name.csv"), "plain/name.csv");
  EXPECT_EQ(json_text("λ\x1b[2J"), "λ\x1b[2J");  // valid UTF-8: JSON escapes controls itself
  EXPECT_EQ(json_text("m\xff.json"), "m\\xFF.json");
  // A backslash in the name could be mistaken for an escape: such a name is escaped whole.
  EXPECT_EQ(json_text("m\\xFF.json"), "m\\\\xFF.json");
  EXPECT_NE(json_text("m\\xFF.json"), json_text("m\xff.json"));
  EXPECT_TRUE(valid_utf8(json_text("\xc0\xaf\xed\xa0\x80")));
}

TEST(Printable, SystemErrorsInWords) {
  EXPECT_EQ(error_words(std::make_error_code(std::errc::filename_too_long)), "file name too long");
  EXPECT_EQ(error_words(std::make_error_code(std::errc::too_many_symbolic_link_levels)),
            "too many levels of symbolic links");
}

TEST(Printable, LibraryErrorsLoseTheirLibrarysFraming) {
  // The backstop of failure_text(): what got past a translation still reads as kasha's line.
  const std::filesystem::filesystem_error fs("status", "a\x1b.csv",
                                             std::make_error_code(std::errc::filename_too_long));
  EXPECT_EQ(library_error_text(fs), "a\\x1B.csv: file name too long");
  try {
    (void)nlohmann::json(std::string("\xff")).dump();
    ADD_FAILURE() << "nlohmann accepted invalid UTF-8";
  } catch (const nlohmann::json::exception& e) {
    EXPECT_EQ(library_error_text(e).rfind("invalid UTF-8 byte", 0), 0u) << library_error_text(e);
  }
}
