// SQLite study store. Each evaluation is its own transaction (autocommit), so a kill -9 loses at
// most the runs in flight; WAL + synchronous=NORMAL keeps that durable against a process kill.
#include "demfit/identify/study_store.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <sqlite3.h>

#include "demfit/identify/curve_json.hpp"
#include "demfit/identify/fnv_hash.hpp"
#include "demfit/identify/json_document.hpp"
#include "demfit/identify/model_fingerprint.hpp"

namespace demfit::identify {
namespace {

// JSON has no NaN: a failed run's objective is stored as null.
nlohmann::json number_or_null(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }
double number_from(const nlohmann::json& json) {
  return json.is_number() ? json.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

IterationRecord iteration_from_json(const nlohmann::json& j) {
  IterationRecord r;
  r.iteration = j.at("iteration").get<int>();
  r.region_center = j.at("region_center").get<std::vector<double>>();
  r.region_range = j.at("region_range").get<std::vector<double>>();
  r.predicted_optimum = j.at("predicted_optimum").get<std::vector<double>>();
  r.predicted_parameters = j.at("predicted_parameters").get<ParameterSet>();
  r.predicted_objective = number_from(j.at("predicted_objective"));
  r.best_objective = number_from(j.at("best_objective"));
  r.runs_done = j.at("runs_done").get<int>();
  r.design_change = number_from(j.at("design_change"));
  r.objective_change = number_from(j.at("objective_change"));
  return r;
}

// FNV-1a 64 of a row's stored texts: detects a row edited or damaged after demfit wrote it (an
// accidental edit, a bad copy, a half-written page). It is no signature: whoever can recompute
// it can forge a row, and the store says so in docs/study_format.md.
std::string row_checksum(const std::vector<std::string>& fields) {
  std::uint64_t hash = kFnvOffsetBasis;
  for (const std::string& field : fields)
    hash = fnv1a64("\x1f", fnv1a64(field, hash));  // unit separator: ("ab","c") differs from ("a","bc")
  char text[20];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

// A REAL column as the checksum sees it: the exact double, or "null".
std::string number_text(double value) {
  if (!std::isfinite(value)) return "null";
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string evaluation_checksum(int iteration, int point, const std::string& kind, const std::string& unit_x,
                                const std::string& parameters, const std::string& curves, double objective,
                                double wall_seconds, const std::string& status, const std::string& error) {
  return row_checksum({std::to_string(iteration), std::to_string(point), kind, unit_x, parameters, curves,
                       number_text(objective), number_text(wall_seconds), status, error});
}

std::string column_text(sqlite3_stmt* statement, int column) {
  const unsigned char* text = sqlite3_column_text(statement, column);
  return text ? reinterpret_cast<const char*>(text) : "";
}

class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &statement_, nullptr) != SQLITE_OK)
      throw std::runtime_error(std::string("study store: ") + sqlite3_errmsg(db));
  }
  ~Statement() { sqlite3_finalize(statement_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  sqlite3_stmt* get() { return statement_; }
  void bind(int index, const std::string& text) {
    sqlite3_bind_text(statement_, index, text.c_str(), -1, SQLITE_TRANSIENT);
  }
  void bind(int index, int value) { sqlite3_bind_int(statement_, index, value); }
  void bind(int index, double value) {
    if (std::isfinite(value))
      sqlite3_bind_double(statement_, index, value);
    else
      sqlite3_bind_null(statement_, index);
  }

 private:
  sqlite3_stmt* statement_ = nullptr;
};

sqlite3* open_database(const std::filesystem::path& path, int flags) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.string().c_str(), &db, flags, nullptr) != SQLITE_OK) {
    const std::string message = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close(db);
    throw std::runtime_error("study store '" + path.string() + "' cannot be opened: " + message);
  }
  sqlite3_busy_timeout(db, 10000);
  return db;
}

}  // namespace

// --resume of a changed model is refused, naming the field; an older store without a
// recorded model gets the current one.
void StudyStore::check_same_model(StudyStore& store, const nlohmann::json& resolved_model) {
  if (resolved_model.is_null()) return;
  const auto stored = store.meta("resolved_model");
  if (!stored) {
    store.put_meta("resolved_model", resolved_model.dump());
    return;
  }
  const std::string change = first_difference(nlohmann::json::parse(*stored), resolved_model);
  if (!change.empty())
    throw std::runtime_error("study store '" + store.path_.string() + "': the model changed since the study started (" +
                             change + "); restore the case or use another --out folder");
}

nlohmann::json to_json(const EvaluationRecord& r) {
  return {{"iteration", r.iteration},
          {"point", r.point},
          {"kind", r.kind},
          {"unit_x", r.unit_x},
          {"parameters", r.parameters},
          {"objective", number_or_null(r.objective)},
          {"wall_seconds", r.wall_seconds},
          {"ok", r.ok},
          {"error", r.error}};
}

nlohmann::json to_json(const IterationRecord& r) {
  return {{"iteration", r.iteration},
          {"region_center", r.region_center},
          {"region_range", r.region_range},
          {"predicted_optimum", r.predicted_optimum},
          {"predicted_parameters", r.predicted_parameters},
          {"predicted_objective", number_or_null(r.predicted_objective)},
          {"best_objective", number_or_null(r.best_objective)},
          {"runs_done", r.runs_done},
          {"design_change", number_or_null(r.design_change)},
          {"objective_change", number_or_null(r.objective_change)}};
}

StudyStore::StudyStore(sqlite3* db, std::filesystem::path path) : db_(db), path_(std::move(path)) {}
StudyStore::StudyStore(StudyStore&& other) noexcept { *this = std::move(other); }
StudyStore& StudyStore::operator=(StudyStore&& other) noexcept {
  if (this != &other) {
    if (db_) sqlite3_close(db_);
    db_ = other.db_;
    other.db_ = nullptr;
    path_ = std::move(other.path_);
    evaluations_ = std::move(other.evaluations_);
    iterations_ = std::move(other.iterations_);
  }
  return *this;
}
StudyStore::~StudyStore() {
  if (db_) sqlite3_close(db_);
}

void StudyStore::execute(const std::string& sql) {
  char* message = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string text = message ? message : "unknown error";
    sqlite3_free(message);
    throw std::runtime_error("study store '" + path_.string() + "': " + text);
  }
}

void StudyStore::put_meta(const std::string& key, const std::string& value) {
  Statement s(db_, "INSERT OR REPLACE INTO meta(key, value, checksum) VALUES(?1, ?2, ?3)");
  s.bind(1, key);
  s.bind(2, value);
  s.bind(3, row_checksum({key, value}));
  if (sqlite3_step(s.get()) != SQLITE_DONE)
    throw std::runtime_error(std::string("study store: ") + sqlite3_errmsg(db_));
}

std::optional<std::string> StudyStore::meta(const std::string& key) const {
  if (key == "schema_version") {  // read without a checksum: a store of another version has none
    Statement s(db_, "SELECT value FROM meta WHERE key = ?1");
    s.bind(1, key);
    if (sqlite3_step(s.get()) == SQLITE_ROW) return column_text(s.get(), 0);
    return std::nullopt;
  }
  Statement s(db_, "SELECT value, checksum FROM meta WHERE key = ?1");
  s.bind(1, key);
  if (sqlite3_step(s.get()) != SQLITE_ROW) return std::nullopt;
  std::string value = column_text(s.get(), 0);
  if (column_text(s.get(), 1) != row_checksum({key, value}))
    throw std::runtime_error("study store '" + path_.string() + "': its '" + key +
                             "' entry was changed after demfit wrote it (checksum mismatch); restore study.db from a "
                             "copy or rerun the study into a new --out folder");
  return value;
}

StudyStore StudyStore::open_for_run(const std::filesystem::path& path, const StudySpec& spec, bool resume,
                                    const nlohmann::json& resolved_model) {
  const bool exists = std::filesystem::exists(path);
  if (exists && !resume)
    throw std::runtime_error("study store '" + path.string() +
                             "' already exists; pass --resume to continue it, or choose another --out folder");
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  StudyStore store(open_database(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE), path);
  store.execute("PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;");
  const std::string hash = std::to_string(study_hash(spec));
  if (!exists) {
    store.execute(
        "CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL, checksum TEXT NOT NULL);"
        "CREATE TABLE evaluations(iteration INTEGER NOT NULL, point INTEGER NOT NULL, kind TEXT NOT NULL,"
        " unit_x TEXT NOT NULL, parameters TEXT NOT NULL, curves TEXT NOT NULL, objective REAL,"
        " wall_seconds REAL NOT NULL, status TEXT NOT NULL, error TEXT NOT NULL, checksum TEXT NOT NULL,"
        " PRIMARY KEY(iteration, point));"
        "CREATE TABLE iterations(iteration INTEGER PRIMARY KEY, record TEXT NOT NULL, checksum TEXT NOT NULL);");
    store.execute("BEGIN");
    store.put_meta("schema_version", std::to_string(kStoreSchemaVersion));
    store.put_meta("study_hash", hash);
    store.put_meta("study_json", to_json(spec).dump());
    if (!resolved_model.is_null()) store.put_meta("resolved_model", resolved_model.dump());
    store.execute("COMMIT");
  } else {
    store.load();
    if (store.meta("study_hash").value_or("") != hash)
      throw std::runtime_error("study store '" + path.string() +
                               "' belongs to another study (different variables, targets or settings); "
                               "use another --out folder");
    check_same_model(store, resolved_model);
    // A resumed study may have a new stopping rule; keep the stored spec current.
    store.put_meta("study_json", to_json(spec).dump());
  }
  return store;
}

StudyStore StudyStore::open_existing(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path))
    throw std::runtime_error("study store '" + path.string() + "' does not exist; give the study.db of a run");
  StudyStore store(open_database(path, SQLITE_OPEN_READWRITE), path);
  store.load();
  return store;
}

void StudyStore::load() {
  std::optional<std::string> version;
  try {
    version = meta("schema_version");
  } catch (const std::exception&) { throw std::runtime_error("'" + path_.string() + "' is not a demfit study store"); }
  if (!version || *version != std::to_string(kStoreSchemaVersion))
    throw std::runtime_error("study store '" + path_.string() + "' has schema version " + version.value_or("?") +
                             ", this demfit reads version " + std::to_string(kStoreSchemaVersion) +
                             "; rerun the study with this version");
  Statement s(db_,
              "SELECT iteration, point, kind, unit_x, parameters, curves, objective, wall_seconds, status, error, "
              "checksum FROM evaluations ORDER BY iteration, point");
  while (sqlite3_step(s.get()) == SQLITE_ROW) {
    EvaluationRecord r;
    r.iteration = sqlite3_column_int(s.get(), 0);
    r.point = sqlite3_column_int(s.get(), 1);
    r.kind = column_text(s.get(), 2);
    const double objective = sqlite3_column_type(s.get(), 6) == SQLITE_NULL ? std::numeric_limits<double>::quiet_NaN()
                                                                            : sqlite3_column_double(s.get(), 6);
    const std::string expected = evaluation_checksum(r.iteration, r.point, r.kind, column_text(s.get(), 3),
                                                     column_text(s.get(), 4), column_text(s.get(), 5), objective,
                                                     sqlite3_column_double(s.get(), 7), column_text(s.get(), 8),
                                                     column_text(s.get(), 9));
    if (column_text(s.get(), 10) != expected)
      throw std::runtime_error("study store '" + path_.string() + "': run " + std::to_string(r.iteration) + "/" +
                               std::to_string(r.point) +
                               " is corrupted or was changed after demfit wrote it (checksum mismatch); restore "
                               "study.db from a copy or rerun the study into a new --out folder");
    try {
      r.unit_x = nlohmann::json::parse(column_text(s.get(), 3)).get<std::vector<double>>();
      r.parameters = nlohmann::json::parse(column_text(s.get(), 4)).get<ParameterSet>();
      r.curves = curves_from_json(nlohmann::json::parse(column_text(s.get(), 5)));
    } catch (const nlohmann::json::exception&) {
      // A damaged row names the store and the run instead of a bare JSON error.
      throw std::runtime_error("study store '" + path_.string() + "': run " + std::to_string(r.iteration) + "/" +
                               std::to_string(r.point) +
                               " is corrupted (unreadable parameters or curves); "
                               "restore study.db from a copy or rerun into a new --out folder");
    }
    r.objective = sqlite3_column_type(s.get(), 6) == SQLITE_NULL ? std::numeric_limits<double>::quiet_NaN()
                                                                 : sqlite3_column_double(s.get(), 6);
    r.wall_seconds = sqlite3_column_double(s.get(), 7);
    r.ok = column_text(s.get(), 8) == "ok";
    r.error = column_text(s.get(), 9);
    evaluations_[{r.iteration, r.point}] = std::move(r);
  }
  Statement it(db_, "SELECT iteration, record, checksum FROM iterations ORDER BY iteration");
  while (sqlite3_step(it.get()) == SQLITE_ROW) {
    IterationRecord r;
    if (column_text(it.get(), 2) != row_checksum({std::to_string(sqlite3_column_int(it.get(), 0)),
                                                  column_text(it.get(), 1)}))
      throw std::runtime_error("study store '" + path_.string() + "': iteration record " +
                               std::to_string(sqlite3_column_int(it.get(), 0)) +
                               " was changed after demfit wrote it (checksum mismatch); restore study.db from a copy "
                               "or rerun the study into a new --out folder");
    try {
      r = iteration_from_json(nlohmann::json::parse(column_text(it.get(), 1)));
    } catch (const nlohmann::json::exception&) {
      throw std::runtime_error("study store '" + path_.string() + "': iteration record " +
                               std::to_string(iterations_.size()) + " is corrupted; restore study.db from a copy");
    }
    iterations_[r.iteration] = r;
  }
}

std::optional<nlohmann::json> StudyStore::resolved_model() const {
  const auto text = meta("resolved_model");
  if (!text) return std::nullopt;
  return parse_json_document(*text, "study store '" + path_.string() + "' (resolved model)");
}

nlohmann::json StudyStore::study_json() const {
  // A received study.db is input like any other: limits and duplicate keys checked.
  return parse_json_document(meta("study_json").value_or("{}"), "study store '" + path_.string() + "' (study)");
}

void StudyStore::add_evaluation(const EvaluationRecord& r) {
  Statement s(db_,
              "INSERT OR REPLACE INTO evaluations(iteration, point, kind, unit_x, parameters, curves, objective,"
              " wall_seconds, status, error, checksum) VALUES(?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)");
  const std::string unit_x = nlohmann::json(r.unit_x).dump();
  const std::string parameters = nlohmann::json(r.parameters).dump();
  const std::string curves = curves_to_json(r.curves).dump();
  const std::string status = r.ok ? "ok" : "failed";
  s.bind(1, r.iteration);
  s.bind(2, r.point);
  s.bind(3, r.kind);
  s.bind(4, unit_x);
  s.bind(5, parameters);
  s.bind(6, curves);
  s.bind(7, r.objective);
  s.bind(8, r.wall_seconds);
  s.bind(9, status);
  s.bind(10, r.error);
  s.bind(11, evaluation_checksum(r.iteration, r.point, r.kind, unit_x, parameters, curves, r.objective,
                                 r.wall_seconds, status, r.error));
  if (sqlite3_step(s.get()) != SQLITE_DONE)
    throw std::runtime_error("study store '" + path_.string() + "': " + sqlite3_errmsg(db_));
  evaluations_[{r.iteration, r.point}] = r;
}

const EvaluationRecord* StudyStore::find_evaluation(int iteration, int point) const {
  const auto found = evaluations_.find({iteration, point});
  return found == evaluations_.end() ? nullptr : &found->second;
}

std::vector<EvaluationRecord> StudyStore::evaluations() const {
  std::vector<EvaluationRecord> out;
  for (const auto& [key, record] : evaluations_)
    if (key.first >= 0) out.push_back(record);
  return out;
}

std::vector<EvaluationRecord> StudyStore::cheap_evaluations() const {
  std::vector<EvaluationRecord> out;
  for (const auto& [key, record] : evaluations_)
    if (key.first == kCheapLevelIteration) out.push_back(record);
  return out;
}

void StudyStore::put_iteration(const IterationRecord& r) {
  Statement s(db_, "INSERT OR REPLACE INTO iterations(iteration, record, checksum) VALUES(?1, ?2, ?3)");
  const std::string record = to_json(r).dump();
  s.bind(1, r.iteration);
  s.bind(2, record);
  s.bind(3, row_checksum({std::to_string(r.iteration), record}));
  if (sqlite3_step(s.get()) != SQLITE_DONE)
    throw std::runtime_error("study store '" + path_.string() + "': " + sqlite3_errmsg(db_));
  iterations_[r.iteration] = r;
}

std::vector<IterationRecord> StudyStore::iterations() const {
  std::vector<IterationRecord> out;
  for (const auto& [key, record] : iterations_) out.push_back(record);
  return out;
}

void StudyStore::put_result(const nlohmann::json& result) { put_meta("result_json", result.dump()); }

std::optional<nlohmann::json> StudyStore::result() const {
  const auto text = meta("result_json");
  if (!text) return std::nullopt;
  return nlohmann::json::parse(*text);
}

}  // namespace demfit::identify
