// Internal: a zero-copy tokenizer / line reader over an in-memory text that tracks 1-based line
// numbers, and std::from_chars based number parsing (no iostreams, no locale) shared by the text
// mesh readers (STL ASCII, OBJ, PLY ASCII, OFF).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace interfere::io_detail {

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}
inline bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

class TextReader {
 public:
  explicit TextReader(std::string_view text, std::int64_t first_line = 1)
      : text_(text), line_(first_line), token_line_(first_line) {}

  /// Next whitespace-separated token, crossing line ends; an empty view at the end of the text.
  std::string_view token() {
    const std::size_t n = text_.size();
    while (pos_ < n && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    token_line_ = line_;
    const std::size_t start = pos_;
    while (pos_ < n && !is_space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  /// Next line without its "\n" or "\r\n"; false at the end of the text. line() is its number.
  bool next_line(std::string_view& out) {
    if (pos_ >= text_.size()) return false;
    token_line_ = line_;
    const std::size_t start = pos_;
    const std::size_t nl = text_.find('\n', pos_);
    std::size_t end = nl == std::string_view::npos ? text_.size() : nl;
    if (nl == std::string_view::npos) {
      pos_ = text_.size();
    } else {
      pos_ = nl + 1;
      ++line_;
    }
    if (end > start && text_[end - 1] == '\r') --end;
    out = text_.substr(start, end - start);
    return true;
  }

  /// Skips the rest of the current line (including its newline).
  void skip_line() {
    const std::size_t nl = text_.find('\n', pos_);
    if (nl == std::string_view::npos) {
      pos_ = text_.size();
    } else {
      pos_ = nl + 1;
      ++line_;
    }
  }

  /// Line of the last token or line returned; at the end of the text, the last line of the text.
  std::int64_t line() const { return token_line_; }
  /// Line of the current position, clamped to the last line that has content (for end-of-file
  /// errors).
  std::int64_t end_line() const {
    std::int64_t l = line_;
    if (pos_ >= text_.size() && !text_.empty() && text_.back() == '\n' && l > 1) --l;
    return l;
  }
  std::size_t position() const { return pos_; }
  bool at_end() const { return pos_ >= text_.size(); }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::int64_t line_;        // line of pos_: 1 + newlines before it
  std::int64_t token_line_;  // line of the last token / line returned
};

/// Splits one line into whitespace-separated tokens.
class LineTokens {
 public:
  explicit LineTokens(std::string_view line) : s_(line) {}
  std::string_view next() {
    while (p_ < s_.size() && is_space(s_[p_])) ++p_;
    const std::size_t start = p_;
    while (p_ < s_.size() && !is_space(s_[p_])) ++p_;
    return s_.substr(start, p_ - start);
  }
  bool done() {
    while (p_ < s_.size() && is_space(s_[p_])) ++p_;
    return p_ >= s_.size();
  }

 private:
  std::string_view s_;
  std::size_t p_ = 0;
};

/// Parses the whole token as a double (std::from_chars; a leading '+' is accepted). NaN and Inf
/// spellings parse; callers decide whether they are allowed.
bool parse_double(std::string_view token, double& out);
/// Parses the whole token as a signed 64-bit integer (a leading '+' is accepted).
bool parse_int(std::string_view token, std::int64_t& out);

/// ASCII case-insensitive comparison.
bool iequals(std::string_view a, std::string_view b);
/// Token quoted for an error message, shortened to 40 characters, control bytes escaped.
std::string quoted(std::string_view token);
/// Drops a leading UTF-8 byte order mark (some Windows exporters write one before text formats).
inline std::string_view strip_bom(std::string_view text) {
  return text.substr(0, 3) == "\xEF\xBB\xBF" ? text.substr(3) : text;
}
/// Removes a '#' comment and surrounding blanks.
std::string_view strip_comment(std::string_view line);

}  // namespace interfere::io_detail
