// Limits checked before a render starts: more threads than the machine has, images that do not
// fit in memory.
#pragma once

namespace tuneray {

// `requested` threads (0 = all cores) clamped to the machine's hardware threads; a note on
// stderr when clamped.
int clamp_threads(int requested);

// Throws std::invalid_argument with both figures when a width x height render would need more
// memory than the machine has available (MemAvailable in /proc/meminfo; no check where that
// cannot be read).
void check_render_memory(int width, int height);

}  // namespace tuneray
