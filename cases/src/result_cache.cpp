// On-disk cache of whole case results (see result_cache.hpp).
#include "demfit/cases/result_cache.hpp"

#include <fstream>

#include "demfit/cases/fill_cache.hpp"
#include "demfit/identify/curve_json.hpp"
#include "demfit/identify/safe_output.hpp"

namespace demfit::cases {
namespace {

using nlohmann::json;

json to_json(const CaseResult& r) {
  json tables = json::object();
  for (const auto& [name, t] : r.tables)
    tables[name] = {{"comments", t.comments}, {"columns", t.columns}, {"values", t.values}};
  return {{"curves", identify::curves_to_json(r.curves)}, {"tables", tables}, {"summary", r.summary}};
}

CaseResult from_json(const json& j) {
  CaseResult r;
  r.curves = identify::curves_from_json(j.at("curves"));
  for (const auto& [name, t] : j.at("tables").items()) {
    r.tables[name] = CurveTable{t.at("comments"), t.at("columns"), t.at("values")};
  }
  r.summary = j.at("summary").get<std::vector<std::pair<std::string, std::string>>>();
  return r;
}

}  // namespace

CaseResult cached_case_result(const CaseSpec& spec, const CaseRunOptions& options, bool* computed) {
  CaseRunOptions resolved = options;
  if (resolved.cache_dir.empty()) resolved.cache_dir = default_cache_dir();
  // to_key_json: effect settings at their "off" values are left out, so results cached before
  // the effects existed stay valid.
  const json key = {{"result_format", 1}, {"case", cases::to_key_json(spec)}};
  std::filesystem::path path = fill_cache_path(resolved.cache_dir, "result", key);
  path.replace_extension(".json");
  if (computed) *computed = false;
  {
    std::ifstream in(path);
    if (in) {
      try {
        const json stored = json::parse(in);
        if (stored.at("key") == key) return from_json(stored.at("result"));
      } catch (const std::exception&) {
        // unreadable or stale entry: recompute below
      }
    }
  }
  CaseResult result = run_case(spec, {}, resolved);
  identify::write_file_atomically(path, json{{"key", key}, {"result", to_json(result)}}.dump());
  if (computed) *computed = true;
  return result;
}

}  // namespace demfit::cases
