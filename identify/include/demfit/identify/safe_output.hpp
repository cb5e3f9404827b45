#pragma once
// Output that can never destroy a user's files. Every command writes through these:
//  - write_file_atomically: a temporary created exclusively (O_EXCL | O_NOFOLLOW) beside the target,
//    written and closed with every error checked (a full disk is an error, not a short file), then
//    renamed over the target. rename() replaces a symbolic link itself, never the file it points to.
//  - OutputFolder rules: an existing folder is only written into (or replaced) when demfit created it
//    (marker file kOutputMarker inside, naming the same kind of command) or it is empty; never the
//    working folder or a parent of it, never a plain file, a link, a path through a link, or a
//    folder whose study store another process holds (StoreLock); a folder replaced as a whole must
//    not hold the command's inputs.
//    A marker without a kind (demfit before kinds, or an empty marker a user added) is accepted by
//    every command when the folder holds no study.db; a folder with a study.db and such a marker
//    is accepted only by identify (to resume it) and by report of that very store.
//  - user strings: control characters are refused (check_user_text) and file names are derived
//    through one slug function (safe_slug); path_inside refuses anything that would leave the folder.
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace demfit::identify {

// Marker file demfit writes into every output folder it creates. Its first line names the kind
// of command that made the folder (output_kind_name); a `report` folder's marker also holds the
// line "study: <absolute path of the study store>" whose results the folder holds.
inline constexpr const char* kOutputMarker = ".demfit-output";

// The commands that write output folders. A folder is only written by the kind that made it
// (`report` may also write into the folder of the very study it reports).
enum class OutputKind { identify, simulate, diagnose, report, reproduce, target };
const char* output_kind_name(OutputKind kind);

// What a command is about to write into an output folder, for the folder rules.
struct OutputRequest {
  OutputRequest(OutputKind k, std::vector<std::filesystem::path> files = {}) : kind(k), inputs(std::move(files)) {}
  OutputKind kind;
  std::vector<std::filesystem::path> inputs;  // files the command reads (never replaced)
  std::string option = "--out";               // the command-line option, named in errors
  std::filesystem::path study_store;          // report: the store whose results are written
  bool lock_held = false;                     // the caller holds the folder's StoreLock itself
};

// Writes `content` to `path` atomically; throws std::runtime_error naming the file on any error.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

// Writes a file the user named outside any output folder (e.g. export --lsdyna): only a regular
// file is ever replaced (never a device, a link, a folder), an existing one only when `overwrite`;
// atomically as write_file_atomically. `option` names the command-line option in errors.
void write_user_file(const std::filesystem::path& path, const std::string& content, bool overwrite,
                     const std::string& option);
// The checks of write_user_file without writing anything.
void check_user_file(const std::filesystem::path& path, bool overwrite, const std::string& option);

// The whole content of an input file, refused up front unless it is a regular file (a device such
// as /dev/zero or a FIFO never ends) and when it is larger than max_bytes; at most max_bytes + 1
// bytes are ever read. `what` names the file in errors ("curve file 'x.csv'").
std::string read_input_file(const std::filesystem::path& path, std::size_t max_bytes, const std::string& what);

// Throws "<field>: contains a control character ..." when text holds a byte < 0x20, 0x7f or a
// Unicode bidirectional control (U+202A..U+202E, U+2066..U+2069): names that reach files, plots
// and report headers are plain text that reads as it is.
void check_user_text(const std::string& field, const std::string& text);

// `text` as it may be echoed in a message or a report: C0 control characters, DEL and the Unicode
// bidirectional controls (U+202A..U+202E, U+2066..U+2069), which can make a name read differently
// from what it is, are written as escapes (\x1B, \u202E); everything else is unchanged.
std::string printable(const std::string& text);
// printable(path) between single quotes: the form every message uses for a path.
std::string quote_path(const std::filesystem::path& path);

// A file-name-safe form of a user string: [A-Za-z0-9._-] kept, everything else '_', no leading
// '.', at most 80 bytes; "" becomes "unnamed". Ordinary names ("pressure_volume") are unchanged.
// A longer name keeps its extension (".csv", up to 8 characters) and gets a hash of the whole text
// before it, so that two long names never share a slug and "x.csv" never becomes "x.png"'s name.
std::string safe_slug(const std::string& text);

// folder / file_name, after checking that file_name is one plain component that stays inside
// the folder (no separator, not "." or "..", no control character).
std::filesystem::path path_inside(const std::filesystem::path& folder, const std::string& file_name);

// Checks that `folder` may receive the output of a command (see the rules above) and creates
// it, marked with the request's kind, if missing. Stale temporaries of dead processes are removed.
void prepare_output_folder(const std::filesystem::path& folder, const OutputRequest& request);

// The checks of prepare_output_folder without creating anything.
void check_output_folder(const std::filesystem::path& folder, const OutputRequest& request);

// Same checks for a folder that the command will replace as a whole (simulate): it must not
// exist, or be an empty folder, or a folder marked by demfit for this kind, and must not hold the
// command's inputs; the folder and everything in it must be writable. Does not create anything.
void check_replaceable_folder(const std::filesystem::path& folder, const OutputRequest& request);

// Writes the marker into a folder demfit has just created (e.g. a staging folder).
void mark_output_folder(const std::filesystem::path& folder, OutputKind kind,
                        const std::filesystem::path& study_store = {});

// Refuses a path with a symbolic link among its existing components ("link/sub"): demfit never
// writes through a link. Throws "<option>: ..." naming the link and the real path to give instead.
void check_no_link_in_path(const std::filesystem::path& path, const std::string& option);

// Removes "<name>.tmp<pid>" files (and .gp scripts) of processes that no longer run; returns the count.
int remove_stale_temporaries(const std::filesystem::path& folder);

}  // namespace demfit::identify
