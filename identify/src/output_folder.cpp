// The output-folder rules of every command (see safe_output.hpp): which existing folder a command
// may write into or replace, the marker naming the kind of command that made a folder, the store
// lock of a running study, and paths that would lead through a symbolic link.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "demfit/identify/safe_output.hpp"

namespace demfit::identify {
namespace fs = std::filesystem;

namespace {

constexpr OutputKind kAllKinds[] = {OutputKind::identify, OutputKind::simulate,  OutputKind::diagnose,
                                    OutputKind::report,   OutputKind::reproduce, OutputKind::target};

// Absolute, with symbolic links of the existing part resolved, so "." and "a/.." compare equal.
fs::path resolved(const fs::path& path) {
  std::error_code error;
  fs::path out = fs::weakly_canonical(fs::absolute(path, error), error);
  return error ? fs::absolute(path).lexically_normal() : out;
}

// True when `inner` is `outer` or lies below it.
bool is_within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;  // trailing separator
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

bool folder_is_empty(const fs::path& folder) {
  std::error_code error;
  return fs::directory_iterator(folder, error) == fs::directory_iterator() && !error;
}

// What a folder's marker says. `present`: a marker file exists (a link or a folder there counts
// as no marker). `kind` empty: a marker of demfit before kinds, or one a user added.
struct Marker {
  bool present = false;
  std::optional<OutputKind> kind;
  std::string study;  // report: the store whose results the folder holds
};

Marker read_marker(const fs::path& folder) {
  Marker marker;
  std::error_code error;
  if (!fs::is_regular_file(fs::symlink_status(folder / kOutputMarker, error))) return marker;
  marker.present = true;
  std::string text;
  try {
    text = read_input_file(folder / kOutputMarker, 4096, "marker");
  } catch (const std::exception&) {
    return marker;  // unreadable or oversized: a marker without a kind
  }
  const std::string first = text.substr(0, text.find('\n'));
  for (OutputKind kind : kAllKinds)
    if (first == output_kind_name(kind)) marker.kind = kind;
  // The markers of demfit before kinds said "created by demfit (demfit simulate)" for simulate.
  if (!marker.kind && text.find("(demfit simulate)") != std::string::npos) marker.kind = OutputKind::simulate;
  const auto at = text.find("\nstudy: ");
  if (at != std::string::npos) {
    const auto end = text.find('\n', at + 1);
    marker.study = text.substr(at + 8, end == std::string::npos ? std::string::npos : end - at - 8);
  }
  return marker;
}

// True when another process holds the folder's study store lock (StoreLock: flock on .demfit-lock).
// The lock file is opened, never created: a folder without one holds no running study.
bool store_locked(const fs::path& folder) {
  const int fd = ::open((folder / ".demfit-lock").c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return false;
  const bool locked = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);  // releases the shared lock just taken, if any
  return locked;
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code error;
  return fs::equivalent(a, b, error) && !error;
}

std::string command_name(OutputKind kind) { return std::string("demfit ") + output_kind_name(kind); }

// The rules on a marked or user folder that exists: the kind of its marker, its study store.
void check_owner(const fs::path& folder, const OutputRequest& request, const std::string& shown) {
  const Marker marker = read_marker(folder);
  const std::string& option = request.option;
  if (!marker.present) {
    if (folder_is_empty(folder)) return;
    throw std::runtime_error(option + ": " + shown + " exists and was not created by demfit (no " + kOutputMarker +
                             " inside); choose a new folder, or add an empty " + kOutputMarker +
                             " file to let demfit replace its content");
  }
  std::error_code error;
  const fs::path db = folder / "study.db";
  const bool has_store = fs::exists(fs::symlink_status(db, error));
  const bool reporting = request.kind == OutputKind::report;
  const bool own_store = reporting && has_store && same_file(db, request.study_store);
  if (reporting && has_store && !own_store)
    throw std::runtime_error(option + ": " + shown + " holds another study's store (study.db) and results; " +
                             command_name(request.kind) + " would overwrite them: give a new folder");
  if (marker.kind && *marker.kind != request.kind && !(own_store && *marker.kind == OutputKind::identify))
    throw std::runtime_error(option + ": " + shown + " holds the output of '" + command_name(*marker.kind) + "' (" +
                             kOutputMarker + "); '" + command_name(request.kind) +
                             "' never writes over another command's results: give a new folder");
  if (marker.kind && reporting && *marker.kind == OutputKind::report && !marker.study.empty() &&
      !same_file(marker.study, request.study_store))
    throw std::runtime_error(option + ": " + shown + " holds the report of another study (" + quote_path(marker.study) +
                             "): give a new folder");
  if (!marker.kind && has_store && request.kind != OutputKind::identify && !own_store)
    throw std::runtime_error(option + ": " + shown + " holds a study (study.db) and its " + kOutputMarker +
                             " does not name the command that made it; '" + command_name(request.kind) +
                             "' will not write over it: give a new folder");
}

// The rules every output folder obeys; returns true when the folder exists (and is allowed).
bool check_folder(const fs::path& folder, const OutputRequest& request, bool replace) {
  const std::string& option = request.option;
  if (folder.empty()) throw std::runtime_error(option + ": empty folder name; give a new folder, e.g. results/run1");
  check_user_text(option, folder.string());
  const fs::path target = resolved(folder);
  const fs::path cwd = resolved(fs::current_path());
  const std::string shown = quote_path(folder);
  if (target == cwd)
    throw std::runtime_error(option + ": " + shown +
                             " is the working folder; demfit writes into a folder of its own, "
                             "give a new name such as results/run1");
  if (is_within(cwd, target))
    throw std::runtime_error(option + ": " + shown + " is a parent of the working folder; give a new folder name");
  std::error_code error;
  const fs::file_status status = fs::symlink_status(folder, error);
  if (fs::is_symlink(status))
    throw std::runtime_error(option + ": " + shown +
                             " is a symbolic link; give a real folder (demfit does not write through links)");
  check_no_link_in_path(folder, option);
  if (!fs::exists(status)) return false;
  if (!fs::is_directory(status))
    throw std::runtime_error(option + ": " + shown + " is an existing file, not a folder; choose another name");
  if (replace) {
    for (const fs::path& input : request.inputs)
      if (!input.empty() && is_within(resolved(input), target))
        throw std::runtime_error(option + ": " + shown + " holds the input " + quote_path(input) +
                                 "; demfit would overwrite it: give a new output folder");
  }
  if (!request.lock_held && store_locked(folder))
    throw std::runtime_error(option + ": " + shown + " is in use by another demfit process (its study store " +
                             quote_path(folder / "study.db") +
                             " is locked); wait for it to finish or give another folder");
  check_owner(folder, request, shown);
  return true;
}

// A folder replaced as a whole is removed file by file: every folder in it must be writable, or
// the replacement would fail after the work is done.
void check_removable(const fs::path& folder, const std::string& option) {
  std::error_code error;
  for (auto it = fs::recursive_directory_iterator(folder, error); !error && it != fs::recursive_directory_iterator();
       it.increment(error)) {
    if (it->is_directory(error) && !it->is_symlink(error) && ::access(it->path().c_str(), W_OK | X_OK) != 0)
      throw std::runtime_error(option + ": " + quote_path(it->path()) + " cannot be changed (" + std::strerror(errno) +
                               "); demfit could not replace " + quote_path(folder) + ": give another folder");
  }
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw std::runtime_error(option + ": " + quote_path(folder) + " cannot be changed (" + std::strerror(errno) +
                             "); give another folder");
}

}  // namespace

const char* output_kind_name(OutputKind kind) {
  switch (kind) {
    case OutputKind::identify:
      return "identify";
    case OutputKind::simulate:
      return "simulate";
    case OutputKind::diagnose:
      return "diagnose";
    case OutputKind::report:
      return "report";
    case OutputKind::reproduce:
      return "reproduce";
    case OutputKind::target:
      return "target";
  }
  return "?";
}

void check_no_link_in_path(const fs::path& path, const std::string& option) {
  fs::path walked;
  for (const fs::path& part : path) {
    walked /= part;
    if (part.empty() || part == "/" || part == "." || part == "..") continue;
    std::error_code error;
    const fs::file_status status = fs::symlink_status(walked, error);
    if (!fs::exists(status)) return;  // the rest is to be created
    if (fs::is_symlink(status))
      throw std::runtime_error(option + ": " + quote_path(walked) + " in " + quote_path(path) +
                               " is a symbolic link; demfit does not write through links: give the real path " +
                               quote_path(resolved(path)));
  }
}

void prepare_output_folder(const fs::path& folder, const OutputRequest& request) {
  const bool exists = check_folder(folder, request, /*replace=*/false);
  if (!exists) {
    std::error_code error;
    fs::create_directories(folder, error);
    if (error)
      throw std::runtime_error(request.option + ": cannot create " + quote_path(folder) + " (" + error.message() +
                               "); check that its parent exists and is writable");
  }
  if (!read_marker(folder).kind) {  // new, or a marker without a kind: name the command now
    std::error_code error;
    const bool has_store = fs::exists(fs::symlink_status(folder / "study.db", error));
    // A study folder is identify's even when report (of that study) is the one marking it.
    mark_output_folder(folder, has_store ? OutputKind::identify : request.kind,
                       has_store ? fs::path() : request.study_store);
  }
  remove_stale_temporaries(folder);
}

void check_output_folder(const fs::path& folder, const OutputRequest& request) {
  check_folder(folder, request, /*replace=*/false);
}

void check_replaceable_folder(const fs::path& folder, const OutputRequest& request) {
  if (check_folder(folder, request, /*replace=*/true)) check_removable(folder, request.option);
}

void mark_output_folder(const fs::path& folder, OutputKind kind, const fs::path& study_store) {
  std::string text = output_kind_name(kind);
  text += "\nThis folder was created by 'demfit ";
  text += output_kind_name(kind);
  text += "' (first line: the command). demfit may replace it or the files in it on a later run of that command.\n";
  if (!study_store.empty()) text += "study: " + resolved(study_store).string() + "\n";
  write_file_atomically(folder / kOutputMarker, text);
}

}  // namespace demfit::identify
