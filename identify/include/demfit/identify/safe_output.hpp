#pragma once
// Output that can never destroy a user's files (issue #13). Every command writes through these:
//  - write_file_atomically: a temporary created exclusively (O_EXCL | O_NOFOLLOW) beside the target,
//    written and closed with every error checked (a full disk is an error, not a short file), then
//    renamed over the target. rename() replaces a symbolic link itself, never the file it points to.
//  - OutputFolder rules: an existing folder is only written into (or replaced) when demfit created it
//    (marker file kOutputMarker inside) or it is empty; never the working folder or a parent of it,
//    never a plain file or a link; a folder replaced as a whole must not hold the command's inputs.
//  - user strings: control characters are refused (check_user_text) and file names are derived
//    through one slug function (safe_slug); path_inside refuses anything that would leave the folder.
#include <filesystem>
#include <string>
#include <vector>

namespace demfit::identify {

// Marker file demfit writes into every output folder it creates.
inline constexpr const char* kOutputMarker = ".demfit-output";

// Writes `content` to `path` atomically; throws std::runtime_error naming the file on any error.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

// Throws "<field>: contains a control character ..." when text holds a byte < 0x20 or 0x7f.
void check_user_text(const std::string& field, const std::string& text);

// A file-name-safe form of a user string: [A-Za-z0-9._-] kept, everything else '_', no leading
// '.', at most 80 bytes; "" becomes "unnamed". Ordinary names ("pressure_volume") are unchanged.
std::string safe_slug(const std::string& text);

// folder / file_name, after checking that file_name is one plain component that stays inside
// the folder (no separator, not "." or "..", no control character).
std::filesystem::path path_inside(const std::filesystem::path& folder, const std::string& file_name);

// Checks that `folder` may receive the output of a command (see the rules above) and creates
// it, marked, if missing. `option` names the command-line option in errors ("--out").
// `inputs` are the files the command reads. Stale temporaries of dead processes are removed.
void prepare_output_folder(const std::filesystem::path& folder, const std::vector<std::filesystem::path>& inputs,
                           const std::string& option);

// The checks of prepare_output_folder without creating anything.
void check_output_folder(const std::filesystem::path& folder, const std::vector<std::filesystem::path>& inputs,
                         const std::string& option);

// Same checks for a folder that the command will replace as a whole (simulate): it must not
// exist, or be an empty folder, or a folder marked by demfit. Does not create anything.
void check_replaceable_folder(const std::filesystem::path& folder, const std::vector<std::filesystem::path>& inputs,
                              const std::string& option);

// Writes the marker into a folder demfit has just created (e.g. a staging folder).
void mark_output_folder(const std::filesystem::path& folder, const std::string& command);

// Removes "<name>.tmp<pid>" files (and .gp scripts) of processes that no longer run; returns the count.
int remove_stale_temporaries(const std::filesystem::path& folder);

}  // namespace demfit::identify
