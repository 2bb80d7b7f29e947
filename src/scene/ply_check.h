// A structural check of PLY files before assimp sees them: assimp 5.2 hangs on a header that
// never ends and crashes on truncated binary bodies, and bad input must never do either.
#pragma once

#include <string>

namespace tuneray {

// Throws SceneError naming `path` when the header is malformed or, for binary files, when the
// body is shorter than its elements require or a face index exceeds the vertex count.
void check_ply_file(const std::string& path);

}  // namespace tuneray
