// Whitespace-separated token streams used to serialise search and model state to the database.
//
// Doubles are written as hexadecimal floats so that a value read back is bit-identical to the
// one written: a resumed search must make exactly the decisions the uninterrupted one makes.
#pragma once

#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "tuner/rng.h"

namespace tuneray::tuner {

class TokenWriter {
 public:
  TokenWriter& put(double value);
  TokenWriter& put(int64_t value);
  TokenWriter& put(int value) { return put(static_cast<int64_t>(value)); }
  TokenWriter& put(bool value) { return put(static_cast<int64_t>(value ? 1 : 0)); }
  // `word` must not contain whitespace; an empty word is written as a placeholder.
  TokenWriter& put_word(std::string_view word);
  TokenWriter& put(const std::vector<double>& values);
  TokenWriter& put(const Rng& rng);
  const std::string& str() const { return text_; }

 private:
  void separate() {
    if (!text_.empty()) text_ += ' ';
  }
  std::string text_;
};

// Throws std::runtime_error when the text ends early or a token does not parse.
class TokenReader {
 public:
  explicit TokenReader(std::string_view text) : text_(text) {}
  double get_double();
  int64_t get_int();
  bool get_bool() { return get_int() != 0; }
  std::string get_word();
  std::vector<double> get_doubles();
  void get(Rng& rng);

 private:
  std::string next_token();
  std::string_view text_;
  size_t position_ = 0;
};

}  // namespace tuneray::tuner
