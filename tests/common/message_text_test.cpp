// Untrusted text in messages (common/message_text.h): cut with the length
// given, control bytes and invalid UTF-8 escaped, valid UTF-8 kept. The
// expected strings are written out by hand.
#include <gtest/gtest.h>

#include <string>

#include "common/config_error.h"
#include "common/message_text.h"

TEST(MessageText, PrintableAsciiIsKeptAndBackslashesDoubled) {
  EXPECT_EQ(bsg::printable_excerpt("target_kl=0.01"), "target_kl=0.01");
  EXPECT_EQ(bsg::printable_excerpt("a\\b"), "a\\\\b");
}

TEST(MessageText, ControlBytesDelAndInvalidUtf8AreEscaped) {
  EXPECT_EQ(bsg::printable_excerpt("le\x1b[31m"), "le\\x1B[31m");
  EXPECT_EQ(bsg::printable_excerpt(std::string("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(bsg::printable_excerpt("x\ty\r\n\x7f"), "x\\ty\\r\\n\\x7F");
  EXPECT_EQ(bsg::printable_excerpt("\xff\xfe"), "\\xFF\\xFE");
  EXPECT_EQ(bsg::printable_excerpt("\xc0\xaf"), "\\xC0\\xAF");          // overlong '/'
  EXPECT_EQ(bsg::printable_excerpt("\xed\xa0\x80"), "\\xED\\xA0\\x80");  // a UTF-16 surrogate
  EXPECT_EQ(bsg::printable_excerpt("\xc2\x9b"), "\\xC2\\x9B");          // C1 control CSI
  EXPECT_EQ(bsg::printable_excerpt("\xe2\x82"), "\\xE2\\x82");          // cut sequence
}

TEST(MessageText, ValidUtf8IsKept) {
  EXPECT_EQ(bsg::printable_excerpt("Lagrange \xce\xbb = 0.5 \xe2\x82\xac \xf0\x9f\x99\x82"),
            "Lagrange \xce\xbb = 0.5 \xe2\x82\xac \xf0\x9f\x99\x82");
}

TEST(MessageText, LongTextIsCutWithItsLength) {
  const std::string value(8 * 1024 * 1024, 'x');
  EXPECT_EQ(bsg::printable_excerpt(value, 5), "xxxxx... (8388608 bytes)");
  EXPECT_EQ(bsg::printable_excerpt(value).size(), 120u + std::string("... (8388608 bytes)").size());
  EXPECT_EQ(bsg::printable_message(value).size(), 8192u + std::string("... (8388608 bytes)").size());
}

TEST(MessageText, AWholeMessageKeepsItsLineEndsAndEscapesTheRest) {
  EXPECT_EQ(bsg::printable_message("line 1\nline\x1b 2\\"), "line 1\nline\\x1B 2\\");
  EXPECT_STREQ(bsg::ConfigError("key 'alg' = 'x\x07'").what(), "key 'alg' = 'x\\x07'");
}
