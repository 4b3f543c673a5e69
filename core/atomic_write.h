// Writing a file so that a killed process never leaves it truncated: the contents go to
// "<path>.tmp-<pid>" in the same folder, which is renamed over `path` only once complete
// (rename(2) within one filesystem is atomic: readers see the old file or the new one).
// While a temporary file is being written its name is registered, so a signal handler
// that is about to _exit can unlink it (remove_pending_temp_files is async-signal-safe).
// No fsync: this protects against a killed process, not against a power failure.
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace dp::core {

// "<path>.tmp-<pid>": the temporary name write_atomically uses for `path`.
std::string temp_path(const std::string& path);

// Calls write(temporary_path), then renames the temporary file to `path`. If `write`
// throws or the rename fails, the temporary file is removed (and the error rethrown as
// is, or as dp::IoError naming `path`); an existing `path` is then left untouched.
void write_atomically(const std::string& path, const std::function<void(const std::string& tmp)>& write);

// write_atomically for a text or binary blob.
void write_file_atomically(const std::string& path, std::string_view contents);

// Unlinks every temporary file currently being written by write_atomically. Only
// async-signal-safe calls (unlink); meant for a signal handler that then calls _exit.
void remove_pending_temp_files() noexcept;

}  // namespace dp::core
