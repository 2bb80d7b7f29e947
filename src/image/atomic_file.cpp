#include "image/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace tuneray {

namespace fs = std::filesystem;

namespace {

// The hidden temporary name the content of `path` is written to first.
std::string temporary_path_for(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const fs::path p(path);
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on "." + std::string.
  std::string name = ".";
  name += p.filename().string();
  name += ".partial-";
  name += std::to_string(getpid());
  name += '-';
  name += std::to_string(counter++);
  return (p.parent_path() / name).string();
}

void rename_over(const std::string& from, const std::string& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec) {
    fs::remove(from, ec);
    throw std::runtime_error("cannot write " + to + ": " + ec.message());
  }
}

}  // namespace

void replace_file(const std::string& path, const std::function<void(const std::string&)>& write) {
  const std::string temporary = temporary_path_for(path);
  try {
    write(temporary);
  } catch (...) {
    std::error_code ec;
    fs::remove(temporary, ec);
    throw;
  }
  rename_over(temporary, path);
}

void write_text_file(const std::string& path, const std::string& text) {
  ReplacingFile f(path);
  f << text;
  f.commit();
}

ReplacingFile::ReplacingFile(std::string path, std::ios::openmode mode)
    : path_(std::move(path)), temporary_(temporary_path_for(path_)) {
  out_.open(temporary_, mode | std::ios::out | std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot write " + path_);
}

ReplacingFile::~ReplacingFile() {
  if (committed_) return;
  out_.close();
  std::error_code ec;
  fs::remove(temporary_, ec);
}

void ReplacingFile::commit() {
  out_.flush();
  const bool written = static_cast<bool>(out_);
  out_.close();
  if (!written || out_.fail()) {
    std::error_code ec;
    fs::remove(temporary_, ec);
    committed_ = true;
    throw std::runtime_error("cannot write " + path_ + " (disk full or file system error)");
  }
  committed_ = true;
  rename_over(temporary_, path_);
}

}  // namespace tuneray
