#include "scene/gltf_check.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "scene/load.h"

namespace tuneray {

namespace {

uint32_t read_u32(const std::string& data, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(data[at + i]);
  return v;
}

}  // namespace

void check_gltf_file(const std::string& path) {
  auto fail = [&](const std::string& what) {
    throw SceneError(path + ": malformed glTF: " + what);
  };
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open file");
  const std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};

  std::string json = data;
  if (data.compare(0, 4, "glTF") == 0) {
    // GLB: magic, version, total length; then chunks of (length, type, bytes), JSON first.
    if (data.size() < 20) fail("GLB shorter than its header");
    if (read_u32(data, 4) != 2)
      fail("GLB version " + std::to_string(read_u32(data, 4)) + ", not 2");
    if (read_u32(data, 8) != data.size())
      fail("GLB header says " + std::to_string(read_u32(data, 8)) + " bytes, the file has " +
           std::to_string(data.size()));
    const uint32_t json_length = read_u32(data, 12);
    if (std::memcmp(data.data() + 16, "JSON", 4) != 0) fail("GLB's first chunk is not JSON");
    if (json_length > data.size() - 20) fail("GLB's JSON chunk runs past the end of the file");
    json = data.substr(20, json_length);
  }
  nlohmann::json doc = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded()) fail("the JSON does not parse");
  if (!doc.is_object()) fail("the JSON is not an object");
}

}  // namespace tuneray
