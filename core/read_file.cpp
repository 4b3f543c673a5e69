#include "core/read_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "core/error.h"

namespace dp::core {

void check_readable_file(const std::string& path, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec) throw IoError("cannot open " + what + ": " + ec.message(), path);
  if (fs::is_directory(st)) throw IoError("cannot open " + what + ": is a directory", path);
  if (!std::ifstream(path, std::ios::binary)) throw IoError("cannot open " + what, path);
}

std::string read_file(const std::string& path, const std::string& what) {
  check_readable_file(path, what);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad() || ss.bad()) throw IoError("cannot read " + what, path);
  return ss.str();
}

}  // namespace dp::core
