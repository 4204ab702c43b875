#include <gtest/gtest.h>

#include "mixmesh/core/quoted.hpp"

namespace mixmesh {
namespace {

TEST(Quoted, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(quoted("wing"), "\"wing\"");
  EXPECT_EQ(quoted("a \"b\" c\\d"), "\"a \\\"b\\\" c\\\\d\"");
  EXPECT_EQ(quoted("line\nnext\tcolumn"), "\"line\\nnext\\tcolumn\"");
  EXPECT_EQ(quoted(std::string("bell\a") + '\x1f' + '\x7f'), "\"bell\\u0007\\u001f\\u007f\"");
  EXPECT_EQ(quoted("\xc3\xa9t\xc3\xa9"), "\"\xc3\xa9t\xc3\xa9\"");  // UTF-8 passes as it is
}

}  // namespace
}  // namespace mixmesh
