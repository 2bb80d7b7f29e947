#include "tuner/token_io.h"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace tuneray::tuner {

namespace {
constexpr std::string_view kEmptyWord = "\x01";
}

TokenWriter& TokenWriter::put(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%a", value);
  separate();
  text_ += buffer;
  return *this;
}

TokenWriter& TokenWriter::put(int64_t value) {
  separate();
  text_ += std::to_string(value);
  return *this;
}

TokenWriter& TokenWriter::put_word(std::string_view word) {
  separate();
  text_ += word.empty() ? kEmptyWord : word;
  return *this;
}

TokenWriter& TokenWriter::put(const std::vector<double>& values) {
  put(static_cast<int64_t>(values.size()));
  for (double v : values) put(v);
  return *this;
}

TokenWriter& TokenWriter::put(const Rng& rng) {
  for (uint64_t word : rng.state()) {
    separate();
    text_ += std::to_string(word);
  }
  return *this;
}

std::string TokenReader::next_token() {
  while (position_ < text_.size() && text_[position_] == ' ') ++position_;
  if (position_ >= text_.size()) throw std::runtime_error("serialised tuner state ends early");
  const size_t start = position_;
  while (position_ < text_.size() && text_[position_] != ' ') ++position_;
  return std::string(text_.substr(start, position_ - start));
}

double TokenReader::get_double() {
  const std::string token = next_token();
  char* end = nullptr;
  const double value = std::strtod(token.c_str(), &end);
  if (end == token.c_str() || *end != '\0') {
    throw std::runtime_error("bad number in serialised tuner state: " + token);
  }
  return value;
}

int64_t TokenReader::get_int() {
  const std::string token = next_token();
  char* end = nullptr;
  const long long value = std::strtoll(token.c_str(), &end, 10);
  if (end == token.c_str() || *end != '\0') {
    throw std::runtime_error("bad integer in serialised tuner state: " + token);
  }
  return value;
}

std::string TokenReader::get_word() {
  std::string word = next_token();
  return word == kEmptyWord ? std::string() : word;
}

std::vector<double> TokenReader::get_doubles() {
  const int64_t count = get_int();
  if (count < 0) throw std::runtime_error("negative length in serialised tuner state");
  std::vector<double> values(static_cast<size_t>(count));
  for (double& v : values) v = get_double();
  return values;
}

void TokenReader::get(Rng& rng) {
  std::array<uint64_t, 4> state{};
  for (uint64_t& word : state) {
    const std::string token = next_token();
    char* end = nullptr;
    word = std::strtoull(token.c_str(), &end, 10);
    if (end == token.c_str() || *end != '\0') {
      throw std::runtime_error("bad generator state in serialised tuner state");
    }
  }
  rng.set_state(state);
}

}  // namespace tuneray::tuner
