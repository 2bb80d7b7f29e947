// A structural check of glTF files before assimp sees them: assimp 5.2 leaks memory on GLB
// containers whose header or chunk lengths are wrong and on JSON it cannot parse (found by
// fuzz/fuzz_mesh), and bad input must never leak, hang or crash.
#pragma once

#include <string>

namespace tuneray {

// Throws SceneError naming `path` when a .glb container is malformed (magic, version 2, total
// length, a first chunk of type JSON within the file) or when the JSON of a .gltf or .glb does
// not parse as a JSON object.
void check_gltf_file(const std::string& path);

}  // namespace tuneray
