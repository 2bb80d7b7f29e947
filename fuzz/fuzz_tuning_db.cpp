// The tuning database as `tune` opens it: the input is the database file itself (random bytes,
// or a valid database with mutations). Opening either refuses the file with an error or gives a
// tuner that can suggest and record; nothing may crash or run away.
#include <cstdint>
#include <exception>
#include <string>

#include "fuzz_files.h"
#include "tuner/hybrid_tuner.h"
#include "tuning/bvh_space.h"
#include "tuning/tuner_state.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tuneray;
  const std::string path = fuzz::write_file("tuning.db", fuzz::as_view(data, size));
  // SQLite keeps its journal beside the file; a stale one from the previous input must not
  // leak into this one.
  fuzz::remove_file("tuning.db-wal");
  fuzz::remove_file("tuning.db-shm");
  try {
    tuner::TunerOptions options;
    options.db_path = path;
    options.tuning_key = "backend+bvh/render/32x24/1spp/3b/wavefront";  // the seed's key
    tuner::HybridTuner tuner(make_backend_space(), make_indicator_schema(), options);
    tuner::State state(make_indicator_schema().size(), 0.5);
    tuner::Config c = tuner.suggest(state);
    tuner.report(c, 0.01);
  } catch (const std::exception&) {
  }
  return 0;
}
