// A look at an EXR file's header before OpenEXR reads it. OpenEXR 3.1 allocates what the header
// says (an attribute's size, one offset per chunk of the data window) before it finds the file
// too short: a few hundred hostile bytes made it allocate 1.6 GB and, under the sanitizers, take
// more than 10 s (fuzz/README.md). The check reads the magic number, the version, every
// attribute's name, type and size, and, for single-part scanline and tiled images, the data
// window and compression, and refuses a file whose header promises more than its bytes hold.
#pragma once

#include <cstdint>
#include <istream>
#include <string>

namespace tuneray::detail {

// Reads the header from `in` (positioned at the file's start; `file_size` bytes in all) and
// skips over attribute values it does not need. Throws ImageError naming `path` and the problem.
void check_exr_header(const std::string& path, std::istream& in, uint64_t file_size);
// The same for the file at `path`.
void check_exr_header(const std::string& path);

}  // namespace tuneray::detail
