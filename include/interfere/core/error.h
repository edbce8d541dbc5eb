// One error channel for the whole library (ARCHITECTURE.md): input errors are returned as values
// carrying the file, the line or byte offset and the reason; inner loops never throw or exit.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <variant>

namespace interfere {

struct Error {
  std::string file;          ///< file the error is about; empty when not about a file
  std::int64_t line = -1;    ///< 1-based line for text formats, -1 when not applicable
  std::int64_t byte = -1;    ///< 0-based byte offset for binary formats, -1 when not applicable
  std::string reason;

  /// "file:line: reason", "file: byte N: reason" or "reason".
  std::string message() const;
};

/// v as printf's %g (6 significant digits): the numbers of reasons, warnings and listings.
std::string short_number(double v);

/// A value or an Error (std::expected is C++23; this is the subset we need).
template <class T>
class Expected {
 public:
  Expected(T value) : v_(std::move(value)) {}
  Expected(Error error) : v_(std::move(error)) {}

  bool has_value() const { return v_.index() == 0; }
  explicit operator bool() const { return has_value(); }
  T& value() & { return std::get<0>(v_); }
  const T& value() const& { return std::get<0>(v_); }
  T&& value() && { return std::get<0>(std::move(v_)); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  const Error& error() const { return std::get<1>(v_); }

 private:
  std::variant<T, Error> v_;
};

/// Success or an Error.
class Status {
 public:
  Status() = default;
  Status(Error error) : error_(std::move(error)), ok_(false) {}
  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const { return error_; }

 private:
  Error error_;
  bool ok_ = true;
};

}  // namespace interfere
