// Whole-file reads for the loaders, with one-line IoErrors naming the file: "is a
// directory" instead of a stream's "basic_filebuf::underflow", the system's reason
// ("File name too long", "No such file or directory") instead of a std::filesystem
// exception that echoes the path in full.
#pragma once

#include <string>

namespace dp::core {

// Throws IoError(`what` + ": " + reason, path) unless `path` names a regular file that
// can be opened for reading. For readers that open the file themselves.
void check_readable_file(const std::string& path, const std::string& what);

// The file's bytes; IoErrors as check_readable_file, and on a failed read.
std::string read_file(const std::string& path, const std::string& what);

}  // namespace dp::core
