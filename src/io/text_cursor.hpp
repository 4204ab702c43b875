// A forward cursor over a whole file image for the text formats (.msh, .su2): tokens
// and lines with the line number every error message needs, plus raw little-endian
// reads for the binary sections of .msh files. Nothing here allocates per token.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "mixmesh/core/error.hpp"

namespace mixmesh::io_detail {

class TextCursor {
 public:
  TextCursor(std::string_view text, std::string name) : text_(text), name_(std::move(name)) {}

  // The next whitespace-separated token; empty at the end of the text.
  std::string_view token();
  // As token(), but the end of the text is an error naming what was expected.
  std::string_view expect_token(std::string_view what);
  // The next token as a number; what names it in the error message.
  long long integer(std::string_view what);
  double real(std::string_view what);  // finite values only

  // The rest of the current line (without the newline); moves to the next line.
  // Returns false at the end of the text.
  bool line(std::string_view& out);
  // Moves past the next newline (the end of a header line before binary data).
  void skip_line_end();
  // Copies n raw bytes; a short read is an error naming what.
  void read_bytes(void* out, std::size_t count, std::string_view what);

  // Advances to just past the next occurrence of marker; false if there is none.
  bool skip_past(std::string_view marker);

  std::size_t remaining() const { return text_.size() - position_; }
  // The line of the last token or line returned (1-based).
  long line_number() const { return token_line_; }
  const std::string& name() const { return name_; }
  Error error(const std::string& message) const { return file_error(name_, token_line_, message); }

 private:
  std::string_view text_;
  std::string name_;
  std::size_t position_ = 0;
  long line_ = 1;
  long token_line_ = 1;
};

// Number parsing for a token already split off; false when the token is not one
// number in full (or, for reals, not finite).
bool parse_integer(std::string_view token, long long& value);
bool parse_real(std::string_view token, double& value);

// A token shortened for an error message.
std::string quoted(std::string_view token);

// Splits a line at blanks into at most capacity tokens; returns the token count, or
// capacity + 1 when the line holds more.
std::size_t split(std::string_view line, std::string_view* tokens, std::size_t capacity);

}  // namespace mixmesh::io_detail
