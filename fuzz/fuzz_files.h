// Fuzz inputs reach our loaders the way users' files do: as files on disk. Each harness writes
// the input's bytes into a private temporary folder (one per process, removed at exit) and hands
// the path to the loader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace tuneray::fuzz {

// Writes `bytes` to `name` in the process's fuzz folder and returns the full path.
std::string write_file(const std::string& name, std::string_view bytes);
// A valid 1x1 PFM (a texture or environment map that inputs can name).
std::string one_texel_pfm();

// Removes `name` from the fuzz folder if it is there.
void remove_file(const std::string& name);

inline std::string_view as_view(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// The input's first byte picks one of `count` variants (file formats); the rest is the content.
struct Selected {
  size_t variant = 0;
  std::string_view rest;
};
inline Selected select(const uint8_t* data, size_t size, size_t count) {
  if (size == 0) return {0, {}};
  return {data[0] % count, as_view(data + 1, size - 1)};
}

}  // namespace tuneray::fuzz
