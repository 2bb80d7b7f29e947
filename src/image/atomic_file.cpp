#include "image/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace tuneray {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPartialMark = ".partial-";

// The hidden temporary name the content of `path` is written to first: ".NAME.partial-PID-N".
std::string temporary_path_for(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const fs::path p(path);
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on "." + std::string.
  std::string name = ".";
  name += p.filename().string();
  name += kPartialMark;
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

void remove_stale_temporaries(const std::string& dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const size_t mark = name.find(kPartialMark);
    if (name[0] != '.' || mark == std::string::npos) continue;
    const long pid = std::strtol(name.c_str() + mark + std::strlen(kPartialMark), nullptr, 10);
    if (pid <= 0 || pid == ::getpid() || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM)
      continue;
    std::error_code ignored;  // another run may have removed it first
    fs::remove(entry.path(), ignored);
  }
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
