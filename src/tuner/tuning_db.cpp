#include "tuner/tuning_db.h"

#include <sqlite3.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "tuner/token_io.h"

namespace tuneray::tuner {

namespace {

constexpr const char* kFormat = "tuneray-tuner";

constexpr const char* kSchema = R"sql(
CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE signatures(id INTEGER PRIMARY KEY, tuning_key TEXT NOT NULL, hardware TEXT NOT NULL,
  space TEXT NOT NULL, indicators TEXT NOT NULL, created REAL NOT NULL,
  UNIQUE(tuning_key, hardware));
CREATE TABLE states(id INTEGER PRIMARY KEY, signature_id INTEGER NOT NULL REFERENCES signatures(id),
  indicators TEXT NOT NULL);
CREATE TABLE configs(id INTEGER PRIMARY KEY, signature_id INTEGER NOT NULL REFERENCES signatures(id),
  text TEXT NOT NULL, UNIQUE(signature_id, text));
CREATE TABLE samples(id INTEGER PRIMARY KEY, signature_id INTEGER NOT NULL REFERENCES signatures(id),
  state_id INTEGER NOT NULL REFERENCES states(id), config_id INTEGER NOT NULL REFERENCES configs(id),
  cost REAL, failed INTEGER NOT NULL, time REAL NOT NULL);
CREATE INDEX samples_by_signature ON samples(signature_id, id);
CREATE TABLE sample_extras(sample_id INTEGER NOT NULL REFERENCES samples(id), name TEXT NOT NULL,
  value REAL NOT NULL, PRIMARY KEY(sample_id, name));
CREATE TABLE searches(signature_id INTEGER NOT NULL, state_id INTEGER NOT NULL, state TEXT NOT NULL,
  PRIMARY KEY(signature_id, state_id));
CREATE TABLE candidates(id INTEGER PRIMARY KEY, signature_id INTEGER NOT NULL,
  config_id INTEGER NOT NULL REFERENCES configs(id));
CREATE TABLE tuner_state(signature_id INTEGER PRIMARY KEY, state TEXT NOT NULL);
CREATE TABLE models(signature_id INTEGER PRIMARY KEY, last_sample_id INTEGER NOT NULL,
  state TEXT NOT NULL);
)sql";

double now_seconds() {
  using namespace std::chrono;
  return duration<double>(system_clock::now().time_since_epoch()).count();
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace

// A prepared statement, reset and with its bindings cleared on every use.
class TuningDb::Statement {
 public:
  Statement(TuningDb& db, const char* sql) : db_(db) {
    if (sqlite3_prepare_v2(db.handle_, sql, -1, &stmt_, nullptr) != SQLITE_OK) {
      db.fail("cannot prepare statement");
    }
  }
  ~Statement() { sqlite3_finalize(stmt_); }

  Statement& reset() {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
    return *this;
  }
  Statement& bind(int index, int64_t value) {
    sqlite3_bind_int64(stmt_, index, value);
    return *this;
  }
  Statement& bind(int index, double value) {
    if (std::isfinite(value)) {
      sqlite3_bind_double(stmt_, index, value);
    } else {
      sqlite3_bind_null(stmt_, index);
    }
    return *this;
  }
  Statement& bind(int index, const std::string& value) {
    sqlite3_bind_text(stmt_, index, value.data(), static_cast<int>(value.size()), SQLITE_TRANSIENT);
    return *this;
  }
  // True while there is a row.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    const std::string message = sqlite3_errmsg(db_.handle_);
    sqlite3_reset(stmt_);
    db_.fail(message);
  }
  void run() {
    while (step()) {
    }
  }
  int64_t integer(int column) const { return sqlite3_column_int64(stmt_, column); }
  double real(int column) const {
    return sqlite3_column_type(stmt_, column) == SQLITE_NULL
               ? std::numeric_limits<double>::infinity()
               : sqlite3_column_double(stmt_, column);
  }
  std::string text(int column) const {
    const auto* p = sqlite3_column_text(stmt_, column);
    return p ? std::string(reinterpret_cast<const char*>(p)) : std::string();
  }

 private:
  TuningDb& db_;
  sqlite3_stmt* stmt_ = nullptr;
};

TuningDb::TuningDb(const std::string& path) : path_(path) {
  if (sqlite3_open_v2(path.c_str(), &handle_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE,
                      nullptr) != SQLITE_OK) {
    const std::string message = handle_ ? sqlite3_errmsg(handle_) : "out of memory";
    sqlite3_close(handle_);
    handle_ = nullptr;
    throw TuningDbError("tuning database " + path + ": cannot open: " + message);
  }
  try {
    sqlite3_busy_timeout(handle_, 5000);
    check_or_create_schema();
    execute("PRAGMA journal_mode=WAL");
    execute("PRAGMA synchronous=NORMAL");
  } catch (...) {
    statements_.clear();
    sqlite3_close(handle_);
    handle_ = nullptr;
    throw;
  }
}

TuningDb::~TuningDb() {
  statements_.clear();
  if (handle_) sqlite3_close(handle_);
}

void TuningDb::fail(const std::string& what) const {
  throw TuningDbError("tuning database " + path_ + ": " + what +
                      (handle_ ? std::string(" (") + sqlite3_errmsg(handle_) + ")" : ""));
}

void TuningDb::execute(const char* sql) {
  char* error = nullptr;
  if (sqlite3_exec(handle_, sql, nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string message = error ? error : "unknown error";
    sqlite3_free(error);
    throw TuningDbError("tuning database " + path_ + ": " + message);
  }
}

TuningDb::Statement& TuningDb::statement(const char* sql) {
  auto& slot = statements_[sql];
  if (!slot) slot = std::make_unique<Statement>(*this, sql);
  return slot->reset();
}

void TuningDb::check_or_create_schema() {
  // Reading sqlite_master first fails cleanly on a file that is not SQLite or is corrupt,
  // before anything is written to it.
  int64_t tables = 0;
  {
    Statement count(*this, "SELECT count(*) FROM sqlite_master");
    if (count.step()) tables = count.integer(0);
  }
  if (tables == 0) {
    execute("BEGIN IMMEDIATE");
    execute(kSchema);
    Statement meta(*this, "INSERT INTO meta(key, value) VALUES (?1, ?2)");
    meta.bind(1, std::string("format")).bind(2, std::string(kFormat)).run();
    meta.reset().bind(1, std::string("schema_version"));
    meta.bind(2, std::to_string(kSchemaVersion)).run();
    execute("COMMIT");
    return;
  }
  std::string format;
  std::string version;
  {
    Statement has_meta(*this,
                       "SELECT count(*) FROM sqlite_master WHERE type='table' AND "
                       "name='meta'");
    if (!has_meta.step() || has_meta.integer(0) == 0) {
      throw TuningDbError("tuning database " + path_ +
                          ": an SQLite database of another program (no tuner meta table); "
                          "refusing to modify it");
    }
    Statement meta(*this, "SELECT key, value FROM meta");
    while (meta.step()) {
      if (meta.text(0) == "format") format = meta.text(1);
      if (meta.text(0) == "schema_version") version = meta.text(1);
    }
  }
  if (format != kFormat) {
    throw TuningDbError("tuning database " + path_ + ": format '" + format + "' is not '" +
                        kFormat + "'; refusing to modify it");
  }
  if (version != std::to_string(kSchemaVersion)) {
    throw TuningDbError("tuning database " + path_ + ": schema version " + version +
                        ", this program understands " + std::to_string(kSchemaVersion));
  }
}

int64_t TuningDb::open_signature(const std::string& tuning_key, const std::string& hardware,
                                 const std::string& space, const std::string& indicators) {
  auto& find =
      statement("SELECT id, space, indicators FROM signatures WHERE tuning_key=?1 AND hardware=?2");
  find.bind(1, tuning_key).bind(2, hardware);
  if (find.step()) {
    const int64_t id = find.integer(0);
    if (find.text(1) != space || find.text(2) != indicators) {
      throw TuningDbError("tuning database " + path_ + ": tuning key '" + tuning_key +
                          "' was recorded with another parameter space or indicator schema; "
                          "use another tuning key or file");
    }
    find.run();
    return id;
  }
  auto& insert = statement(
      "INSERT INTO signatures(tuning_key, hardware, space, indicators, created) "
      "VALUES (?1, ?2, ?3, ?4, ?5)");
  insert.bind(1, tuning_key).bind(2, hardware).bind(3, space).bind(4, indicators);
  insert.bind(5, now_seconds()).run();
  return sqlite3_last_insert_rowid(handle_);
}

std::optional<int64_t> TuningDb::find_signature(const std::string& tuning_key,
                                                const std::string& hardware) {
  auto& find = statement("SELECT id FROM signatures WHERE tuning_key=?1 AND hardware=?2");
  find.bind(1, tuning_key).bind(2, hardware);
  if (!find.step()) return std::nullopt;
  const int64_t id = find.integer(0);
  find.run();
  return id;
}

std::vector<TuningDb::HardwareSamples> TuningDb::hardware_with_samples(
    const std::string& tuning_key) {
  auto& find = statement(
      "SELECT g.id, g.hardware, COUNT(s.id) FROM signatures g JOIN samples s ON "
      "s.signature_id=g.id WHERE g.tuning_key=?1 GROUP BY g.id ORDER BY g.id");
  find.bind(1, tuning_key);
  std::vector<HardwareSamples> rows;
  while (find.step()) rows.push_back({find.integer(0), find.text(1), find.integer(2)});
  return rows;
}

int64_t TuningDb::add_state(int64_t signature, const std::vector<double>& indicators) {
  TokenWriter text;
  text.put(indicators);
  auto& insert = statement("INSERT INTO states(signature_id, indicators) VALUES (?1, ?2)");
  insert.bind(1, signature).bind(2, text.str()).run();
  return sqlite3_last_insert_rowid(handle_);
}

std::vector<StoredState> TuningDb::states(int64_t signature) {
  std::vector<StoredState> result;
  auto& query = statement("SELECT id, indicators FROM states WHERE signature_id=?1 ORDER BY id");
  query.bind(1, signature);
  while (query.step()) {
    result.push_back({query.integer(0), TokenReader(query.text(1)).get_doubles()});
  }
  return result;
}

int64_t TuningDb::config_id(int64_t signature, const std::string& text) {
  auto& find = statement("SELECT id FROM configs WHERE signature_id=?1 AND text=?2");
  find.bind(1, signature).bind(2, text);
  if (find.step()) {
    const int64_t id = find.integer(0);
    find.run();
    return id;
  }
  auto& insert = statement("INSERT INTO configs(signature_id, text) VALUES (?1, ?2)");
  insert.bind(1, signature).bind(2, text).run();
  return sqlite3_last_insert_rowid(handle_);
}

std::string TuningDb::config_text(int64_t config_id) {
  auto& query = statement("SELECT text FROM configs WHERE id=?1");
  query.bind(1, config_id);
  if (!query.step()) fail("no configuration " + std::to_string(config_id));
  std::string text = query.text(0);
  query.run();
  return text;
}

std::vector<StoredSample> TuningDb::samples(int64_t signature, int64_t after_id) {
  std::vector<StoredSample> result;
  auto& query = statement(
      "SELECT s.id, s.state_id, s.config_id, c.text, s.cost, s.failed FROM samples s "
      "JOIN configs c ON c.id = s.config_id WHERE s.signature_id=?1 AND s.id>?2 ORDER BY s.id");
  query.bind(1, signature).bind(2, after_id);
  std::unordered_map<int64_t, size_t> index;
  while (query.step()) {
    const double cost = query.integer(5) ? std::numeric_limits<double>::infinity() : query.real(4);
    index[query.integer(0)] = result.size();
    result.push_back(
        {query.integer(0), query.integer(1), query.integer(2), query.text(3), cost, {}});
  }
  auto& extras = statement(
      "SELECT e.sample_id, e.name, e.value FROM sample_extras e JOIN samples s ON s.id = "
      "e.sample_id WHERE s.signature_id=?1 AND s.id>?2");
  extras.bind(1, signature).bind(2, after_id);
  while (extras.step()) {
    const auto it = index.find(extras.integer(0));
    if (it != index.end()) result[it->second].extras[extras.text(1)] = extras.real(2);
  }
  return result;
}

int64_t TuningDb::add_sample(int64_t signature, int64_t state_id, int64_t config_id, double cost,
                             const Extras& extras) {
  auto& insert = statement(
      "INSERT INTO samples(signature_id, state_id, config_id, cost, failed, time) "
      "VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
  insert.bind(1, signature).bind(2, state_id).bind(3, config_id).bind(4, cost);
  insert.bind(5, static_cast<int64_t>(std::isfinite(cost) ? 0 : 1)).bind(6, now_seconds()).run();
  const int64_t id = sqlite3_last_insert_rowid(handle_);
  for (const auto& [name, value] : extras) {
    auto& extra = statement("INSERT INTO sample_extras(sample_id, name, value) VALUES (?1,?2,?3)");
    extra.bind(1, id).bind(2, name).bind(3, value).run();
  }
  return id;
}

void TuningDb::put_search(int64_t signature, int64_t state_id, const std::string& state) {
  auto& upsert = statement(
      "INSERT INTO searches(signature_id, state_id, state) VALUES (?1, ?2, ?3) "
      "ON CONFLICT(signature_id, state_id) DO UPDATE SET state=excluded.state");
  upsert.bind(1, signature).bind(2, state_id).bind(3, state).run();
}

std::vector<std::pair<int64_t, std::string>> TuningDb::searches(int64_t signature) {
  std::vector<std::pair<int64_t, std::string>> result;
  auto& query =
      statement("SELECT state_id, state FROM searches WHERE signature_id=?1 ORDER BY state_id");
  query.bind(1, signature);
  while (query.step()) result.emplace_back(query.integer(0), query.text(1));
  return result;
}

void TuningDb::add_candidate(int64_t signature, int64_t config_id) {
  auto& insert = statement("INSERT INTO candidates(signature_id, config_id) VALUES (?1, ?2)");
  insert.bind(1, signature).bind(2, config_id).run();
}

std::vector<int64_t> TuningDb::candidates(int64_t signature) {
  std::vector<int64_t> result;
  auto& query = statement("SELECT config_id FROM candidates WHERE signature_id=?1 ORDER BY id");
  query.bind(1, signature);
  while (query.step()) result.push_back(query.integer(0));
  return result;
}

void TuningDb::put_tuner_state(int64_t signature, const std::string& state) {
  auto& upsert = statement(
      "INSERT INTO tuner_state(signature_id, state) VALUES (?1, ?2) "
      "ON CONFLICT(signature_id) DO UPDATE SET state=excluded.state");
  upsert.bind(1, signature).bind(2, state).run();
}

std::optional<std::string> TuningDb::tuner_state(int64_t signature) {
  auto& query = statement("SELECT state FROM tuner_state WHERE signature_id=?1");
  query.bind(1, signature);
  if (!query.step()) return std::nullopt;
  std::string state = query.text(0);
  query.run();
  return state;
}

void TuningDb::put_model(int64_t signature, int64_t last_sample_id, const std::string& state) {
  auto& upsert = statement(
      "INSERT INTO models(signature_id, last_sample_id, state) VALUES (?1, ?2, ?3) "
      "ON CONFLICT(signature_id) DO UPDATE SET last_sample_id=excluded.last_sample_id, "
      "state=excluded.state");
  upsert.bind(1, signature).bind(2, last_sample_id).bind(3, state).run();
}

std::optional<std::pair<int64_t, std::string>> TuningDb::model(int64_t signature) {
  auto& query = statement("SELECT last_sample_id, state FROM models WHERE signature_id=?1");
  query.bind(1, signature);
  if (!query.step()) return std::nullopt;
  std::pair<int64_t, std::string> result{query.integer(0), query.text(1)};
  query.run();
  return result;
}

void TuningDb::export_csv(std::ostream& out, int64_t signature) {
  out << "sample_id,tuning_key,hardware,state_id,indicators,config,cost,failed,extras,time\n";
  auto& query = statement(
      "SELECT s.id, g.tuning_key, g.hardware, s.state_id, st.indicators, c.text, s.cost, "
      "s.failed, (SELECT group_concat(name || '=' || value, ';') FROM sample_extras e WHERE "
      "e.sample_id = s.id), s.time FROM samples s JOIN signatures g ON g.id = s.signature_id "
      "JOIN states st ON st.id = s.state_id JOIN configs c ON c.id = s.config_id "
      "WHERE ?1 = 0 OR s.signature_id = ?1 ORDER BY s.id");
  query.bind(1, signature);
  char number[64];
  while (query.step()) {
    std::string indicators;
    for (double v : TokenReader(query.text(4)).get_doubles()) {
      std::snprintf(number, sizeof number, "%.17g", v);
      if (!indicators.empty()) indicators += ';';
      indicators += number;
    }
    std::snprintf(number, sizeof number, "%.17g", query.real(6));
    out << query.integer(0) << ',' << csv_field(query.text(1)) << ',' << csv_field(query.text(2))
        << ',' << query.integer(3) << ',' << indicators << ',' << csv_field(query.text(5)) << ','
        << (query.integer(7) ? "" : number) << ',' << query.integer(7) << ','
        << csv_field(query.text(8)) << ',';
    std::snprintf(number, sizeof number, "%.3f", query.real(9));
    out << number << '\n';
  }
}

TuningDb::Transaction::Transaction(TuningDb& db) : db_(db) {
  db_.execute("BEGIN IMMEDIATE");
}

TuningDb::Transaction::~Transaction() {
  if (!done_) {
    char* error = nullptr;
    sqlite3_exec(db_.handle_, "ROLLBACK", nullptr, nullptr, &error);
    sqlite3_free(error);
  }
}

void TuningDb::Transaction::commit() {
  db_.execute("COMMIT");
  done_ = true;
}

}  // namespace tuneray::tuner
