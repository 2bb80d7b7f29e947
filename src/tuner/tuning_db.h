// The tuning database: SQLite file holding everything a tuner learnt, so that a restarted
// program resumes where it stopped.
//
// Layout (schema version kSchemaVersion, stored in table `meta` with format "tuneray-tuner"):
//   signatures(id, tuning_key, hardware, space, indicators)  one row per tuning key + hardware
//       signature; `space`/`indicators` describe the domains and must match on reopening.
//   states(id, signature_id, indicators)            raw indicator values (exact hex floats)
//   configs(id, signature_id, text)                 Config::to_string(), unique per signature
//   samples(id, signature_id, state_id, config_id, cost, failed, time)
//   sample_extras(sample_id, name, value)           named timings such as build_ms, render_ms
//   searches(signature_id, state_id, state)         Nelder-Mead state per state (simplex,
//       phase, repeats, generator)
//   candidates(id, signature_id, config_id)         configurations past searches converged to
//   tuner_state(signature_id, state)                policy: current state, mode, generator
//   models(signature_id, last_sample_id, state)     θ and RBF centres, with the last sample
//       folded into them; later samples are replayed into θ on opening.
// Several tuning keys ("bvh/render", "bvh/total") and machines share one file.
//
// Durability: journal_mode=WAL, synchronous=NORMAL. Every report is one transaction; when it
// commits the data is in the WAL file (in the OS page cache), so killing the process, even with
// SIGKILL, loses nothing whose report returned. A power loss or OS crash may lose the last
// transactions (never corrupts the file); synchronous=FULL would close that gap at the price of
// an fsync per report.
//
// Safety: a file that is not SQLite, or an SQLite file without our `meta` table (a foreign
// database), or a newer schema version, throws TuningDbError; the file is never modified then.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace tuneray::tuner {

class TuningDbError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using Extras = std::map<std::string, double>;

struct StoredState {
  int64_t id;
  std::vector<double> indicators;
};

struct StoredSample {
  int64_t id;
  int64_t state_id;
  int64_t config_id;
  std::string config;  // Config::to_string()
  double cost;         // +infinity for a failure
  Extras extras;
};

class TuningDb {
 public:
  static constexpr int kSchemaVersion = 1;

  // Opens or creates `path`. Throws TuningDbError (see above).
  explicit TuningDb(const std::string& path);
  ~TuningDb();
  TuningDb(const TuningDb&) = delete;
  TuningDb& operator=(const TuningDb&) = delete;

  // Returns the id of (tuning_key, hardware), creating it if needed. Throws TuningDbError if
  // it exists with another space or indicator description.
  int64_t open_signature(const std::string& tuning_key, const std::string& hardware,
                         const std::string& space, const std::string& indicators);

  // Id of an existing (tuning_key, hardware), nullopt if the file has none.
  std::optional<int64_t> find_signature(const std::string& tuning_key, const std::string& hardware);

  // Every machine that recorded samples under `tuning_key` (rows without samples left out), in
  // order of creation: a study checks that it does not mix machines' measurements.
  struct HardwareSamples {
    int64_t signature;
    std::string hardware;
    int64_t samples;
  };
  std::vector<HardwareSamples> hardware_with_samples(const std::string& tuning_key);

  int64_t add_state(int64_t signature, const std::vector<double>& indicators);
  std::vector<StoredState> states(int64_t signature);
  // Id of a configuration text, inserted if new.
  int64_t config_id(int64_t signature, const std::string& text);
  std::string config_text(int64_t config_id);

  // Samples of a signature with id > after_id, oldest first.
  std::vector<StoredSample> samples(int64_t signature, int64_t after_id = 0);
  int64_t add_sample(int64_t signature, int64_t state_id, int64_t config_id, double cost,
                     const Extras& extras);

  void put_search(int64_t signature, int64_t state_id, const std::string& state);
  std::vector<std::pair<int64_t, std::string>> searches(int64_t signature);
  void add_candidate(int64_t signature, int64_t config_id);
  std::vector<int64_t> candidates(int64_t signature);
  void put_tuner_state(int64_t signature, const std::string& state);
  std::optional<std::string> tuner_state(int64_t signature);
  void put_model(int64_t signature, int64_t last_sample_id, const std::string& state);
  std::optional<std::pair<int64_t, std::string>> model(int64_t signature);

  // One row per sample: sample_id,tuning_key,hardware,state_id,indicators,config,cost,failed,
  // extras,time. Fields with commas are quoted. signature = 0 exports every signature.
  void export_csv(std::ostream& out, int64_t signature = 0);

  // Groups writes into one atomic transaction; rolls back if destroyed without commit().
  class Transaction {
   public:
    explicit Transaction(TuningDb& db);
    ~Transaction();
    void commit();

   private:
    TuningDb& db_;
    bool done_ = false;
  };

  const std::string& path() const { return path_; }

 private:
  class Statement;
  Statement& statement(const char* sql);
  void execute(const char* sql);
  void check_or_create_schema();
  [[noreturn]] void fail(const std::string& what) const;

  std::string path_;
  sqlite3* handle_ = nullptr;
  std::unordered_map<const char*, std::unique_ptr<Statement>> statements_;
};

}  // namespace tuneray::tuner
