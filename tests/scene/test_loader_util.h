// Temporary folder for loader tests: files written into it are removed with it.
#pragma once

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    m_dir = std::filesystem::temp_directory_path() / ("dp_loader_test_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(m_dir);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(m_dir, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string path(const std::string& name) const { return (m_dir / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream out(m_dir / name, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    return path(name);
  }

 private:
  std::filesystem::path m_dir;
};
