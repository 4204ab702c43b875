#include "io/text_cursor.hpp"

#include <charconv>
#include <cmath>
#include <cstring>

namespace mixmesh::io_detail {

namespace {

bool is_blank(char character) {
  return character == ' ' || character == '\t' || character == '\r' || character == '\n' ||
         character == '\f' || character == '\v';
}

}  // namespace

std::string_view TextCursor::token() {
  while (position_ < text_.size() && is_blank(text_[position_])) {
    if (text_[position_] == '\n') ++line_;
    ++position_;
  }
  token_line_ = line_;
  const std::size_t start = position_;
  while (position_ < text_.size() && !is_blank(text_[position_])) ++position_;
  return text_.substr(start, position_ - start);
}

std::string_view TextCursor::expect_token(std::string_view what) {
  const std::string_view found = token();
  if (found.empty()) throw error("unexpected end of file, expected " + std::string(what));
  return found;
}

long long TextCursor::integer(std::string_view what) {
  const std::string_view found = expect_token(what);
  long long value = 0;
  if (!parse_integer(found, value))
    throw error("expected " + std::string(what) + " (an integer), found " + quoted(found));
  return value;
}

double TextCursor::real(std::string_view what) {
  const std::string_view found = expect_token(what);
  double value = 0;
  if (!parse_real(found, value))
    throw error("expected " + std::string(what) + " (a finite number), found " + quoted(found));
  return value;
}

bool TextCursor::line(std::string_view& out) {
  if (position_ >= text_.size()) return false;
  token_line_ = line_;
  const std::size_t end = text_.find('\n', position_);
  const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
  out = text_.substr(position_, stop - position_);
  if (!out.empty() && out.back() == '\r') out.remove_suffix(1);
  position_ = end == std::string_view::npos ? text_.size() : end + 1;
  if (end != std::string_view::npos) ++line_;
  return true;
}

void TextCursor::skip_line_end() {
  const std::size_t end = text_.find('\n', position_);
  if (end == std::string_view::npos) throw error("unexpected end of file after a header line");
  position_ = end + 1;
  ++line_;
}

void TextCursor::read_bytes(void* out, std::size_t count, std::string_view what) {
  if (remaining() < count)
    throw error("unexpected end of file in binary data, expected " + std::string(what));
  std::memcpy(out, text_.data() + position_, count);
  position_ += count;
}

bool TextCursor::skip_past(std::string_view marker) {
  const std::size_t found = text_.find(marker, position_);
  if (found == std::string_view::npos) return false;
  for (std::size_t index = position_; index < found; ++index)
    if (text_[index] == '\n') ++line_;
  position_ = found + marker.size();
  return true;
}

bool parse_integer(std::string_view token, long long& value) {
  const char* first = token.data();
  const char* last = first + token.size();
  if (first != last && *first == '+') ++first;
  const auto [end, code] = std::from_chars(first, last, value);
  return code == std::errc() && end == last && first != last;
}

bool parse_real(std::string_view token, double& value) {
  const char* first = token.data();
  const char* last = first + token.size();
  if (first != last && *first == '+') ++first;
  const auto [end, code] = std::from_chars(first, last, value);
  return code == std::errc() && end == last && first != last && std::isfinite(value);
}

std::string quoted(std::string_view token) {
  constexpr std::size_t longest = 32;
  if (token.size() > longest) return "'" + std::string(token.substr(0, longest)) + "...'";
  return "'" + std::string(token) + "'";
}

std::size_t split(std::string_view line, std::string_view* tokens, std::size_t capacity) {
  std::size_t count = 0;
  std::size_t position = 0;
  while (true) {
    while (position < line.size() && is_blank(line[position])) ++position;
    if (position >= line.size()) return count;
    const std::size_t start = position;
    while (position < line.size() && !is_blank(line[position])) ++position;
    if (count == capacity) return capacity + 1;
    tokens[count++] = line.substr(start, position - start);
  }
}

}  // namespace mixmesh::io_detail
