#include "fuzz_files.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace tuneray::fuzz {

namespace {

struct Folder {
  std::filesystem::path path;
  Folder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "tuneray-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path = pattern;
  }
  ~Folder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

Folder& folder() {
  static Folder instance;
  return instance;
}

}  // namespace

std::string one_texel_pfm() {
  const float texel[3] = {0.5f, 0.25f, 1.0f};
  std::string pfm = "PF\n1 1\n-1.0\n";
  pfm.append(reinterpret_cast<const char*>(texel), sizeof texel);
  return pfm;
}

void remove_file(const std::string& name) {
  std::error_code ec;
  std::filesystem::remove(folder().path / name, ec);
}

std::string write_file(const std::string& name, std::string_view bytes) {
  const std::string path = (folder().path / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write fuzz input " + path);
  return path;
}

}  // namespace tuneray::fuzz
